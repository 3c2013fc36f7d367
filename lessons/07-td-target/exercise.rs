//! Lesson 07 exercise: the TD target and the TD error, one value per transition.
//!
//! Grade: `ppo-tutor grade td_target` and `ppo-tutor grade td_delta` (or `g` in the tutor).
//! Start over: `ppo-tutor reset td_target` (restores this whole file).

/// The seed's `td_target = rewards + self.gamma * self.critic(next_states) * (1 - dones)`,
/// where `next_values[i]` is `V(s_{i+1})`.
pub fn td_target(rewards: &[f32], next_values: &[f32], dones: &[bool], gamma: f32) -> Vec<f32> {
    // TODO: for each row i, the reward now plus the discounted value of the next state,
    // except that a finished episode (dones[i] true) has no next state worth anything.
    todo!()
}

/// The seed's `td_delta = td_target - self.critic(states)`, where `values[i]` is `V(s_i)`.
pub fn td_delta(td_target: &[f32], values: &[f32]) -> Vec<f32> {
    // TODO: for each row i, how much better the step went than the critic predicted.
    todo!()
}
