//! Lesson 03 exercise: sample an action from the policy's probabilities.
//!
//! Grade: `ppo-tutor grade sample_action` (or `g` in the tutor).
//! Start over: `ppo-tutor reset sample_action`.

/// Draws one action from the policy, as the seed's `Categorical(probs).sample()` does.
///
/// The agent does not always take its most probable action: it samples. An action of
/// probability p is taken a fraction p of the time, and this is how the agent explores. Here
/// the randomness comes in from outside, as one number `u`, so the same `u` always gives the
/// same action.
///
/// - `probs[i]` is the policy's probability of action `i`. CartPole has two actions (0 pushes
///   left, 1 pushes right); the grader also tries three to five. They are non-negative and
///   sum to 1, up to f32 rounding.
/// - `u` is a uniform random number in `[0, 1)`.
///
/// Return an index into `probs`. Which action a given `u` picks must match the seed: the
/// smallest values of `u` go to action 0, the next ones to action 1, and so on in index
/// order, each action getting a share `probs[i]` of `[0, 1)`. Two edge cases matter: while `u`
/// is below the probabilities' sum, an action of probability 0 is never returned, not even when
/// `u` lands exactly on its boundary; and if rounding leaves that sum a hair less than `u`, no
/// piece is left for `u`: return the last action, whatever its probability.
///
/// Taught in lesson 3 (episode-loop), step 2 "take_action: sampling, not choosing the best".
pub fn sample_action(probs: &[f32], u: f32) -> usize {
    // TODO: your code here; `h` in the tutor reveals hints one by one.
    // Picture [0, 1) as a ruler: which stretch of it belongs to each action?
    todo!()
}
