//! Re-running a recorded PyTorch `PPOContinuous.update`: how anyone checks our numbers.
//!
//! The input has the schema of `ppo_continuous_update_pytorch.json` (made by
//! `ppo_continuous_fixtures.py`):
//!
//! ```text
//! {"cases": [{"hyper": {"actor_lr", "critic_lr", "gamma", "lmbda", "epochs", "eps", "hidden_dim"},
//!             "weights_before": {"actor.fc1.weight": (H, 3), ..., "actor.fc_mu.weight": (1, H),
//!                                ..., "critic.fc2.bias": (1)},
//!             "batch": {"states": (N, 3), "actions": (N) torques, "rewards": (N),
//!                       "next_states": (N, 3), "dones": (N)}}, ...]}
//! ```
//!
//! Each case runs [`PpoContinuous::update`] from `weights_before` on `batch` with fresh Adam
//! state; [`ContinuousReplayOutput`] holds what the fixture's `expected` and `weights_after`
//! hold, with the same key names and shapes (columns as `(N, 1)` lists of one-element lists).

use crate::i18n::t;
use serde::Serialize;
use serde_json::{Map, Value};

use super::agent::{ContinuousTransitions, PpoContinuous};
use super::params::parameter_shapes;
use super::{PpoContinuousConfig, STATE_DIM};
use crate::ppo::PpoError;
use crate::ppo::model::NamedWeights;
use crate::ppo::replay_file::{Reader, batch_expected, hyper_expected, nested};

/// One case to replay.
#[derive(Debug, Clone)]
pub struct ContinuousReplayCase {
    /// The hyper-parameters from `hyper` (`num_episodes` is the book's default, unused).
    pub config: PpoContinuousConfig,
    /// `weights_before`.
    pub weights_before: NamedWeights,
    /// `batch`.
    pub batch: ContinuousTransitions,
}

/// One replayed case, in the fixture's key names and shapes.
#[derive(Debug, Clone, Serialize)]
pub struct ContinuousReplayOutput {
    /// `(N, 1)`: `(r + 8) / 8`.
    pub scaled_rewards: Vec<[f32; 1]>,
    /// `(N, 1)`.
    pub td_target: Vec<[f32; 1]>,
    /// `(N, 1)`.
    pub td_delta: Vec<[f32; 1]>,
    /// `(N, 1)`.
    pub advantage: Vec<[f32; 1]>,
    /// `(N, 1)`: μ before the update.
    pub mu: Vec<[f32; 1]>,
    /// `(N, 1)`: σ before the update.
    pub std: Vec<[f32; 1]>,
    /// `(N, 1)`.
    pub old_log_probs: Vec<[f32; 1]>,
    /// One per epoch.
    pub epochs: Vec<ContinuousReplayEpoch>,
    /// Every parameter after the update, nested lists in PyTorch's layout.
    pub weights_after: Map<String, Value>,
}

/// One epoch of a replayed case.
#[derive(Debug, Clone, Serialize)]
pub struct ContinuousReplayEpoch {
    /// `(N, 1)`.
    pub log_probs: Vec<[f32; 1]>,
    /// `(N, 1)`.
    pub ratio: Vec<[f32; 1]>,
    /// `(N, 1)`.
    pub surr1: Vec<[f32; 1]>,
    /// `(N, 1)`.
    pub surr2: Vec<[f32; 1]>,
    /// Scalar.
    pub actor_loss: f32,
    /// Scalar.
    pub critic_loss: f32,
}

/// Parses a continuous replay file's text; `file` names it in errors.
///
/// # Errors
/// [`PpoError::File`] for text that is not JSON; [`PpoError::MissingKey`] /
/// [`PpoError::WrongShape`] naming the key path (like `cases[0].batch.states`) and the
/// expected shape; [`PpoError::InvalidConfig`] for a hyper-parameter out of range.
pub fn parse_continuous_replay(
    text: &str,
    file: &str,
) -> Result<Vec<ContinuousReplayCase>, PpoError> {
    let r = Reader { file };
    r.cases(text, |case, path| parse_case(&r, case, path))
}

