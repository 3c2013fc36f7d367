pub fn gaussian_log_prob(mu: &[f32], std: &[f32], actions: &[f32]) -> Vec<f32> {
    let mut out = Vec::new();
    for i in 0..mu.len() {
        let z = (actions[i] - mu[i]) / std[i];
        out.push(-z * z - std[i].ln() - 0.5 * (2.0 * std::f32::consts::PI).ln());
    }
    out
}
