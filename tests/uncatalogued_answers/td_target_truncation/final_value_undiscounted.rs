pub fn td_target_truncation(
    rewards: &[f32],
    next_values: &[f32],
    final_values: &[f32],
    terminated: &[bool],
    truncated: &[bool],
    gamma: f32,
) -> Vec<f32> {
    // Right choice of value on every row, but the real last observation's value is added
    // without its discount.
    let mut out = Vec::new();
    for t in 0..rewards.len() {
        if terminated[t] {
            out.push(rewards[t]);
        } else if truncated[t] {
            out.push(rewards[t] + final_values[t]);
        } else {
            out.push(rewards[t] + gamma * next_values[t]);
        }
    }
    out
}
