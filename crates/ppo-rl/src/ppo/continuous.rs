//! The book's `PPOContinuous` (*Hands-on RL* chapter 12, second half) on candle: PPO with a
//! Gaussian policy, for Pendulum-v1's one torque in `[-2, 2]`.
//!
//! Everything but the policy is the discrete PPO's: the same [`ValueNet`](super::ValueNet),
//! TD target, GAE ([`compute_advantage`](super::compute_advantage)), clipped surrogate and
//! [`Adam`](super::Adam). What changes:
//!
//! ```text
//! h     = relu(fc1(s))                 s (N, 3) -> h (N, H)
//! μ     = 2 · tanh(fc_mu(h))           (N, 1), in (-2, 2)
//! σ     = softplus(fc_std(h))          (N, 1), > 0; softplus(x) = log(1 + eˣ) (x if x > 20)
//! a     ~ Normal(μ, σ)                 one torque per step
//! log π(a|s) = -(a - μ)² / (2σ²) - log σ - log √(2π)
//! rewards are rescaled to (r + 8) / 8 inside update(): Pendulum's r ∈ [-16.3, 0]
//! ```
//!
//! Read it in this order:
//!
//! - [`config`]: [`PpoContinuousConfig`], whose `Default` is the book's hyper-parameters.
//! - [`model`]: [`PolicyNetContinuous`] `(μ, σ)(s)` with PyTorch's softplus, and a plain-Rust
//!   copy of it for acting.
//! - [`normal`]: `Normal(μ, σ).log_prob` exactly as `torch.distributions.Normal`.
//! - [`agent`]: [`PpoContinuous`] with `take_action` and `update`, which returns a
//!   [`ContinuousUpdateTrace`] ([`trace`]).
//! - [`checkpoint`]: safetensors with PyTorch's names, marked as a Pendulum-v1 agent.
//! - [`replay`]: re-running a recorded PyTorch update (`ppo_continuous_update_pytorch.json`).
//! - the book's episode loop on Pendulum-v1 is the shared
//!   [`Training`](super::train::Training) ([`ContinuousTrainer`]): this agent implements
//!   [`OnPolicyAgent`] below.
//!
//! ```
//! use ppo_rl::ppo::{ContinuousTransitions, PpoContinuous, PpoContinuousConfig};
//!
//! let mut agent = PpoContinuous::new(&PpoContinuousConfig::default(), 0)?;
//! let state = [1.0_f32, 0.0, 0.0]; // (cos θ, sin θ, θ̇): upright, at rest
//! let torque = agent.take_action(&state)?;
//! let mut batch = ContinuousTransitions::default();
//! batch.push(state, torque, -0.5, [1.0, 0.01, 0.2], true);
//! let trace = agent.update(&batch)?;
//! assert_eq!(trace.scaled_rewards, vec![(-0.5 + 8.0) / 8.0]);
//! assert_eq!(trace.epochs[0].ratio, vec![1.0]); // π = π_old before the first step
//! # Ok::<(), ppo_rl::ppo::PpoError>(())
//! ```

pub mod agent;
pub mod checkpoint;
pub mod config;
pub mod model;
pub mod normal;
pub mod params;
pub mod replay;
pub mod trace;
#[cfg(test)]
mod train;

use std::path::Path;

use crate::env::Pendulum;
use crate::ppo::PpoError;
use crate::ppo::checkpoint::CheckpointKind;
use crate::ppo::model::NamedWeights;
use crate::ppo::on_policy::{AgentConfig, Batch, OnPolicyAgent, Replayed};

pub use crate::ppo::train::ContinuousTrainer;
pub use agent::{ContinuousTransitions, PpoContinuous};
pub use config::PpoContinuousConfig;
pub use model::{ContinuousActorSnapshot, PolicyNetContinuous, softplus, softplus_f32};
pub use normal::{log_prob, normal_log_prob};
pub use trace::{ContinuousEpochTrace, ContinuousUpdateTrace};

/// What one training episode on Pendulum produced.
pub type ContinuousEpisodeReport = crate::ppo::train::EpisodeReport<ContinuousUpdateTrace>;

