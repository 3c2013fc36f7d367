pub fn td_target_truncation(
    rewards: &[f32],
    next_values: &[f32],
    final_values: &[f32],
    terminated: &[bool],
    truncated: &[bool],
    gamma: f32,
) -> Vec<f32> {
    // Every ended episode bootstraps from its real last observation, fallen or cut.
    let mut out = Vec::new();
    for t in 0..rewards.len() {
        let ended = terminated[t] || truncated[t];
        if ended {
            out.push(rewards[t] + gamma * final_values[t]);
        } else {
            out.push(rewards[t] + gamma * next_values[t]);
        }
    }
    out
}
