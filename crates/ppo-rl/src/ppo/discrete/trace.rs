//! Every intermediate of one [`Agent::update`](crate::ppo::Agent::update), as plain data.
//!
//! The lessons, the terminal app and the notebooks display these; nothing here holds a
//! tensor. Shapes, for an episode of `N` steps (column tensors `(N, 1)` stored flat):
//!
//! ```text
//! states, next_states (N, 4)      actions, rewards, dones (N)
//! values = V(s), next_values = V(s') (N)
//! td_target, td_delta, advantage, lambda_return, old_log_probs (N)
//! per epoch: log_probs, ratio, surr1, surr2, clipped (N); actor_loss, critic_loss, approx_kl,
//!            clip_fraction, entropy (scalars); PPO-Penalty only: kl (N), kl_mean (scalar)
//! per update: explained_variance, early_stop (scalars), path (which implementation ran);
//!             kl_after (the mean exact KL(π_old ‖ π_new), every objective; not in JSON);
//!             PPO-Penalty only: penalty (β before and after, the KL after the last epoch);
//!             KL line search only: line_search (the accepted step, its halvings, KL and gain)
//! ```

use serde::Serialize;

use crate::ppo::update_path::UpdatePath;

/// One episode's batch and everything the update computed from it.
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct UpdateTrace {
    /// `s_t`, the observation each action was taken in.
    pub states: Vec<[f32; 4]>,
    /// `a_t`, 0 (left) or 1 (right).
    pub actions: Vec<usize>,
    /// `r_t` as the update saw it (f32).
    pub rewards: Vec<f32>,
    /// `s_{t+1}`.
    pub next_states: Vec<[f32; 4]>,
    /// `done_t`, as used in the TD target (the seed's `terminated or truncated`, or only
    /// `terminated` with the truncation switch).
    pub dones: Vec<bool>,
    /// `V(s_t)` before the update.
    pub values: Vec<f32>,
    /// `V(s_{t+1})` before the update.
    pub next_values: Vec<f32>,
    /// `r_t + γ V(s_{t+1}) (1 - done_t)`.
    pub td_target: Vec<f32>,
    /// `td_target_t - V(s_t)`.
    pub td_delta: Vec<f32>,
    /// GAE of `td_delta`, as the epochs used it (normalised if the switch is on).
    pub advantage: Vec<f32>,
    /// The λ-return `Â_t + V(s_t)` (before any normalisation of `Â`): what CleanRL fits the
    /// critic to, where the seed uses `td_target`. With λ = 1 (REINFORCE) it is the
    /// discounted return `G_t`.
    pub lambda_return: Vec<f32>,
    /// `log π_old(a_t|s_t)` before the first epoch, held fixed.
    pub old_log_probs: Vec<f32>,
    /// One entry per epoch that ran, in order: all `epochs` of them, or fewer when
    /// `target_kl` stopped the update ([`Self::early_stop`]).
    pub epochs: Vec<EpochTrace>,
    /// Where `target_kl` stopped the update, `None` if every epoch ran.
    pub early_stop: Option<EarlyStop>,
    /// How much of the TD target's variance the critic explains before the update,
    /// `1 − Var[td_target − V(s)] / Var[td_target]` (CleanRL's `explained_variance`): 1 is a
    /// perfect critic, 0 one no better than a constant, below 0 worse. `None` when the
    /// targets do not vary.
    pub explained_variance: Option<f32>,
    /// Which implementation computed this update: the plain `f32` kernels or candle with
    /// autograd (the same numbers; see [`update_path`](crate::ppo::update_path) for when
    /// each runs, and `PPO_TUTOR_UPDATE=candle` to force candle). PPO-Penalty always runs on
    /// candle: the plain kernels hold only the clipped surrogate's gradient.
    pub path: UpdatePath,
    /// PPO-Penalty's β and the KL it was adapted on; `None` for the clip and REINFORCE.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub penalty: Option<PenaltyTrace>,
    /// The KL line search's step ([`line_search`](super::line_search)); `None` for the other
    /// objectives and REINFORCE.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub line_search: Option<LineSearchTrace>,
    /// The mean over the batch of the exact `KL(π_old(·|s_t) ‖ π_new(·|s_t))` between the
    /// actor before and after this update, the same measure for every objective (clip, no
    /// clip, PPO-Penalty, the line search, REINFORCE), so that the lab compares how far each
    /// moves the policy per update. Set by [`Agent::update`](crate::ppo::Agent::update) and
    /// [`Agent::update_with`](crate::ppo::Agent::update_with) (`None` in a trace built
    /// otherwise). Not serialised, so that saved traces and their hashes are unchanged;
    /// PPO-Penalty's and the line search's own records carry their KL in JSON.
    #[serde(skip)]
    pub kl_after: Option<f32>,
}