/// Observations per state: Pendulum's `(cos θ, sin θ, θ̇)`.
pub const STATE_DIM: usize = 3;
/// Actions per step: one torque.
pub const ACTION_DIM: usize = 1;
/// The book's reward rescaling inside `update()`: `(r + REWARD_SHIFT) / REWARD_SCALE`.
pub const REWARD_SHIFT: f64 = 8.0;
/// See [`REWARD_SHIFT`].
pub const REWARD_SCALE: f64 = 8.0;

impl Batch for ContinuousTransitions {
    type Obs = [f32; 3];
    type Action = f32;

    /// `terminated` is not kept: Pendulum never terminates, and the book's `done` is all
    /// its update reads.
    fn record(
        &mut self,
        state: [f32; 3],
        action: f32,
        reward: f32,
        next_state: [f32; 3],
        done: bool,
        _terminated: bool,
    ) {
        self.push(state, action, reward, next_state, done);
    }

    fn steps(&self) -> usize {
        self.len()
    }

    /// Never: the pendulum has no terminal state (its episodes end at the time limit).
    fn terminated(&self) -> Vec<bool> {
        vec![false; self.len()]
    }
}

impl AgentConfig for PpoContinuousConfig {
    type Agent = PpoContinuous;

    fn validate(&self) -> Result<(), PpoError> {
        PpoContinuousConfig::validate(self)
    }

    fn num_episodes(&self) -> usize {
        self.num_episodes
    }

    fn env_id(&self) -> &'static str {
        crate::env::pendulum::ENV_ID
    }

    /// Pendulum's rewards are at most 0.
    fn max_return(&self) -> f64 {
        0.0
    }

    const ENV_IDS: &'static [&'static str] = &[crate::env::pendulum::ENV_ID];

    fn set_env_id(&mut self, id: &str) -> bool {
        id == crate::env::pendulum::ENV_ID
    }
}

impl OnPolicyAgent for PpoContinuous {
    type Config = PpoContinuousConfig;
    type Env = Pendulum;
    type Rollout = super::rollout::OneEpisode<Pendulum>;
    type Batch = ContinuousTransitions;
    type Trace = ContinuousUpdateTrace;

    const CHECKPOINT: CheckpointKind = CheckpointKind {
        env: "Pendulum-v1",
        algorithm: "ppo-continuous",
        telltale: "actor.fc_mu.weight",
        train_flags: "--env Pendulum-v1 ",
    };

    fn create(config: &PpoContinuousConfig, seed: u64) -> Result<Self, PpoError> {
        PpoContinuous::new(config, seed)
    }

    fn environment(_config: &PpoContinuousConfig) -> Pendulum {
        Pendulum::new()
    }

    fn act(&mut self, obs: &[f32; 3]) -> Result<f32, PpoError> {
        self.take_action(obs)
    }

    fn learn(&mut self, batch: &ContinuousTransitions) -> Result<ContinuousUpdateTrace, PpoError> {
        self.update(batch)
    }

    fn path_of(trace: &ContinuousUpdateTrace) -> crate::ppo::UpdatePath {
        trace.path
    }

    fn named_weights(&self) -> Result<NamedWeights, PpoError> {
        self.weights()
    }

    fn load_from(path: &Path, config: &PpoContinuousConfig, seed: u64) -> Result<Self, PpoError> {
        PpoContinuous::load(path, config, seed)
    }

    /// A Gaussian policy: `actor.fc_mu`.
    fn replays(weights_before: &serde_json::Value) -> bool {
        weights_before.get("actor.fc_mu.weight").is_some()
    }

    fn replay(text: &str, file: &str) -> Result<Vec<Result<Replayed, PpoError>>, PpoError> {
        let cases = replay::parse_continuous_replay(text, file)?;
        Ok(Replayed::all(
            &cases,
            replay::replay_continuous_case,
            |case, out| {
                let losses = out.epochs.iter().map(|e| (e.actor_loss, e.critic_loss));
                (case.batch.len(), losses.collect())
            },
        ))
    }
}
