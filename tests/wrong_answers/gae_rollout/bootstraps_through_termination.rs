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
        let delta = rewards[t] + gamma * next_values[t] - values[t];
        if terminated[t] || truncated[t] {
            last = 0.0;
        }
        last = delta + gamma * lmbda * last;
        advantages[t] = last;
    }
    let mut returns = vec![0.0; n];
    for t in 0..n {
        returns[t] = advantages[t] + values[t];
    }
    (advantages, returns)
}
