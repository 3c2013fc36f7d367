//! Lesson 10 exercise: how far apart two policies are.
//!
//! Grade: `ppo-tutor grade categorical_kl` (or `g` in the tutor).
//! Start over: `ppo-tutor reset categorical_kl`.

/// The exact KL divergence `KL(π_old(·|s) ‖ π_new(·|s))` between the old and the new policy,
/// one number per state.
///
/// Lesson 10 measured how far the new policy has moved from the old one with this
/// divergence, and PPO-Penalty adds it to the loss. Here you compute it exactly for a whole
/// batch of states, for any number of actions, including an old policy that never takes
/// some action.
///
/// - `old_probs` holds the old policy's probabilities, row-major: `N` rows of `n_actions`
///   entries, row `i` being `π_old(·|s_i)`. An entry may be exactly 0: an action the old
///   policy never takes in that state.
/// - `new_probs` holds the new policy's probabilities in the same layout; every entry is
///   positive (a softmax never gives exactly 0).
/// - Each row sums to 1. `n_actions` is 2 in CartPole; the grader uses 2 to 6.
///
/// Return `N` numbers, the divergence of each state (natural logarithm), in row order; no
/// rows give an empty vector. The result is never negative, and exactly 0 for a row where
/// the two policies agree. The grader compares to 1e-5 absolute and 1e-4 relative.
///
/// Taught in lesson 10 (trust-region), where PPO-Penalty's KL term is computed.
pub fn categorical_kl(old_probs: &[f32], new_probs: &[f32], n_actions: usize) -> Vec<f32> {
    // TODO: your code here; `h` in the tutor reveals hints one by one.
    // The divergence is an average of something over the actions: under which of the two
    // policies are the actions weighted, and what should an action that policy never takes
    // count for?
    todo!()
}
