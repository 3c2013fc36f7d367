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
        let m = if t + n > len { len - t } else { n };
        let mut total = 0.0;
        let mut g = 1.0;
        for k in 0..m {
            total += g * rewards[t + k];
            g *= gamma;
        }
        // the (1 - done) mask of the TD target, on the last step of the window
        let last_done = if dones[t + m - 1] { 1.0 } else { 0.0 };
        total += g * values[t + m] * (1.0 - last_done);
        out.push(total);
    }
    out
}