/// Runs one case: the update from `weights_before` with fresh Adam state.
///
/// # Errors
/// [`PpoError::NonFinite`] when the update produces NaN; shape errors cannot happen after
/// [`parse_continuous_replay`].
pub fn replay_continuous_case(
    case: &ContinuousReplayCase,
) -> Result<ContinuousReplayOutput, PpoError> {
    let mut agent =
        PpoContinuous::from_weights(&case.config, &case.weights_before, 0, "weights_before")?;
    let trace = agent.update(&case.batch)?;
    let col = |v: &[f32]| v.iter().map(|&x| [x]).collect::<Vec<_>>();
    let mut weights_after = Map::new();
    for (name, w) in agent.weights()? {
        weights_after.insert(name, nested(&w));
    }
    Ok(ContinuousReplayOutput {
        scaled_rewards: col(&trace.scaled_rewards),
        td_target: col(&trace.td_target),
        td_delta: col(&trace.td_delta),
        advantage: col(&trace.advantage),
        mu: col(&trace.mu),
        std: col(&trace.std),
        old_log_probs: col(&trace.old_log_probs),
        epochs: trace
            .epochs
            .iter()
            .map(|e| ContinuousReplayEpoch {
                log_probs: col(&e.log_probs),
                ratio: col(&e.ratio),
                surr1: col(&e.surr1),
                surr2: col(&e.surr2),
                actor_loss: e.actor_loss,
                critic_loss: e.critic_loss,
            })
            .collect(),
        weights_after,
    })
}

fn parse_case(r: &Reader<'_>, case: &Value, path: &str) -> Result<ContinuousReplayCase, PpoError> {
    let config = hyper(
        r,
        r.key(case, path, "hyper", hyper_expected())?,
        &format!("{path}.hyper"),
    )?;
    let weights = r.key(
        case,
        path,
        "weights_before",
        t(
            "the ten actor./critic. tensors",
            "actor./critic. 的十个张量",
        ),
    )?;
    let weights_before = r.named_tensors(
        weights,
        &format!("{path}.weights_before"),
        parameter_shapes(config.hidden_dim),
    )?;
    let batch = batch(
        r,
        r.key(case, path, "batch", batch_expected())?,
        &format!("{path}.batch"),
    )?;
    Ok(ContinuousReplayCase {
        config,
        weights_before,
        batch,
    })
}

fn hyper(r: &Reader<'_>, h: &Value, path: &str) -> Result<PpoContinuousConfig, PpoError> {
    let num = |key: &str, expected: &str| -> Result<f64, PpoError> {
        r.number(
            r.key(h, path, key, expected)?,
            &format!("{path}.{key}"),
            expected,
        )
    };
    let count = |key: &str| -> Result<usize, PpoError> {
        let expected = t("a positive integer", "正整数");
        let v = r.key(h, path, key, expected)?;
        v.as_u64()
            .and_then(|n| usize::try_from(n).ok())
            .ok_or_else(|| r.wrong(&format!("{path}.{key}"), expected, v))
    };
    let config = PpoContinuousConfig {
        actor_lr: num("actor_lr", t("a number > 0", "大于 0 的数"))?,
        critic_lr: num("critic_lr", t("a number > 0", "大于 0 的数"))?,
        gamma: num("gamma", t("a number in (0, 1]", "(0, 1] 内的数"))?,
        lmbda: num("lmbda", t("a number in [0, 1]", "[0, 1] 内的数"))?,
        eps: num("eps", t("a number in (0, 1)", "(0, 1) 内的数"))?,
        epochs: count("epochs")?,
        hidden_dim: count("hidden_dim")?,
        ..PpoContinuousConfig::default()
    };
    config.validate()?;
    Ok(config)
}

