pub fn td_target_truncation(
    rewards: &[f32],
    next_values: &[f32],
    final_values: &[f32],
    terminated: &[bool],
    truncated: &[bool],
    gamma: f32,
) -> Vec<f32> {
    // Picks the value of what follows first (0 after a fall), then adds it in f64.
    let mut out = Vec::new();
    for t in 0..rewards.len() {
        let future = match (terminated[t], truncated[t]) {
            (true, _) => 0.0,
            (false, true) => final_values[t],
            (false, false) => next_values[t],
        };
        let target = f64::from(rewards[t]) + f64::from(gamma) * f64::from(future);
        out.push(target as f32);
    }
    out
}
