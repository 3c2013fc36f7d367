//! Re-running a recorded PyTorch update: how anyone checks our numbers against PyTorch.
//!
//! The input has the schema of `ppo_update_pytorch.json` (made by `ppo_fixtures.py`):
//!
//! ```text
//! {"cases": [{"hyper": {"actor_lr", "critic_lr", "gamma", "lmbda", "epochs", "eps", "hidden_dim"},
//!             "weights_before": {"actor.fc1.weight": (H, 4), ..., "critic.fc2.bias": (1)},
//!             "batch": {"states": (N, 4), "actions": (N), "rewards": (N),
//!                       "next_states": (N, 4), "dones": (N)}}, ...]}
//! ```
//!
//! Each case runs [`Agent::update`] from `weights_before` on `batch` with fresh Adam state,
//! and [`ReplayOutput`] holds what the fixture's `expected` and `weights_after` hold, with
//! the same key names and shapes (column tensors as `(N, 1)` lists of one-element lists).
//!
//! A PPO-Penalty case (`ppo_penalty_update_pytorch.json`, made by `ppo_fixtures.py
//! --objective penalty`) says `"objective": "penalty"` and adds `beta` (β₀) and `kl_target`
//! (δ, our `kl_delta`) to `hyper`; its update starts from the β the recording had reached,
//! `expected.beta_before`. Its epochs hold `ratio`, `kl` (per row), `actor_loss` and
//! `critic_loss` (no `surr1`, `surr2`), and the output adds `beta_before`, `kl_after` and
//! `beta_after`, as the fixture does.
//!
//! The continuous agent's fixture (`ppo_continuous_update_pytorch.json`, the book's
//! `PPOContinuous` on Pendulum) has the same layout with a Gaussian actor
//! (`actor.fc_mu`, `actor.fc_std`); each agent's `OnPolicyAgent::replays` tells the two
//! apart by those keys (the course's `run::replay_any` asks every agent) and [`continuous::replay`](crate::ppo::continuous::replay) runs it.

use crate::i18n::t;
use serde::Serialize;
use serde_json::{Map, Value};

use super::checkpoint::parameter_shapes;
use super::{Agent, Objective, PpoConfig, Transitions};
use crate::ppo::PpoError;
use crate::ppo::model::NamedWeights;
use crate::ppo::replay_file::{Reader, batch_expected, hyper_expected, nested};

/// One case to replay.
#[derive(Debug, Clone)]
pub struct ReplayCase {
    /// The hyper-parameters from `hyper` (the rest of the config is the seed's default).
    pub config: PpoConfig,
    /// `weights_before`.
    pub weights_before: NamedWeights,
    /// `batch`.
    pub batch: Transitions,
    /// PPO-Penalty: β when the recorded update started (`expected.beta_before`, else
    /// `hyper.beta`); `None` for the clip.
    pub beta_before: Option<f64>,
}

/// One replayed case, in the fixture's key names and shapes.
#[derive(Debug, Clone, Serialize)]
pub struct ReplayOutput {
    /// `(N, 1)`.
    pub td_target: Vec<[f32; 1]>,
    /// `(N, 1)`.
    pub td_delta: Vec<[f32; 1]>,
    /// `(N, 1)`.
    pub advantage: Vec<[f32; 1]>,
    /// `(N, 1)`.
    pub old_log_probs: Vec<[f32; 1]>,
    /// One per epoch.
    pub epochs: Vec<ReplayEpoch>,
    /// PPO-Penalty: β during the update.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub beta_before: Option<f64>,
    /// PPO-Penalty: the mean KL under the updated actor.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub kl_after: Option<f32>,
    /// PPO-Penalty: β for the next update.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub beta_after: Option<f64>,
    /// Every parameter after the update, nested lists in PyTorch's layout.
    pub weights_after: Map<String, Value>,
}

/// One epoch of a replayed case.
#[derive(Debug, Clone, Serialize)]
pub struct ReplayEpoch {
    /// `(N, 1)`.
    pub ratio: Vec<[f32; 1]>,
    /// `(N, 1)`; the clip only.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub surr1: Option<Vec<[f32; 1]>>,
    /// `(N, 1)`; the clip only.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub surr2: Option<Vec<[f32; 1]>>,
    /// `(N, 1)`, the exact KL(π_old ‖ π) of each row; PPO-Penalty only.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub kl: Option<Vec<[f32; 1]>>,
    /// Scalar.
    pub actor_loss: f32,
    /// Scalar.
    pub critic_loss: f32,
}

