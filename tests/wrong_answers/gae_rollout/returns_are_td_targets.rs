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
    let mut returns = vec![0.0; n];
    for t in (0..n).rev() {
        let mut next_value = next_values[t];
        if terminated[t] {
            next_value = 0.0;
        }
        let target = rewards[t] + gamma * next_value;
        let delta = target - values[t];
        if terminated[t] || truncated[t] {
            last = 0.0;
        }
        last = delta + gamma * lmbda * last;
        advantages[t] = last;
        returns[t] = target;
    }
    (advantages, returns)
}
