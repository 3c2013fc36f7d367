//! Lesson 09 exercise: what the importance ratio is for.
//!
//! Grade: `ppo-tutor grade importance_weighted_mean` (or `g` in the tutor).
//! Start over: `ppo-tutor reset importance_weighted_mean`.

/// The mean return when the *new* policy chooses one action and the *old* one plays on,
/// estimated from steps the *old* policy played.
///
/// The old policy visited some states and, in each, drew an action from its own
/// probabilities; you observed the return that followed. The new policy would pick those
/// same actions more or less often. Averaging the returns as they are answers for the old
/// policy. Use the importance ratio of lesson 9 to correct the average, so that it estimates
/// the mean return on these states when the new policy chooses the sample's action and the
/// old policy plays every step after it. (One ratio corrects one choice: the states stay
/// those the old policy visited, and so do the later actions, whose returns are in the
/// observed one. That is why lesson 10 asks how far from the old policy this estimate can
/// be trusted.)
///
/// - `probs` holds the new policy's probabilities, row-major: `N` rows of `n_actions`
///   entries, row `i` being `π_new(·|s_i)` for the state of sample `i`. `n_actions` is 2 in
///   CartPole; the grader also uses up to 6.
/// - `actions[i]` is the action the old policy took in sample `i`, in `0..n_actions`.
/// - `old_log_probs[i]` is `log π_old(a_i|s_i)`, the old policy's log-probability of that
///   action (natural logarithm), as the seed records it.
/// - `returns[i]` is the return observed after sample `i`'s action.
///
/// `actions`, `old_log_probs` and `returns` have the same length `N >= 1`, and `probs` has
/// `N * n_actions` entries. Return a single number. When the new policy equals the old one,
/// the answer is the plain mean of the returns. The grader tries rare actions (a small old
/// probability) and compares to 1e-5 absolute and 1e-4 relative.
///
/// Taught in lesson 9 (ratio), step 1 "Log-probability of the action taken" and step 3
/// "The ratio".
pub fn importance_weighted_mean(
    probs: &[f32],
    n_actions: usize,
    actions: &[usize],
    old_log_probs: &[f32],
    returns: &[f32],
) -> f32 {
    // TODO: your code here; `h` in the tutor reveals hints one by one.
    // An action the old policy took rarely but the new one likes: should its return count
    // for more or for less than the others in your average?
    todo!()
}