fn batch(r: &Reader<'_>, b: &Value, path: &str) -> Result<ContinuousTransitions, PpoError> {
    let column = |key: &str, expected: &str| -> Result<&Vec<Value>, PpoError> {
        r.array(
            r.key(b, path, key, expected)?,
            &format!("{path}.{key}"),
            expected,
        )
    };
    let n = column("actions", t("a list of N torques", "N 个力矩的列表"))?.len();
    if n == 0 {
        return Err(r.wrong(
            &format!("{path}.actions"),
            t("at least one transition", "至少一条转移"),
            &Value::Array(vec![]),
        ));
    }
    let numbers = |key: &str, what: &str| -> Result<Vec<f32>, PpoError> {
        // f64 in the file, rounded to f32 as `torch.tensor(..., dtype=torch.float)` does
        let expected = crate::tr!(
            "a list of {n} {what} (one per step)",
            "{n} 个{what}的列表，每步一个"
        );
        r.floats(
            r.key(b, path, key, &expected)?,
            &format!("{path}.{key}"),
            Some(n),
            &expected,
        )
    };
    let rows = |key: &str| -> Result<Vec<[f32; 3]>, PpoError> {
        let expected = crate::tr!(
            "a list of shape [{n}, {STATE_DIM}] (one observation per step)",
            "形状 [{n}, {STATE_DIM}] 的列表，每步一个观测"
        );
        let list = column(key, &expected)?;
        if list.len() != n {
            let got = Value::Array(list.clone());
            return Err(r.wrong(&format!("{path}.{key}"), &expected, &got));
        }
        list.iter()
            .enumerate()
            .map(|(t, row)| {
                let key = format!("{path}.{key}[{t}]");
                let v = r.floats(row, &key, Some(STATE_DIM), &expected)?;
                Ok([v[0], v[1], v[2]])
            })
            .collect()
    };
    let dones_expected = format!("a list of {n} booleans (one per step)");
    let dones_v = column("dones", &dones_expected)?;
    if dones_v.len() != n {
        let got = Value::Array(dones_v.clone());
        return Err(r.wrong(&format!("{path}.dones"), &dones_expected, &got));
    }
    let dones = dones_v
        .iter()
        .enumerate()
        .map(|(t, d)| {
            d.as_bool().ok_or_else(|| {
                r.wrong(
                    &format!("{path}.dones[{t}]"),
                    crate::i18n::t("true or false", "true 或 false"),
                    d,
                )
            })
        })
        .collect::<Result<Vec<bool>, _>>()?;
    Ok(ContinuousTransitions {
        states: rows("states")?,
        actions: numbers("actions", t("torques", "力矩"))?,
        rewards: numbers("rewards", t("rewards", "奖励"))?,
        next_states: rows("next_states")?,
        dones,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ppo::on_policy::{OnPolicyAgent, Replayed};
    use crate::ppo::replay_file::first_weights;
    use crate::ppo::{Agent, PpoContinuous};

    /// Replays `text` as the agent that claims it, as the course's registry does.
    #[allow(clippy::type_complexity)]
    fn replay_any(text: &str, file: &str) -> Result<Vec<Result<Replayed, PpoError>>, PpoError> {
        let weights = first_weights(text, file)?;
        assert!(
            !Agent::replays(&weights),
            "the discrete agent does not claim it"
        );
        if PpoContinuous::replays(&weights) {
            PpoContinuous::replay(text, file)
        } else {
            Agent::replay(text, file)
        }
    }

    fn case_json() -> Value {
        serde_json::json!({"cases": [{
            "hyper": {"actor_lr": 1e-4, "critic_lr": 5e-3, "gamma": 0.9, "lmbda": 0.9,
                      "epochs": 2, "eps": 0.2, "hidden_dim": 2},
            "weights_before": {
                "actor.fc1.weight": [[0.1, 0.2, 0.3], [-0.1, 0.0, 0.1]],
                "actor.fc1.bias": [0.0, 0.1],
                "actor.fc_mu.weight": [[0.5, -0.5]], "actor.fc_mu.bias": [0.0],
                "actor.fc_std.weight": [[0.2, 0.1]], "actor.fc_std.bias": [0.0],
                "critic.fc1.weight": [[0.1, 0.2, 0.3], [-0.1, 0.0, 0.1]],
                "critic.fc1.bias": [0.0, 0.1], "critic.fc2.weight": [[0.5, -0.5]],
                "critic.fc2.bias": [0.0]},
            "batch": {"states": [[1.0, 0.0, 0.1]], "actions": [0.5], "rewards": [-8.0],
                      "next_states": [[1.0, 0.01, 0.2]], "dones": [true]}}]})
    }

    #[test]
    fn a_small_case_replays() -> Result<(), PpoError> {
        let text = case_json().to_string();
        let replayed = replay_any(&text, "t.json")?;
        assert_eq!(replayed.len(), 1, "recognised as the continuous agent's");
        let cases = parse_continuous_replay(&text, "t.json")?;
        let out = replay_continuous_case(&cases[0])?;
        let first = replayed.into_iter().next().ok_or(PpoError::EmptyBatch)??;
        assert_eq!(
            first.output,
            serde_json::to_string(&out).unwrap_or_default()
        );
        assert_eq!((first.transitions, first.losses.len()), (1, 2));
        assert_eq!(out.scaled_rewards, vec![[0.0]]); // (-8 + 8) / 8
        assert_eq!(out.td_target, vec![[0.0]]); // done: no bootstrap
        assert_eq!(out.epochs.len(), 2);
        assert_eq!(out.weights_after.len(), 10);
        Ok(())
    }

    #[test]
    fn errors_name_the_key_and_shape() {
        let mut j = case_json();
        j["cases"][0]["weights_before"]["actor.fc_std.weight"] = serde_json::json!([[0.5]]);
        let err = replay_any(&j.to_string(), "t.json")
            .err()
            .map(|e| e.to_string())
            .unwrap_or_default();
        assert!(
            err.contains("cases[0].weights_before.actor.fc_std.weight[0]")
                && err.contains("[1, 2]"),
            "{err}"
        );
        let mut j = case_json();
        j["cases"][0]["batch"]["states"] = serde_json::json!([[1.0, 0.0, 0.1, 0.0]]);
        let err = replay_any(&j.to_string(), "t.json")
            .err()
            .map(|e| e.to_string())
            .unwrap_or_default();
        assert!(
            err.contains("cases[0].batch.states[0]") && err.contains("[1, 3]"),
            "{err}"
        );
    }
}