/// Parses a replay file's text; `file` names it in errors.
///
/// # Errors
/// [`PpoError::File`] for text that is not JSON; [`PpoError::MissingKey`] /
/// [`PpoError::WrongShape`] naming the key path (like `cases[0].batch.states`) and the
/// expected shape.
pub fn parse_replay(text: &str, file: &str) -> Result<Vec<ReplayCase>, PpoError> {
    let r = Reader { file };
    r.cases(text, |case, path| r.case(case, path))
}

/// Runs one case: the update from `weights_before` with fresh Adam state.
///
/// # Errors
/// [`PpoError::NonFinite`] when the update produces NaN; shape errors cannot happen after
/// [`parse_replay`].
pub fn replay_case(case: &ReplayCase) -> Result<ReplayOutput, PpoError> {
    let mut agent = Agent::from_weights(&case.config, &case.weights_before, 0, "weights_before")?;
    if let Some(beta) = case.beta_before {
        agent.set_beta(beta)?;
    }
    let trace = agent.update(&case.batch)?;
    let penalty = case.config.objective == Objective::Penalty;
    let col = |v: &[f32]| v.iter().map(|&x| [x]).collect::<Vec<_>>();
    let mut weights_after = Map::new();
    for (name, w) in agent.weights()? {
        weights_after.insert(name, nested(&w));
    }
    Ok(ReplayOutput {
        td_target: col(&trace.td_target),
        td_delta: col(&trace.td_delta),
        advantage: col(&trace.advantage),
        old_log_probs: col(&trace.old_log_probs),
        epochs: trace
            .epochs
            .iter()
            .map(|e| ReplayEpoch {
                ratio: col(&e.ratio),
                surr1: (!penalty).then(|| col(&e.surr1)),
                surr2: (!penalty).then(|| col(&e.surr2)),
                kl: penalty.then(|| col(&e.kl)),
                actor_loss: e.actor_loss,
                critic_loss: e.critic_loss,
            })
            .collect(),
        beta_before: trace.penalty.map(|p| p.beta_before),
        kl_after: trace.penalty.map(|p| p.kl_after),
        beta_after: trace.penalty.map(|p| p.beta_after),
        weights_after,
    })
}

