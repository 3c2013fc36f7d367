//! What the live session shows of the seed's PPO on CartPole: the update's trace, the
//! probabilities the episode was played with, Gymnasium's two end flags, the two policy
//! gradients at θ_old and θ_old itself (where the trust-region probe steps from), and the
//! live values only this agent computes.

use super::super::batch::{Actions, Batch, EpochView, Rows};
use super::super::session::LiveAgent;
use super::super::values::{clip_marks, labelled, return_to_go, signed};
use super::super::{Index, LatestView, Snapshot, TensorView};
use crate::i18n::t;
use crate::ppo::model::ActorSnapshot;
use crate::ppo::{
    Agent, EpisodeReport, EpochTrace, PolicyNet, PpoConfig, PpoError, SurrogateGradients,
    UpdateTrace, surrogate_gradients,
};

/// What a CartPole run shows of its latest episode and update.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct CartPoleLatest {
    /// The latest update's batch and intermediates.
    pub trace: UpdateTrace,
    /// `π(·|s_t)` over the batch under the policy that played it (before the update).
    pub probs: Vec<[f32; 2]>,
    /// Gymnasium's `terminated` for each step of the episode.
    pub terminated: Vec<bool>,
    /// Gymnasium's `truncated` for each step of the episode.
    pub truncated: Vec<bool>,
    /// The batch's two policy gradients at θ_old, PPO's surrogate and REINFORCE's
    /// `log π · Â` (the policy-gradient lesson shows them side by side).
    pub gradients: SurrogateGradients,
    /// The actor that played the batch, θ_old (before the batch's update), as plain
    /// weights: where the trust-region probe ([`crate::lesson::live::probe`]) steps from.
    pub played_with: ActorSnapshot,
}

impl crate::run::IntoLatest for CartPoleLatest {
    fn into_latest(self) -> crate::run::Latest {
        crate::run::Latest::CartPole(Some(Box::new(self)))
    }
}

impl Snapshot {
    /// A CartPole run's latest episode and update; `None` before the first episode or in
    /// another agent's run.
    #[must_use]
    pub fn cartpole_update(&self) -> Option<&CartPoleLatest> {
        match &self.latest {
            crate::run::Latest::CartPole(latest) => latest.as_deref(),
            _ => None,
        }
    }
}

/// The live values only the discrete policy's runs have, in the seed's order.
const LIVE_VALUES: &[&str] = &[
    "probs",
    "obs",
    "terminated",
    "truncated",
    "return_to_go",
    "lambda_return",
    "clipped",
    "approx_kl",
    "kl_mean",
    "beta",
    "kl_after",
    "clip_frac",
    "entropy",
    "epochs_run",
    "explained_variance",
    "grad_surrogate",
    "grad_log_prob",
    "grad_max_diff",
];

/// Live values that only PPO-Penalty's update computes (`objective = "penalty"`): in a run
/// of another objective they stay empty ([`LatestView::why_missing`] says so).
pub const PENALTY_ONLY: [&str; 2] = ["kl_mean", "beta"];

impl LiveAgent for Agent {
    /// The policy the episode is played with, before the episode's update changes it: its
    /// probabilities are the ones the actions were sampled from (`old_log_probs`); and
    /// θ_old as candle variables, for the two policy gradients of the batch it played.
    type Before = (ActorSnapshot, PolicyNet);
    type Latest = CartPoleLatest;
    const LIVE_VALUES: &'static [&'static str] = LIVE_VALUES;

    fn hyper(c: &PpoConfig, seed: u64) -> Vec<(String, String)> {
        vec![
            ("actor_lr".into(), format!("{}", c.actor_lr)),
            ("critic_lr".into(), format!("{}", c.critic_lr)),
            ("num_episodes".into(), c.num_episodes.to_string()),
            ("hidden_dim".into(), c.hidden_dim.to_string()),
            ("gamma".into(), c.gamma.to_string()),
            ("lmbda".into(), c.lmbda.to_string()),
            ("epochs".into(), c.epochs.to_string()),
            ("eps".into(), c.eps.to_string()),
            ("env_name".into(), c.env_id.as_str().into()),
            ("seed".into(), seed.to_string()),
            (
                "bootstrap_on_truncation".into(),
                c.bootstrap_on_truncation.to_string(),
            ),
            (
                "normalize_advantage".into(),
                c.normalize_advantage.to_string(),
            ),
            ("no_clip".into(), c.no_clip.to_string()),
            ("algorithm".into(), c.algorithm.as_str().into()),
        ]
    }

    fn eps_gamma(c: &PpoConfig) -> (f64, f64) {
        (c.eps, c.gamma)
    }

    fn before_episode(&self) -> Result<Self::Before, PpoError> {
        Ok((
            ActorSnapshot::of(self.actor())?,
            self.actor().frozen_copy()?,
        ))
    }

    fn show(
        &self,
        (played_with, theta_old): Self::Before,
        report: EpisodeReport,
    ) -> Result<CartPoleLatest, PpoError> {
        let gradients = surrogate_gradients(
            &theta_old,
            &report.trace.states,
            &report.trace.actions,
            &report.trace.advantage,
        )?;
        Ok(CartPoleLatest {
            probs: probs_over(&played_with, &report.trace.states),
            terminated: report.terminated,
            truncated: report.truncated,
            gradients,
            trace: report.trace,
            played_with,
        })
    }
}

