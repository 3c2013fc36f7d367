//! Every intermediate of one [`PpoContinuous::update`](super::PpoContinuous::update), as
//! plain data, for the lessons, the terminal app and the notebooks to display.
//!
//! Shapes, for an episode of `N` steps (column tensors `(N, 1)` stored flat):
//!
//! ```text
//! states, next_states (N, 3)      actions (torques), rewards, dones (N)
//! scaled_rewards = (r + 8) / 8 (N)
//! values = V(s), next_values = V(s') (N)
//! td_target, td_delta, advantage (N)
//! mu, std = π's (μ, σ) before the update, old_log_probs = log N(a; μ, σ) (N)
//! per epoch: log_probs, ratio, surr1, surr2 (N); actor_loss, critic_loss (scalars)
//! per update: path (which implementation ran)
//! ```
//!
//! The names are those of `ppo_continuous_update_pytorch.json`'s `expected` object (`path`
//! is ours).

use serde::Serialize;

use crate::ppo::update_path::UpdatePath;

/// One episode's batch and everything the update computed from it.
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct ContinuousUpdateTrace {
    /// `s_t`, the observation `(cos θ, sin θ, θ̇)` each torque was chosen in.
    pub states: Vec<[f32; 3]>,
    /// `a_t`, the sampled torque (before the environment clips it to `[-2, 2]`).
    pub actions: Vec<f32>,
    /// `r_t` as the environment gave it (f32).
    pub rewards: Vec<f32>,
    /// `s_{t+1}`.
    pub next_states: Vec<[f32; 3]>,
    /// `done_t` (terminated or truncated, as the book folds them).
    pub dones: Vec<bool>,
    /// `(r_t + 8) / 8`, the rewards the TD target uses.
    pub scaled_rewards: Vec<f32>,
    /// `V(s_t)` before the update.
    pub values: Vec<f32>,
    /// `V(s_{t+1})` before the update.
    pub next_values: Vec<f32>,
    /// `scaled_r_t + γ V(s_{t+1}) (1 - done_t)`.
    pub td_target: Vec<f32>,
    /// `td_target_t - V(s_t)`.
    pub td_delta: Vec<f32>,
    /// GAE of `td_delta`.
    pub advantage: Vec<f32>,
    /// `μ(s_t)` before the update.
    pub mu: Vec<f32>,
    /// `σ(s_t)` before the update.
    pub std: Vec<f32>,
    /// `log N(a_t; μ, σ)` before the first epoch, held fixed.
    pub old_log_probs: Vec<f32>,
    /// One entry per epoch, in order.
    pub epochs: Vec<ContinuousEpochTrace>,
    /// Which implementation computed this update: the plain `f32` kernels or candle with
    /// autograd (the same numbers; see [`update_path`](crate::ppo::update_path) for when
    /// each runs, and `PPO_TUTOR_UPDATE=candle` to force candle).
    pub path: UpdatePath,
}

/// One pass over the batch: values before that epoch's optimizer step.
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct ContinuousEpochTrace {
    /// `log N(a_t; μ, σ)` under the current actor.
    pub log_probs: Vec<f32>,
    /// `exp(log_probs - old_log_probs)`.
    pub ratio: Vec<f32>,
    /// `ratio · advantage`.
    pub surr1: Vec<f32>,
    /// `clamp(ratio, 1-ε, 1+ε) · advantage`.
    pub surr2: Vec<f32>,
    /// `mean(-min(surr1, surr2))`.
    pub actor_loss: f32,
    /// `mean((V(s_t) - td_target_t)²)`.
    pub critic_loss: f32,
}

impl ContinuousUpdateTrace {
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

    /// The last epoch, whose losses summarise the update.
    #[must_use]
    pub fn last_epoch(&self) -> Option<&ContinuousEpochTrace> {
        self.epochs.last()
    }
}
