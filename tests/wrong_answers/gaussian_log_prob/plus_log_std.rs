pub fn gaussian_log_prob(mu: &[f32], std: &[f32], actions: &[f32]) -> Vec<f32> {
    let mut out = Vec::new();
    for i in 0..mu.len() {
        let diff = actions[i] - mu[i];
        let var = std[i] * std[i];
        let log_sqrt_2pi = 0.5 * (2.0 * std::f32::consts::PI).ln();
        out.push(-(diff * diff) / (2.0 * var) + std[i].ln() - log_sqrt_2pi);
    }
    out
}
