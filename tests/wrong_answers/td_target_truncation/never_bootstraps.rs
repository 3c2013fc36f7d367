pub fn td_target_truncation(
    rewards: &[f32],
    next_values: &[f32],
    terminated: &[bool],
    truncated: &[bool],
    gamma: f32,
) -> Vec<f32> {
    let mut out = Vec::new();
    for t in 0..rewards.len() {
        out.push(rewards[t]);
    }
    out
}
