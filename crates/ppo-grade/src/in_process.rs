//! Grading a function that lives in the running program: a notebook cell.
//!
//! The notebooks cannot hand the grader a file (a cell's text is not visible to the code it
//! defines), so the learner passes the function itself: `grade::in_process::td_target(td_target)`.
//! It runs on exactly the cases of `ppo-tutor grade`, is compared with the same reference
//! and tolerance by the same judge, and a failure gets the same diagnosis and hint; only the
//! compile step is the notebook's own. Each case runs on a worker thread: a panic is caught
//! and reported with its message, and a function that has not answered within the time
//! limit is reported as never returning (the thread is left behind; in a notebook, restart
//! the kernel to stop it).
//!
//! The candle exercise is graded the same way: `grade::in_process::ppo_losses(ppo_losses)`
//! runs the checks of `ppo-tutor grade ppo_losses` (losses and gradients, then CartPole
//! trained with the function) on the function itself, with a time limit on each call.
//!
//! ```
//! use ppo_grade::in_process;
//!
//! fn critic_loss(values: &[f32], td_target: &[f32]) -> f32 {
//!     let n = values.len() as f32;
//!     values.iter().zip(td_target).map(|(v, y)| (v - y) * (v - y)).sum::<f32>() / n
//! }
//! let report = in_process::critic_loss(critic_loss);
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
