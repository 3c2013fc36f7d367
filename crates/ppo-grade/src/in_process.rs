//! Grading a function that lives in the running program: a notebook cell.
//!
//! The notebooks cannot hand the grader a file (a cell's text is not visible to the code it
//! defines), so the learner passes the function itself: `grade::in_process::reverse_kl(reverse_kl)`.
//! It runs on exactly the cases of `ppo-tutor grade`, is compared with the same reference
//! and tolerance by the same judge, and a failure gets the same diagnosis and hint; only the
//! compile step is the notebook's own. Each case runs on a worker thread: a panic is caught
//! and reported with its message, and a function that has not answered within the time
//! limit is reported as never returning (the thread is left behind; in a notebook, restart
//! the kernel to stop it). What the function prints (`println!`, `dbg!`) goes where the
//! notebook's prints go, the cell's output, once per case it runs on: the report does not
//! repeat it (a file graded by `ppo-tutor grade` shows a few lines beside each case
//! instead), and a cell that starts a function still `todo!()` reports it as not started
//! from its first panic.
//!
//! The candle exercise is graded the same way: `grade::in_process::ppo_losses(ppo_losses)`
//! runs the checks of `ppo-tutor grade ppo_losses` (losses and gradients, then CartPole
//! trained with the function) on the function itself, with a time limit on each call.
//!
//! ```
//! use ppo_grade::in_process;
//!
//! fn reverse_kl(old_log_probs: &[f32], log_probs: &[f32]) -> f32 {
//!     let rows = old_log_probs.iter().zip(log_probs);
//!     let total: f32 = rows.map(|(o, l)| (l - o).exp() * (l - o - 1.0) + 1.0).sum();
//!     total / old_log_probs.len() as f32
//! }
//! let report = in_process::reverse_kl(reverse_kl);
//! assert!(report.passed(), "{}", report.render());
//! ```

/// Every exercise's in-place grader, by the exercise's name (from the registry).
// Empty when no lesson feature is enabled (`exercises` alone: the graders, no exercise).
#[allow(unused_imports)]
pub use super::exercises::in_place::*;
/// The name a report gives to the graded code.
pub use super::learner::IN_PLACE as DISPLAY;
/// How long the learner's function may take: on all cases together (plain exercises), or
/// on each call (the candle exercise).
pub use super::learner::IN_PLACE_LIMIT as TIME_LIMIT;