impl Reader<'_> {
    fn case(&self, case: &Value, path: &str) -> Result<ReplayCase, PpoError> {
        let objective = match case.get("objective") {
            None => Objective::Clip,
            Some(v) => match serde_json::from_value(v.clone()) {
                Ok(o @ (Objective::Clip | Objective::Penalty)) => o,
                // No PyTorch recording of the KL line search exists to replay.
                _ => {
                    return Err(self.wrong(
                        &format!("{path}.objective"),
                        "\"clip\" or \"penalty\" (the objectives ppo_fixtures.py records)",
                        v,
                    ));
                }
            },
        };
        let hpath = format!("{path}.hyper");
        let hyper = self.key(case, path, "hyper", hyper_expected())?;
        let mut config = self.hyper(hyper, &hpath)?;
        let mut beta_before = None;
        if objective == Objective::Penalty {
            let num = |key: &str| -> Result<f64, PpoError> {
                let expected = t("a number > 0 (PPO-Penalty)", "大于 0 的数（PPO-惩罚）");
                self.number(
                    self.key(hyper, &hpath, key, expected)?,
                    &format!("{hpath}.{key}"),
                    expected,
                )
            };
            config = PpoConfig {
                objective,
                beta_init: num("beta")?,
                kl_delta: num("kl_target")?,
                ..config
            };
            config.validate()?;
            let recorded = case.get("expected").and_then(|e| e.get("beta_before"));
            beta_before = Some(match recorded {
                Some(v) => self.number(
                    v,
                    &format!("{path}.expected.beta_before"),
                    t("a number > 0", "大于 0 的数"),
                )?,
                None => config.beta_init,
            });
        }
        let wpath = format!("{path}.weights_before");
        let weights = self.key(
            case,
            path,
            "weights_before",
            t(
                "the eight actor./critic. tensors",
                "actor./critic. 的八个张量",
            ),
        )?;
        let weights_before = self.weights(weights, &wpath, config.hidden_dim)?;
        let batch = self.batch(
            self.key(case, path, "batch", batch_expected())?,
            &format!("{path}.batch"),
        )?;
        Ok(ReplayCase {
            config,
            weights_before,
            batch,
            beta_before,
        })
    }

    fn hyper(&self, h: &Value, path: &str) -> Result<PpoConfig, PpoError> {
        let num = |key: &str, expected: &str| -> Result<f64, PpoError> {
            self.number(
                self.key(h, path, key, expected)?,
                &format!("{path}.{key}"),
                expected,
            )
        };
        let count = |key: &str| -> Result<usize, PpoError> {
            let expected = t("a positive integer", "正整数");
            let v = self.key(h, path, key, expected)?;
            v.as_u64()
                .and_then(|n| usize::try_from(n).ok())
                .ok_or_else(|| self.wrong(&format!("{path}.{key}"), expected, v))
        };
        let config = PpoConfig {
            actor_lr: num("actor_lr", t("a number > 0", "大于 0 的数"))?,
            critic_lr: num("critic_lr", t("a number > 0", "大于 0 的数"))?,
            gamma: num("gamma", t("a number in (0, 1]", "(0, 1] 内的数"))?,
            lmbda: num("lmbda", t("a number in [0, 1]", "[0, 1] 内的数"))?,
            eps: num("eps", t("a number in (0, 1)", "(0, 1) 内的数"))?,
            epochs: count("epochs")?,
            hidden_dim: count("hidden_dim")?,
            ..PpoConfig::default()
        };
        config.validate()?;
        Ok(config)
    }

    fn weights(&self, w: &Value, path: &str, hidden_dim: usize) -> Result<NamedWeights, PpoError> {
        self.named_tensors(w, path, parameter_shapes(hidden_dim))
    }

    fn batch(&self, b: &Value, path: &str) -> Result<Transitions, PpoError> {
        let column = |key: &str, expected: &str| -> Result<&Vec<Value>, PpoError> {
            self.array(
                self.key(b, path, key, expected)?,
                &format!("{path}.{key}"),
                expected,
            )
        };
        let actions_v = column(
            "actions",
            t("a list of N actions (0 or 1)", "N 个动作（0 或 1）的列表"),
        )?;
        let n = actions_v.len();
        let rows = |key: &str| -> Result<Vec<[f32; 4]>, PpoError> {
            let expected = crate::tr!(
                "a list of shape [{n}, 4] (one observation per action)",
                "形状 [{n}, 4] 的列表，每个动作一个观测"
            );
            let list = column(key, &expected)?;
            if list.len() != n {
                return Err(self.wrong(
                    &format!("{path}.{key}"),
                    &expected,
                    &Value::Array(list.clone()),
                ));
            }
            list.iter()
                .enumerate()
                .map(|(t, row)| {
                    let v = self.floats(row, &format!("{path}.{key}[{t}]"), Some(4), &expected)?;
                    Ok([v[0], v[1], v[2], v[3]])
                })
                .collect()
        };
        let states = rows("states")?;
        let next_states = rows("next_states")?;
        let expected = crate::tr!(
            "a list of {n} numbers (one per action)",
            "{n} 个数的列表，每个动作一个"
        );
        let rewards = self.floats(
            self.key(b, path, "rewards", &expected)?,
            &format!("{path}.rewards"),
            Some(n),
            &expected,
        )?;
        let dones_expected = crate::tr!(
            "a list of {n} booleans (one per action)",
            "{n} 个布尔值的列表，每个动作一个"
        );
        let dones_v = column("dones", &dones_expected)?;
        if dones_v.len() != n {
            return Err(self.wrong(
                &format!("{path}.dones"),
                &dones_expected,
                &Value::Array(dones_v.clone()),
            ));
        }
        let dones = dones_v
            .iter()
            .enumerate()
            .map(|(t, d)| {
                d.as_bool().ok_or_else(|| {
                    self.wrong(
                        &format!("{path}.dones[{t}]"),
                        crate::i18n::t("true or false", "true 或 false"),
                        d,
                    )
                })
            })
            .collect::<Result<Vec<bool>, _>>()?;
        let actions = actions_v
            .iter()
            .enumerate()
            .map(|(t, a)| match a.as_u64() {
                Some(a @ 0..=1) => Ok(a as usize),
                _ => Err(self.wrong(
                    &format!("{path}.actions[{t}]"),
                    crate::i18n::t("0 or 1", "0 或 1"),
                    a,
                )),
            })
            .collect::<Result<Vec<usize>, _>>()?;
        if n == 0 {
            return Err(self.wrong(
                &format!("{path}.actions"),
                t("at least one transition", "至少一条转移"),
                &Value::Array(vec![]),
            ));
        }
        Ok(Transitions {
            states,
            actions,
            rewards,
            next_states,
            terminated: dones.clone(),
            dones,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn case_json() -> Value {
        serde_json::json!({"cases": [{
            "hyper": {"actor_lr": 1e-3, "critic_lr": 1e-2, "gamma": 0.98, "lmbda": 0.95,
                      "epochs": 2, "eps": 0.2, "hidden_dim": 2},
            "weights_before": {
                "actor.fc1.weight": [[0.1, 0.2, 0.3, 0.4], [-0.1, 0.0, 0.1, 0.2]],
                "actor.fc1.bias": [0.0, 0.1], "actor.fc2.weight": [[0.5, -0.5], [0.2, 0.1]],
                "actor.fc2.bias": [0.0, 0.0],
                "critic.fc1.weight": [[0.1, 0.2, 0.3, 0.4], [-0.1, 0.0, 0.1, 0.2]],
                "critic.fc1.bias": [0.0, 0.1], "critic.fc2.weight": [[0.5, -0.5]],
                "critic.fc2.bias": [0.0]},
            "batch": {"states": [[0.0, 0.1, 0.0, 0.1]], "actions": [1], "rewards": [1.0],
                      "next_states": [[0.0, 0.2, 0.0, 0.0]], "dones": [true]}}]})
    }

    #[test]
    fn a_small_case_replays() -> Result<(), PpoError> {
        let cases = parse_replay(&case_json().to_string(), "t.json")?;
        let out = replay_case(&cases[0])?;
        assert_eq!(out.td_target, vec![[1.0]]); // done: no bootstrap
        assert_eq!(out.epochs.len(), 2);
        Ok(())
    }

    #[test]
    fn errors_name_the_key_and_shape() {
        let mut j = case_json();
        j["cases"][0]["weights_before"]["critic.fc2.weight"] = serde_json::json!([[0.5]]);
        let err = parse_replay(&j.to_string(), "t.json")
            .err()
            .map(|e| e.to_string())
            .unwrap_or_default();
        assert!(
            err.contains("cases[0].weights_before.critic.fc2.weight[0]") && err.contains("[1, 2]"),
            "{err}"
        );
        let mut j = case_json();
        if let Some(b) = j["cases"][0]["batch"].as_object_mut() {
            b.remove("next_states");
        }
        let err = parse_replay(&j.to_string(), "t.json")
            .err()
            .map(|e| e.to_string())
            .unwrap_or_default();
        assert!(
            err.contains("missing key 'cases[0].batch.next_states'") && err.contains("[1, 4]"),
            "{err}"
        );
    }

    /// Only the objectives PyTorch recorded replay: the KL line search has no recording, and
    /// a file that says it is refused by name, as is an unknown objective.
    #[test]
    fn an_objective_without_a_recording_is_refused() {
        for objective in ["line-search", "trpo"] {
            let mut j = case_json();
            j["cases"][0]["objective"] = serde_json::json!(objective);
            let err = parse_replay(&j.to_string(), "t.json")
                .err()
                .map(|e| e.to_string())
                .unwrap_or_default();
            assert!(
                err.contains("cases[0].objective")
                    && err.contains("\"clip\" or \"penalty\"")
                    && err.contains(&format!("{objective:?}")),
                "{err}"
            );
        }
    }
}
