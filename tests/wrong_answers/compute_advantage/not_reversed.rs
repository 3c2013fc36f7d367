pub fn compute_advantage(gamma: f32, lmbda: f32, td_delta: &[f32]) -> Vec<f32> {
    let mut out = Vec::new();
    let mut adv = 0.0;
    for &delta in td_delta.iter().rev() {
        adv = gamma * lmbda * adv + delta;
        out.push(adv);
    }
    out
}
