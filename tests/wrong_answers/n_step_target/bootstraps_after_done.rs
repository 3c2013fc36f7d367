pub fn n_step_target(
    rewards: &[f32],
    values: &[f32],
    dones: &[bool],
    gamma: f32,
    n: usize,
) -> Vec<f32> {
    let len = rewards.len();
    let mut out = Vec::new();
    for t in 0..len {
        let mut total = 0.0;
        let mut g = 1.0;
        let mut k = 0;
        while k < n && t + k < len {
            total += g * rewards[t + k];
            g *= gamma;
            k += 1;
            if dones[t + k - 1] {
                break;
            }
        }
        total += g * values[t + k];
        out.push(total);
    }
    out
}
