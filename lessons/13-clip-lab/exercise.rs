//! Lesson 13 exercise: measuring how far an update moved the policy, and stopping it in time.
//!
//! Grade: `ppo-tutor grade approx_kl` and `ppo-tutor grade kl_early_stop` (or `g` in the
//! tutor). Start over: `ppo-tutor reset approx_kl` (restores this whole file).

/// How far the policy has moved from the one that collected the batch, as one number.
///
/// Estimate the KL divergence KL(π_old ‖ π_θ) from the sampled actions only: the estimator
/// CleanRL logs as `approx_kl`, which is never negative row by row and unbiased because the
/// actions were drawn from π_old. Lesson 13 names it.
///
/// - `old_log_probs[i]` is `log π_old(a_i|s_i)`, fixed before the update; `log_probs[i]` is
///   `log π_θ(a_i|s_i)` under the current parameters. Same length, at least 1.
/// - Return the mean over the rows, in float32.
///
/// Taught in lesson 13 (clip-lab), step 1 "What to watch in every update".
pub fn approx_kl(old_log_probs: &[f32], log_probs: &[f32]) -> f32 {
    // TODO: which estimator is never negative row by row? (`h` reveals hints one by one.)
    todo!()
}

/// How many gradient steps an update takes under Spinning Up's early stopping.
///
/// The clip does not stop the policy drifting away from the one that collected the batch
/// (lesson 13, experiment 4). Spinning Up's PPO adds a guard: before each epoch's gradient
/// step it estimates how far the policy has moved, and if the estimate has passed its margin
/// above `target_kl` it ends the update there, without taking that step. Apply its rule, with
/// its estimator, to an update whose log-probabilities you are given epoch by epoch.
///
/// - `old_log_probs[i]` is `log π_old(a_i|s_i)`, fixed before the update; `N` rows, at
///   least 1.
/// - `log_probs_per_epoch` holds `E` rows of `N` numbers one after the other (row-major,
///   `E = log_probs_per_epoch.len() / N`, at least 1): row `e` is `log π(a_i|s_i)` under the
///   policy at the *start* of epoch `e`, before that epoch's step.
/// - `target_kl` is Spinning Up's `target_kl` (0.01 by default).
///
/// Return how many of the `E` epochs took their gradient step: `E` when the guard never
/// fires. The estimates are means over the rows, in float32.
///
/// Taught in lesson 13 (clip-lab), step 5 "Experiment 4: stopping early at a target KL".
pub fn kl_early_stop(old_log_probs: &[f32], log_probs_per_epoch: &[f32], target_kl: f32) -> usize {
    // TODO: your code here; `h` in the tutor reveals hints one by one.
    // Which estimate of the KL divergence does Spinning Up test, and what happens to the step
    // of the epoch where it is first too large?
    todo!()
}
