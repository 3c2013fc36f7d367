//! # ppo-tutor
//!
//! Learn Proximal Policy Optimization by running it. The crate is an engine with faces:
//!
//! - [`env`](mod@env): a native CartPole-v1 and Pendulum-v1 identical to Gymnasium's (same states,
//!   bit for bit, same seeds).
//! - [`ppo`]: the seed's PPO (*Hands-on RL*, `task_PPO.py`) on candle, same numbers as PyTorch.
//! - [`plot`]: return curves in the terminal and as PNG/SVG figures (plotters).
//! - [`grade`]: graded exercises: the learner's plain-Rust PPO pieces against the references.
//! - [`lesson`]: the course as data (`lessons/`, embedded), code anchors, live values, progress.
//! - [`notebook`]: rich output for the Jupyter notebooks (evcxr): HTML tables, inline SVG;
//!   and the generator of the notebooks themselves (`ppo-tutor dev notebooks`).
//! - `tui`: the terminal app (ratatui), training on a worker thread.
//! - `cli`: the `ppo-tutor` command line (the binary only parses arguments and calls it).
//!
//! `tui` and `cli` (and grading on save) come with the default feature `app`. The notebooks
//! depend on the crate without it (`default-features = false`), which spares a fresh
//! Jupyter kernel compiling ratatui, crossterm, clap and the faces' code.
//!
//! The engine never imports a face; the terminal app, the notebooks and the graders all
//! drive the same engine.

#[cfg(feature = "app")]
pub mod cli;
pub mod env;
#[cfg(feature = "exercises")]
pub mod grade;
pub mod i18n;
pub mod lesson;
pub mod notebook;
pub mod plot;
pub mod ppo;
#[cfg(feature = "app")]
pub mod tui;

/// The candle-core ppo-tutor is built on, so a notebook cell can write the candle exercise
/// without a `:dep` of its own: `use ppo_tutor::candle_core::{Result, Tensor};`.
pub use candle_core;
/// The candle-nn ppo-tutor is built on (`ppo_tutor::candle_nn::ops::log_softmax`, ...), for
/// the same reason.
pub use candle_nn;