/// What one KL line search did ([`line_search`](super::line_search)): the step along the
/// surrogate's gradient it accepted, if any.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct LineSearchTrace {
    /// `‖g‖`, the L2 norm of `∇θ mean(ratio · Â)` at θ_old over every actor parameter; 0
    /// when the advantages are all 0 (then no step is tried).
    pub grad_norm: f32,
    /// The mean exact KL of the first try (α = `ls_max_step`); `None` when no step was tried.
    pub first_kl: Option<f32>,
    /// The accepted α (the step's length in parameter space), `None` when every try was
    /// refused and the actor kept θ_old.
    pub step: Option<f64>,
    /// How many times α was halved: before the accepted try, or every halving allowed
    /// (`ls_backtracks`) when none was accepted; 0 when no step was tried.
    pub halvings: usize,
    /// The accepted step's mean exact KL(π_old ‖ π_θ) over the batch (≤ `kl_delta`).
    pub kl: Option<f32>,
    /// The accepted step's surrogate gain `mean((ratio − 1) · Â)` (> 0).
    pub gain: Option<f32>,
}

/// What one PPO-Penalty update did to β ([`penalty`](super::penalty)).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PenaltyTrace {
    /// β during this update's epochs.
    pub beta_before: f64,
    /// `d`, the mean exact KL(π_old ‖ π) under the actor after the last epoch.
    pub kl_after: f32,
    /// β for the next update: halved if `d < δ / 1.5`, doubled if `d > 1.5 · δ`, else kept.
    pub beta_after: f64,
}

/// An update that `target_kl` ended before its last epoch.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct EarlyStop {
    /// The epoch (from 1) that did not take its step.
    pub epoch: usize,
    /// Its `approx_kl`, above `1.5 · target_kl`.
    pub approx_kl: f32,
}

/// One pass over the batch: values before that epoch's optimizer step.
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct EpochTrace {
    /// `log π(a_t|s_t)` under the current actor.
    pub log_probs: Vec<f32>,
    /// `exp(log_probs - old_log_probs)`.
    pub ratio: Vec<f32>,
    /// `ratio · advantage`.
    pub surr1: Vec<f32>,
    /// `clamp(ratio, 1-ε, 1+ε) · advantage`.
    pub surr2: Vec<f32>,
    /// Whether the ratio left `[1-ε, 1+ε]` (CleanRL's `clipfrac` counts these).
    pub clipped: Vec<bool>,
    /// `mean(-min(surr1, surr2))`, or PPO-Penalty's `−mean(surr1) + β · kl_mean` (minus the
    /// entropy bonus when that switch is on), or `−mean(surr1)` for `no_clip` and the line
    /// search (whose actor takes no Adam step: its epochs step only the critic).
    pub actor_loss: f32,
    /// `mean((V(s_t) - td_target_t)²)`.
    pub critic_loss: f32,
    /// `mean((ratio - 1) - log ratio)`, CleanRL's estimate of KL(π_old ‖ π).
    pub approx_kl: f32,
    /// The share of `clipped` entries.
    pub clip_fraction: f32,
    /// Mean policy entropy over the batch, `-Σ_a π log π`.
    pub entropy: f32,
    /// PPO-Penalty: the exact `KL(π_old(·|s_t) ‖ π(·|s_t))` of each row under the current
    /// actor; empty for the clip and REINFORCE.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub kl: Vec<f32>,
    /// PPO-Penalty: `mean(kl)`, the term β multiplies in this epoch's actor loss; `None` for
    /// the clip and REINFORCE.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub kl_mean: Option<f32>,
}

impl UpdateTrace {
    /// The number of transitions in the batch.
    #[must_use]
    pub fn len(&self) -> usize {
        self.actions.len()
    }

    /// Whether the batch is empty.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.actions.is_empty()
    }

    /// The number of epochs that took their optimizer step.
    #[must_use]
    pub fn epochs_run(&self) -> usize {
        self.epochs.len()
    }

    /// The last epoch, whose losses summarise the update.
    #[must_use]
    pub fn last_epoch(&self) -> Option<&EpochTrace> {
        self.epochs.last()
    }
}
