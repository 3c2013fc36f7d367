pub fn td_target_truncation(
    rewards: &[f32],
    next_values: &[f32],
    final_values: &[f32],
    terminated: &[bool],
    truncated: &[bool],
    gamma: f32,
) -> Vec<f32> {
    // The seed's done = term or trunc: no bootstrap after either end.
    let mut out = Vec::new();
    for t in 0..rewards.len() {
        if terminated[t] || truncated[t] {
            out.push(rewards[t]);
        } else {
            out.push(rewards[t] + gamma * next_values[t]);
        }
    }
    out
}