/// `π(·|s)` under `policy` for each of `states` (NaN where a probability is missing).
pub(crate) fn probs_over(policy: &ActorSnapshot, states: &[[f32; 4]]) -> Vec<[f32; 2]> {
    states
        .iter()
        .map(|s| {
            let p = policy.probs(s);
            [
                p.first().copied().unwrap_or(f32::NAN),
                p.get(1).copied().unwrap_or(f32::NAN),
            ]
        })
        .collect()
}

impl LatestView for CartPoleLatest {
    fn batch(&self) -> Batch<'_> {
        let t = &self.trace;
        Batch {
            states: Rows::of(&t.states),
            next_states: Rows::of(&t.next_states),
            actions: Actions::Discrete(&t.actions),
            rewards: &t.rewards,
            dones: &t.dones,
            values: &t.values,
            next_values: &t.next_values,
            td_target: &t.td_target,
            td_delta: &t.td_delta,
            advantage: &t.advantage,
            old_log_probs: &t.old_log_probs,
            epochs: t
                .epochs
                .iter()
                .map(|e| EpochView {
                    log_probs: &e.log_probs,
                    ratio: &e.ratio,
                    surr1: &e.surr1,
                    surr2: &e.surr2,
                    clipped: Some(&e.clipped),
                    actor_loss: e.actor_loss,
                    critic_loss: e.critic_loss,
                })
                .collect(),
        }
    }

    fn tensor(&self, n: &'static str, s: &Snapshot) -> Option<TensorView> {
        let trace = &self.trace;
        let last = trace.epochs.last();
        Some(match n {
            "probs" => {
                let values = self.probs.iter().flatten().map(|&p| f64::from(p)).collect();
                TensorView::new(n, vec![self.probs.len(), 2], "float32", values)
            }
            "obs" => TensorView::rows(n, &trace.next_states),
            "terminated" => TensorView::flags(n, &self.terminated),
            "truncated" => TensorView::flags(n, &self.truncated),
            "return_to_go" => {
                let g: Vec<f32> = return_to_go(&trace.rewards, &trace.dones, s.gamma)
                    .into_iter()
                    .map(|x| x as f32)
                    .collect();
                TensorView::column(n, &g)
            }
            "lambda_return" => TensorView::column(n, &trace.lambda_return),
            "clipped" => {
                let epoch = last?;
                let mut v = TensorView::flags(n, &epoch.clipped);
                v.dtype = "bool";
                v.marks = clip_marks(&epoch.clipped);
                v
            }
            "approx_kl" => series(n, trace, |e| e.approx_kl),
            "kl_mean" => {
                trace.penalty?;
                let values: Vec<f64> = trace
                    .epochs
                    .iter()
                    .map(|e| e.kl_mean.map_or(f64::NAN, f64::from))
                    .collect();
                TensorView::new(n, vec![values.len()], "float32", values).counting(Index::Epoch)
            }
            "beta" => {
                let p = trace.penalty?;
                let rows = [
                    (
                        t("β in this update's loss", "本次更新损失中的 β"),
                        p.beta_before,
                    ),
                    (
                        t("d, the KL after it", "d，更新后的 KL"),
                        f64::from(p.kl_after),
                    ),
                    (t("β for the next update", "下一次更新的 β"), p.beta_after),
                ];
                labelled(n, "float64", (&rows, 23), |v| format!("{v:.4e}"))
            }
            "kl_after" => TensorView::new(n, vec![1], "float32", vec![f64::from(trace.kl_after?)]),
            "clip_frac" => series(n, trace, |e| e.clip_fraction),
            "entropy" => series(n, trace, |e| e.entropy),
            "epochs_run" => TensorView::new(n, vec![1], "int64", vec![trace.epochs_run() as f64]),
            "explained_variance" => {
                let ev = trace.explained_variance.map_or(f64::NAN, f64::from);
                TensorView::new(n, vec![1], "float32", vec![ev])
            }
            "grad_surrogate" => signed(TensorView::column(n, &self.gradients.surrogate)),
            "grad_log_prob" => signed(TensorView::column(n, &self.gradients.log_prob)),
            "grad_max_diff" => {
                let g = &self.gradients;
                let rows = [
                    (
                        t("max |surrogate − log π|", "两个梯度之差的最大绝对值"),
                        f64::from(g.max_abs_diff()),
                    ),
                    (
                        t("max |log π gradient|", "log π 梯度的最大绝对值"),
                        f64::from(g.max_abs()),
                    ),
                ];
                labelled(n, "float32", (&rows, 0), |v| format!("{:.3e}", v as f32))
            }
            _ => return None,
        })
    }

    fn why_missing(&self, name: &str) -> Option<String> {
        PENALTY_ONLY.contains(&name).then(|| {
            crate::tr!(
                "{name}: only PPO-Penalty computes it (objective = penalty); this run's objective is another",
                "{name}：只有 PPO-惩罚才计算它（objective = penalty），这次运行用的是别的目标"
            )
        })
    }
}

