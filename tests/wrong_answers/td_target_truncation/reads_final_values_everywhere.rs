pub fn td_target_truncation(
    rewards: &[f32],
    next_values: &[f32],
    final_values: &[f32],
    terminated: &[bool],
    truncated: &[bool],
    gamma: f32,
) -> Vec<f32> {
    // The flags as 0/1 factors, so every row reads both values.
    let mut out = Vec::new();
    for t in 0..rewards.len() {
        let term = if terminated[t] { 1.0 } else { 0.0 };
        let trunc = if truncated[t] { 1.0 } else { 0.0 };
        let future = (1.0 - trunc) * next_values[t] + trunc * final_values[t];
        out.push(rewards[t] + gamma * (1.0 - term) * future);
    }
    out
}
