//! # ppo-engine
//!
//! The engine under ppo-tutor's three faces (the terminal app, the notebooks and the graded
//! exercises): the course on its RL core, and nothing that draws a terminal, parses a
//! command line or grades a learner's file. The RL core is its own crate, `ppo-rl` (the
//! environments, the agents, training, checkpoints, replay), re-exported here under the same
//! paths, so a notebook's `:dep ppo-engine` reaches both; the two languages are the leaf
//! crate `ppo-i18n`.
//!
//! - [`env`](mod@env): a native CartPole-v1 and Pendulum-v1 identical to Gymnasium's (same
//!   states, bit for bit, same seeds).
//! - [`ppo`]: the agents behind one abstraction, [`ppo::OnPolicyAgent`]: the seed's
//!   PPO (*Hands-on RL*, `task_PPO.py`) and REINFORCE on CartPole, the book's
//!   `PPOContinuous` on Pendulum, all on candle with the same numbers as PyTorch.
//! - [`plot`]: return curves in the terminal and as PNG/SVG figures (plotters).
//! - [`lesson`]: the course as data (`lessons/`, embedded), code anchors, quizzes, the live
//!   session that turns a training run into the numbers every face shows, and progress.
//! - [`notebook`]: what the Jupyter notebooks' cells call (evcxr): snapshots, HTML tables,
//!   inline SVG, the lab. A notebook depends on this crate alone
//!   (`:dep ppo-engine = { path = "../crates/ppo-engine" }`), plus `ppo-grade` where its
//!   lesson has exercises.
//! - [`run`]: the configuration of a run, the one place that matches on the environment.
//! - [`i18n`]: the language of what is printed for people (English or Simplified Chinese).
//!
//! The engine never imports a face: the terminal app, the notebooks and the graders all
//! drive the same engine.

pub mod lesson;
pub mod notebook;
pub mod plot;
pub mod ppo;
pub mod run;

/// The language of what is printed, from the leaf crate `ppo-i18n`.
pub use ppo_i18n::{causes, i18n, text, tr};
/// The environments, from the RL core.
pub use ppo_rl::env;
/// Writing a file atomically, from the RL core.
pub use ppo_rl::files;
/// Statistics over seeds (the RL core's): IQM, bootstrap intervals, paired comparisons.
pub use ppo_rl::stats;

/// The candle-core the engine is built on, so a notebook cell can write the candle exercise
/// without a `:dep` of its own: `use ppo_engine::candle_core::{Result, Tensor};`.
pub use candle_core;
/// The candle-nn the engine is built on (`ppo_engine::candle_nn::ops::log_softmax`, ...),
/// for the same reason.
pub use candle_nn;
