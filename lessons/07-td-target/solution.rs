//! Reference solution for lesson 07: the seed's
//! `td_target = rewards + self.gamma * self.critic(next_states) * (1 - dones)` and
//! `td_delta = td_target - self.critic(states)`, row by row.

/// `td_target[i] = rewards[i] + gamma * next_values[i] * (1 - dones[i])`.
pub fn td_target(rewards: &[f32], next_values: &[f32], dones: &[bool], gamma: f32) -> Vec<f32> {
    rewards
        .iter()
        .zip(next_values)
        .zip(dones)
        .map(|((&r, &v), &done)| {
            let not_done = if done { 0.0 } else { 1.0 };
            r + gamma * v * not_done
        })
        .collect()
}

/// `td_delta[i] = td_target[i] - values[i]`: how much better the step went than the critic
/// predicted.
pub fn td_delta(td_target: &[f32], values: &[f32]) -> Vec<f32> {
    td_target.iter().zip(values).map(|(t, v)| t - v).collect()
}
