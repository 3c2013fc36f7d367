//! Lesson 10 exercise: PPO's clipped surrogate loss.
//!
//! Grade: `ppo-tutor grade actor_loss` (or `g` in the tutor).
//! Start over: `ppo-tutor reset actor_loss`.

/// PPO's actor loss: the one number the optimizer minimises to improve the policy, the
/// seed's `actor_loss`.
///
/// It rewards making actions with a positive advantage more likely and actions with a
/// negative advantage less likely, but only up to a band around a ratio of 1, `[1 − ε, 1 + ε]`.
/// Once a row's ratio has left the band in the direction its advantage wants, that row earns
/// no further credit. A row that moved the wrong way keeps its full penalty: the objective is
/// pessimistic.
///
/// - `ratio[i]` is `π_θ(a_i|s_i) / π_old(a_i|s_i)` (lesson 9): above 1 when the current
///   policy makes the action taken more likely than the policy that played it.
/// - `advantage[i]` is `Â_i`, how much better the action of step `i` turned out than
///   expected (lesson 8); either sign.
/// - `eps` is the clip range ε (0.2 in the seed).
///
/// Both slices have the same length, at least one. Return a single number. PPO maximises its
/// objective while the optimizer minimises, so mind the sign: a better policy gives a lower
/// loss. Like the seed's, the loss must not grow with the number of rows. The grader tries a
/// single step, only negative advantages and ratios outside the band, and compares to 1e-5
/// absolute and 1e-4 relative.
///
/// Taught in lesson 10 (clipping), step 3 "Taking the minimum", after step 1 "Two
/// surrogates" and step 2 on the band around 1.
pub fn actor_loss(ratio: &[f32], advantage: &[f32], eps: f32) -> f32 {
    // TODO: your code here; `h` in the tutor reveals hints one by one.
    // A row with a positive advantage has a ratio of 1.5: how much credit should it get?
    todo!()
}

/// Which rows the clipped objective has stopped pushing on.
///
/// Each row contributes one term to the clipped surrogate PPO maximises (the term your
/// `actor_loss` averages, sign flipped). Return, for each row, `true` when that term's
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
/// Taught in lesson 10 (clipping), steps 4 and 5: "When the advantage is positive" and "When
/// the advantage is negative". Grade: `ppo-tutor grade zero_gradient_rows`.
pub fn zero_gradient_rows(ratio: &[f32], advantage: &[f32], eps: f32) -> Vec<bool> {
    // TODO: for a positive advantage, which side of the band stops the gradient? And for a
    // negative one?
    todo!()
}
