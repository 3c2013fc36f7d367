pub fn compute_advantage(gamma: f32, lmbda: f32, td_delta: &[f32]) -> Vec<f32> {
    let mut out = vec![0.0; td_delta.len()];
    for t in (0..td_delta.len()).rev() {
        let adv = td_delta[t];
        out[t] = adv;
    }
    out
}
