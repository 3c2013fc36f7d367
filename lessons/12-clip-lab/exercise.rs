//! Lesson 12 exercise: the two numbers CleanRL logs to watch an update, computed from the
//! batch yourself.
//!
//! Grade: `ppo-tutor grade approx_kl` and `ppo-tutor grade clip_fraction` (or `g` in the
//! tutor). Start over: `ppo-tutor reset approx_kl` (restores this whole file).

/// How far the policy has moved from the one that collected the batch, as one number.
///
/// Estimate the KL divergence KL(π_old ‖ π_θ) from the sampled actions only: the estimator
/// CleanRL logs as `approx_kl`, which is never negative row by row and unbiased because the
/// actions were drawn from π_old. Lesson 12 names it.
///
/// - `old_log_probs[i]` is `log π_old(a_i|s_i)`, fixed before the update; `log_probs[i]` is
///   `log π_θ(a_i|s_i)` under the current parameters. Same length, at least 1.
/// - Return the mean over the rows, in float32.
///
/// Taught in lesson 12 (clip-lab), step 1 "What to watch in every update".
pub fn approx_kl(old_log_probs: &[f32], log_probs: &[f32]) -> f32 {
    // TODO: which estimator is never negative row by row? (`h` reveals hints one by one.)
    todo!()
}

/// How much of the batch the clip is acting on: CleanRL's `clipfracs`.
///
/// - `ratio[i]` is `π_θ(a_i|s_i) / π_old(a_i|s_i)`, at least one row; `eps` is the clip
///   range ε.
/// - Return the share of rows (between 0 and 1) whose ratio is further than ε from 1,
///   measured as CleanRL measures it, in float32.
///
/// Taught in lesson 12 (clip-lab), step 1 "What to watch in every update", and lesson 10
/// (clipping), step 6 "How much is being clipped".
pub fn clip_fraction(ratio: &[f32], eps: f32) -> f32 {
    // TODO: your code here.
    todo!()
}
