pub fn gae_rollout(
    rewards: &[f32],
    values: &[f32],
    next_values: &[f32],
    terminated: &[bool],
    truncated: &[bool],
    gamma: f32,
    lmbda: f32,
) -> (Vec<f32>, Vec<f32>) {
    let n = rewards.len();
    let mut advantages = vec![0.0; n];
    let mut last = 0.0;
    for t in (0..n).rev() {
        let mut next_value = next_values[t];
        if terminated[t] {
            next_value = 0.0;
        }
        let delta = rewards[t] + gamma * next_value - values[t];
        if terminated[t] || truncated[t] {
            last = 0.0;
        }
        last = delta + gamma * lmbda * last;
        advantages[t] = last;
    }
    let returns = advantages.clone();
    (advantages, returns)
}
