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
        let mut sum = 0.0;
        let mut steps = 0;
        let mut ended = false;
        while steps < n && t + steps < len {
            sum += rewards[t + steps];
            steps += 1;
            if dones[t + steps - 1] {
                ended = true;
                break;
            }
        }
        if !ended {
            sum += gamma.powi(steps as i32) * values[t + steps];
        }
        out.push(sum);
    }
    out
}
