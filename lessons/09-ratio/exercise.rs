//! Lesson 09 exercise: log-probabilities of the actions taken, and the ratio.
//!
//! Grade: `ppo-tutor grade log_prob_of_actions` and `ppo-tutor grade ratio` (or `g` in the
//! tutor). Start over: `ppo-tutor reset ratio` (restores this whole file).

/// The seed's `torch.log(self.actor(states).gather(1, actions))`: `probs[i]` is `π(·|s_i)`
/// over CartPole's two actions and `actions[i]` the action taken.
pub fn log_prob_of_actions(probs: &[[f32; 2]], actions: &[usize]) -> Vec<f32> {
    // TODO: for each row, pick the probability of the action taken (gather), then take its
    // natural logarithm.
    todo!()
}

/// The seed's `ratio = torch.exp(log_probs - old_log_probs)`: `π(a|s) / π_old(a|s)` per row.
pub fn ratio(log_probs: &[f32], old_log_probs: &[f32]) -> Vec<f32> {
    // TODO: turn the two log-probabilities of each row into the ratio of the new policy's
    // probability to the old one's.
    todo!()
}
