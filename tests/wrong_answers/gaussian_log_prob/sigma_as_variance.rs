pub fn gaussian_log_prob(mu: &[f32], std: &[f32], actions: &[f32]) -> Vec<f32> {
    let mut out = Vec::new();
    for i in 0..mu.len() {
        let var = std[i];
        let diff = actions[i] - mu[i];
        let log_norm = 0.5 * (2.0 * std::f32::consts::PI * var).ln();
        out.push(-(diff * diff) / (2.0 * var) - log_norm);
    }
    out
}
