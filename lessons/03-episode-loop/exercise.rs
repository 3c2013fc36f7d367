//! Lesson 03 exercise: sample an action from the policy's probabilities.
//!
//! Grade: `ppo-tutor grade sample_action` (or `g` in the tutor).
//! Start over: `ppo-tutor reset sample_action`.

/// The seed's `torch.distributions.Categorical(probs).sample()`, given the uniform random
/// number `u` in `[0, 1)` that the sampler draws.
pub fn sample_action(probs: &[f32], u: f32) -> usize {
    // TODO: cut [0, 1) into consecutive pieces, one per action, of lengths probs[0],
    // probs[1], ... and return the index of the piece that `u` falls in (the inverse CDF).
    // If rounding makes the probabilities sum to a hair less than `u`, return the last action.
    todo!()
}
