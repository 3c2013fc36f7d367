pub fn td_target_truncation(
    rewards: &[f32],
    next_values: &[f32],
    final_values: &[f32],
    terminated: &[bool],
    truncated: &[bool],
    gamma: f32,
) -> Vec<f32> {
    // Lesson 16's fix as printed: mask with terminated only, bootstrap from the observation
    // the environment returned, even when that is already the next episode's first one.
    let mut out = Vec::new();
    for t in 0..rewards.len() {
        if terminated[t] {
            out.push(rewards[t]);
        } else {
            out.push(rewards[t] + gamma * next_values[t]);
        }
    }
    out
}
