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
        let mut last = t;
        let mut ended = false;
        for k in 0..n {
            if t + k >= len {
                break;
            }
            total += g * rewards[t + k];
            g *= gamma;
            last = t + k;
            if dones[t + k] {
                ended = true;
                break;
            }
        }
        if !ended {
            // the value after the last reward taken
            total += g * values[last];
        }
        out.push(total);
    }
    out
}
