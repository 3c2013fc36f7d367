//! Lesson 11 exercise: the critic's loss.
//!
//! Grade: `ppo-tutor grade critic_loss` (or `g` in the tutor).
//! Start over: `ppo-tutor reset critic_loss`.

/// The critic's loss: one number that says how far the critic's predictions are from their
/// TD targets over the whole episode. The critic learns by regression, and minimising this
/// number moves each prediction `V(s_i)` towards its target. It is the seed's `critic_loss`.
///
/// - `values[i]` is the critic's prediction `V(s_i)` for the state of step `i`.
/// - `td_target[i]` is the TD target of step `i` (lesson 7), a fixed number here: only the
///   prediction depends on the critic's weights.
///
/// Both slices have the same length, at least one. Return a single number: 0 when every
/// prediction hits its target, larger the further off they are, and not growing with the
/// number of rows. Use the same loss as the seed: the grader checks its exact scale, with
/// errors of both signs and a single step, to 1e-5 absolute and 1e-4 relative.
///
/// Taught in lesson 11 (losses), step 2 "The critic loss".
pub fn critic_loss(values: &[f32], td_target: &[f32]) -> f32 {
    // TODO: your code here; `h` in the tutor reveals hints one by one.
    // Should a miss of −2 cost as much as a miss of +2? And more than a miss of 1?
    todo!()
}
