//! Lesson 10 exercise: how far apart two policies are, from what their networks output.
//!
//! Grade: `ppo-tutor grade categorical_kl` (or `g` in the tutor).
//! Start over: `ppo-tutor reset categorical_kl`.

/// The exact KL divergence `KL(π_old(·|s) ‖ π_new(·|s))` between the old and the new policy,
/// one number per state, computed from the two policies' logits.
///
/// Lesson 10 measured how far the new policy has moved from the old one with this
/// divergence, from the two policies' probabilities. A policy network does not output
/// probabilities: it outputs logits, one unconstrained number per action, and the policy is
/// their softmax. In a game, an action that is illegal in a state is masked: its logit is
/// `f32::NEG_INFINITY`, so the policy gives it probability 0. Here you compute the KL from
/// the logits, for a whole batch of states.
///
/// - `old_logits` holds the old policy's logits, row-major: `N` rows of `n_actions` entries,
///   row `i` being state `s_i`'s. `new_logits` holds the new policy's in the same layout.
///   `n_actions` is 2 in CartPole; the grader uses 2 to 6.
/// - An entry is a finite number or `f32::NEG_INFINITY` (a masked action). Each row of each
///   table has at least one finite entry. The logits are defined up to a constant: adding
///   the same number to every logit of a row does not change the policy.
///
/// Return `N` numbers, the divergence of each state (natural logarithm), in row order; no
/// rows give an empty vector. The result must be:
/// - exact where the logits are large, such as 100 or 1000, where `exp` of a logit
///   overflows `f32` to infinity, and where a probability is so small that it rounds to 0
///   in `f32` without its action being masked: no NaN, and no infinity;
/// - exactly 0 for a row where the two policies agree, including logits that differ by a
///   constant;
/// - free of NaN where the old policy masks an action, whatever logit the new policy gives
///   that action: the old policy never takes it, so its own term is 0;
/// - `f32::INFINITY` for a row where the new policy masks an action the old policy can
///   take, as PyTorch's `kl_divergence` returns.
///
/// The grader compares to 1e-5 absolute and 1e-4 relative (an infinity must be an
/// infinity), on 100 seeded random batches (some with the same actions masked in both
/// policies), on rows with masks in the old policy only and in the new policy only, rows
/// that agree, large logits, recorded PyTorch results, and no rows.
///
/// Taught in lesson 10 (trust-region), step "How far is far: the KL between two policies".
pub fn categorical_kl(old_logits: &[f32], new_logits: &[f32], n_actions: usize) -> Vec<f32> {
    // TODO: your code here; `h` in the tutor reveals hints one by one.
    // The divergence is an average over the actions, weighted by one of the two policies:
    // first turn each row of logits into what that average needs, without letting `exp`
    // overflow; then decide what a masked action counts for on each side.
    todo!()
}
