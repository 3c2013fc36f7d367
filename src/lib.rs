//! # ppo-tutor
//!
//! Learn Proximal Policy Optimization by running it. This crate is the terminal app and the
//! command line, built on two library crates of the workspace (`crates/`):
//!
//! - `ppo-engine` (re-exported here as [`env`](mod@env), [`ppo`], [`plot`], [`lesson`],
//!   [`i18n`] and [`notebook`]): the environments, the agents, the course, its live session
//!   and what the notebooks' cells call. A notebook compiles only this crate.
//! - `ppo-grade` (re-exported as [`grade`]): the graded exercises and the pipeline that
//!   builds a learner's file.
//! - [`generator`]: the notebooks' generator (`ppo-tutor dev notebooks`), which no notebook
//!   compiles.
//! - [`tui`]: the terminal app (ratatui), training on a worker thread; [`watch`]: grading
//!   on save.
//! - [`cli`]: the `ppo-tutor` command line (the binary only parses arguments and calls it).
//! - [`screenshot`]: the README's pictures, the app's own screens painted to PNG
//!   (`ppo-tutor dev screenshots`).
//!
//! The engine never imports a face; the terminal app, the notebooks and the graders all
//! drive the same engine.

pub mod cli;
pub mod generator;
pub mod screenshot;
pub mod tui;
pub mod watch;

#[doc(hidden)]
pub use ppo_engine::tr;
pub use ppo_engine::{candle_core, candle_nn, env, i18n, lesson, notebook, plot, ppo, run, stats};
pub use ppo_grade as grade;
