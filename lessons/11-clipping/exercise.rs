//! Lesson 11 exercise: which rows dual-clip PPO's objective has stopped pushing on.
//!
//! Grade: `ppo-tutor grade zero_gradient_rows` (or `g` in the tutor).
//! Start over: `ppo-tutor reset zero_gradient_rows`.

/// Which rows dual-clip PPO's objective has stopped pushing on.
///
/// The seed's agent, and every live step of lesson 11, use PPO's plain clip. This exercise
/// asks about a variant the lesson does not show: dual-clip PPO (Ye et al. 2020, "Mastering
/// Complex Control in MOBA Games with Deep Reinforcement Learning"), which adds a second
/// bound for rows with a negative advantage, so that a huge ratio cannot make a row's loss
/// arbitrarily large. The term each row contributes to the objective it maximises is
///
/// - for Â ≥ 0, PPO's usual `min(r·Â, clamp(r, 1 − ε, 1 + ε)·Â)`;
/// - for Â < 0, `max(min(r·Â, clamp(r, 1 − ε, 1 + ε)·Â), c·Â)`, with a constant `c > 1`
///   (3 in the paper).
///
/// Return, for each row, `true` when that term's derivative with respect to the row's ratio
/// is zero, so that the row's own term no longer pushes on the probability of its action
/// (other rows, through the shared weights, may still move it), and `false` when the
/// gradient still flows.
///
/// - `ratio[i]` is `π_θ(a_i|s_i) / π_old(a_i|s_i)`, `advantage[i]` is `Â_i`, both the same
///   length; `eps` is the clip range ε and `c` the dual clip's constant. The result has one
///   flag per row.
/// - Decide it from the sign of the advantage and where the ratio lies; do not differentiate
///   numerically.
/// - Follow PyTorch's autograd at the boundaries: at exactly `r = 1 − ε` or `r = 1 + ε`,
///   `clamp` passes the gradient (its derivative is 1 on the closed interval); where the two
///   arguments of `torch.max` are equal, each gets half the gradient. A row whose advantage
///   is exactly 0 has nothing to push on.
///
/// Pass bar: every flag equal to the reference's, on 100 seeded random batches (ε from 0.05
/// to 0.4, c from 1.5 to 4, ratios from 0.4 to 2c + 1, about one advantage in ten exactly
/// 0), on the recorded PyTorch batches (their ε, c = 3), and on edge cases: each side of the
/// band and of c for each sign, a zero advantage, and ratios exactly at 1 − ε, 1 + ε and c
/// (ε a multiple of 1/8 and c of 1/2 there: exact in f32). Every case has c > 1 + ε.
///
/// Taught in lesson 11 (clipping), steps 4 and 5: "When the advantage is positive" and "When
/// the advantage is negative"; here the same reasoning meets one more term. Grade:
/// `ppo-tutor grade zero_gradient_rows`.
pub fn zero_gradient_rows(ratio: &[f32], advantage: &[f32], eps: f32, c: f32) -> Vec<bool> {
    // TODO: for each sign of the advantage and each range of the ratio, which term does the
    // objective pick, and does that term move when r moves?
    todo!()
}
