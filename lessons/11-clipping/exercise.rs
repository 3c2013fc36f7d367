//! Lesson 11 exercise: which rows the clipped objective has stopped pushing on.
//!
//! Grade: `ppo-tutor grade zero_gradient_rows` (or `g` in the tutor).
//! Start over: `ppo-tutor reset zero_gradient_rows`.

/// Which rows the clipped objective has stopped pushing on.
///
/// Each row contributes one term to the clipped surrogate PPO maximises,
/// `min(r·Â, clamp(r, 1 − ε, 1 + ε)·Â)` (the seed's actor loss is the mean of these terms,
/// sign flipped). Return, for each row, `true` when that term's
/// derivative with respect to the row's ratio is zero, so that the update no longer moves
/// the policy's probability of that row's action, and `false` when the gradient still flows.
///
/// - `ratio[i]` is `π_θ(a_i|s_i) / π_old(a_i|s_i)`, `advantage[i]` is `Â_i`, both the same
///   length; `eps` is the clip range ε. The result has one flag per row.
/// - Decide it from the sign of the advantage and where the ratio lies; do not differentiate
///   numerically.
/// - At exactly `r = 1 − ε` or `r = 1 + ε`, follow PyTorch: `clamp` passes the gradient at its
///   bounds. A row whose advantage is exactly 0 has nothing to push on.
///
/// Taught in lesson 11 (clipping), steps 4 and 5: "When the advantage is positive" and "When
/// the advantage is negative". Grade: `ppo-tutor grade zero_gradient_rows`.
pub fn zero_gradient_rows(ratio: &[f32], advantage: &[f32], eps: f32) -> Vec<bool> {
    // TODO: for a positive advantage, which side of the band stops the gradient? And for a
    // negative one?
    todo!()
}
