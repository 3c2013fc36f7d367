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
//! - [`train`](mod@train): the book's episode loop on Pendulum-v1 as a step-by-step
//!   [`ContinuousTrainer`], and [`train_continuous`].
//!
//! ```
//! use ppo_engine::ppo::{ContinuousTransitions, PpoContinuous, PpoContinuousConfig};
//!
//! let mut agent = PpoContinuous::new(&PpoContinuousConfig::default(), 0)?;
//! let state = [1.0_f32, 0.0, 0.0]; // (cos θ, sin θ, θ̇): upright, at rest
//! let torque = agent.take_action(&state)?;
//! let mut batch = ContinuousTransitions::default();
//! batch.push(state, torque, -0.5, [1.0, 0.01, 0.2], true);
//! let trace = agent.update(&batch)?;
//! assert_eq!(trace.scaled_rewards, vec![(-0.5 + 8.0) / 8.0]);
//! assert_eq!(trace.epochs[0].ratio, vec![1.0]); // π = π_old before the first step
//! # Ok::<(), ppo_engine::ppo::PpoError>(())
//! ```

pub mod agent;
pub mod checkpoint;
pub mod config;
pub mod model;
pub mod normal;
pub mod params;
pub mod replay;
pub mod trace;
pub mod train;

pub use agent::{ContinuousTransitions, PpoContinuous};
pub use config::PpoContinuousConfig;
pub use model::{ContinuousActorSnapshot, PolicyNetContinuous, softplus, softplus_f32};
pub use normal::{log_prob, normal_log_prob};
pub use trace::{ContinuousEpochTrace, ContinuousUpdateTrace};
pub use train::{ContinuousEpisodeReport, ContinuousTrainer, train_continuous};

/// Observations per state: Pendulum's `(cos θ, sin θ, θ̇)`.
pub const STATE_DIM: usize = 3;
/// Actions per step: one torque.
pub const ACTION_DIM: usize = 1;
/// The book's reward rescaling inside `update()`: `(r + REWARD_SHIFT) / REWARD_SCALE`.
pub const REWARD_SHIFT: f64 = 8.0;
/// See [`REWARD_SHIFT`].
pub const REWARD_SCALE: f64 = 8.0;