/// A per-epoch scalar of the update as a vector over epochs (`(epochs,)`).
fn series(name: &'static str, t: &UpdateTrace, f: impl Fn(&EpochTrace) -> f32) -> TensorView {
    let values: Vec<f64> = t.epochs.iter().map(|e| f64::from(f(e))).collect();
    TensorView::new(name, vec![values.len()], "float32", values).counting(Index::Epoch)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// PPO-Penalty's live values come from its trace: each epoch's exact mean KL (0 before
    /// the first step), β before, d and β after; a clip run has none of them and says why.
    #[test]
    fn penalty_values_view_the_penalty_trace() -> Result<(), crate::ppo::PpoError> {
        use crate::lesson::Session;
        use crate::ppo::{Objective, PpoConfig};
        let penalty = PpoConfig {
            objective: Objective::Penalty,
            num_episodes: 3,
            ..PpoConfig::default()
        };
        let s = Session::run(penalty, 0, 3)?;
        let t = &s
            .cartpole_update()
            .ok_or(crate::ppo::PpoError::EmptyBatch)?
            .trace;
        let p = t.penalty.ok_or(crate::ppo::PpoError::EmptyBatch)?;
        let beta = s.tensor("beta").ok_or(crate::ppo::PpoError::EmptyBatch)?;
        assert_eq!(
            beta.values,
            [p.beta_before, f64::from(p.kl_after), p.beta_after]
        );
        assert_eq!(beta.labels.len(), 3);
        let kl = s
            .tensor("kl_mean")
            .ok_or(crate::ppo::PpoError::EmptyBatch)?;
        assert_eq!(kl.values.len(), t.epochs.len());
        assert_eq!(kl.values[0], 0.0, "π_θ is π_old before the first step");
        assert!(kl.values.windows(2).all(|w| w[1] >= w[0]) && kl.values[9] > 0.0);
        let after = s
            .tensor("kl_after")
            .ok_or(crate::ppo::PpoError::EmptyBatch)?;
        // The same KL, computed by the penalty (candle) and for every objective (plain f32).
        let d = f64::from(p.kl_after);
        assert!(
            (after.values[0] - d).abs() < 1e-5 * d,
            "d is kl_after: {after:?} {d}"
        );

        let clip = Session::run(
            PpoConfig {
                num_episodes: 3,
                ..PpoConfig::default()
            },
            0,
            3,
        )?;
        for name in PENALTY_ONLY {
            assert!(clip.tensor(name).is_none(), "{name}");
            assert!(
                crate::lesson::live::why_missing(name, &clip).contains("penalty"),
                "{name}"
            );
        }
        assert!(
            clip.tensor("kl_after").is_some(),
            "every objective reports it"
        );
        let fresh = Snapshot::default();
        assert!(crate::lesson::live::why_missing("beta", &fresh).contains("train an episode"));
        Ok(())
    }
}
