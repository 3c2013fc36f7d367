//! Lesson 09 exercise: log-probabilities of the actions taken, and the ratio.
//!
//! Grade: `ppo-tutor grade log_prob_of_actions` and `ppo-tutor grade ratio` (or `g` in the
//! tutor). Start over: `ppo-tutor reset ratio` (restores this whole file).

/// The log-probability of the action actually taken on each step, under the policy that
/// produced `probs`. The ratio below, and with it PPO's loss, is built from these numbers.
/// Computed once before the epochs, they are the seed's `old_log_probs`; inside the epochs,
/// its `log_probs`.
///
/// - `probs[i]` is `π(·|s_i)`, the actor's output for state `s_i`: the probabilities of
///   CartPole's two actions, 0 (push left) and 1 (push right).
/// - `actions[i]` is the action taken on step `i`, 0 or 1.
///
/// Both slices have the same length, at least one. Return one value per row, in the same
/// order. Every value is at most 0, since a probability is at most 1. "Log" means the natural
/// logarithm here, as in PyTorch. The grader includes near-certain and near-impossible actions
/// and compares in f32, to about 1e-5.
///
/// Taught in lesson 9 (ratio), step 1 "Log-probability of the action taken".
pub fn log_prob_of_actions(probs: &[[f32; 2]], actions: &[usize]) -> Vec<f32> {
    // TODO: your code here; `h` in the tutor reveals hints one by one.
    // Each row holds two probabilities: which one belongs to this step?
    todo!()
}

/// The importance ratio of each step: how much more likely (above 1) or less likely (below 1)
/// the current policy makes the action taken than the old policy that played the episode did.
/// A ratio of exactly 1 means no change for that row. PPO's clip works on this number
/// (lesson 10).
///
/// - `log_probs[i]` is `log π_θ(a_i|s_i)`, the current policy's log-probability of the action
///   taken on step `i`.
/// - `old_log_probs[i]` is `log π_θ_old(a_i|s_i)`, the same for the policy that played the
///   episode; it stays fixed during the epochs.
///
/// Both slices have the same length, at least one. Return one ratio per row, in the same
/// order; every ratio is positive. In the first epoch the two inputs are identical, and then
/// every ratio must come out as 1. The grader compares in f32, to about 1e-5.
///
/// Taught in lesson 9 (ratio), step 3 "The ratio".
pub fn ratio(log_probs: &[f32], old_log_probs: &[f32]) -> Vec<f32> {
    // TODO: your code here. You are given logarithms, but the ratio is between
    // probabilities: what does a difference of two logarithms say about their numbers?
    todo!()
}
