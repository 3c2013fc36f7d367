//! # ppo-rl
//!
//! ppo-tutor's reinforcement-learning core: what runs, and nothing of the course that
//! teaches it (no lessons, quizzes, progress, snapshots, knobs, plots or notebook output).
//!
//! - [`env`](mod@env): a native CartPole-v1 and Pendulum-v1 identical to Gymnasium's (same
//!   states, bit for bit, same seeds), and their vector forms.
//! - [`ppo`]: the agents behind one abstraction, [`ppo::OnPolicyAgent`]: the seed's PPO
//!   (*Hands-on RL*, `task_PPO.py`) and REINFORCE on CartPole, the book's `PPOContinuous` on
//!   Pendulum, all on candle with the same numbers as PyTorch; training, seeds,
//!   checkpoints and the replay of recorded PyTorch updates.
//! - [`files`]: writing a file atomically.
//!
//! The course crate (`ppo-engine`) builds on this one and re-exports it under the same
//! paths (`ppo_rl::env`, `ppo_rl::ppo`); nothing here imports the course.
//! Messages are worded in the current language by the leaf crate `ppo-i18n`.

pub mod env;
pub mod files;
pub mod ppo;
pub mod stats;

pub(crate) use ppo_i18n::{causes, i18n, tr};

/// The candle-core the core is built on.
pub use candle_core;
/// The candle-nn the core is built on.
pub use candle_nn;
