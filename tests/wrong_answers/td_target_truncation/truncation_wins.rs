pub fn td_target_truncation(
    rewards: &[f32],
    next_values: &[f32],
    final_values: &[f32],
    terminated: &[bool],
    truncated: &[bool],
    gamma: f32,
) -> Vec<f32> {
    // Asks about the time limit first, so a row with both flags bootstraps.
    let mut out = Vec::new();
    for t in 0..rewards.len() {
        if truncated[t] {
            out.push(rewards[t] + gamma * final_values[t]);
        } else if terminated[t] {
            out.push(rewards[t]);
        } else {
            out.push(rewards[t] + gamma * next_values[t]);
        }
    }
    out
}
