pub fn gaussian_log_prob(mu: &[f32], std: &[f32], actions: &[f32]) -> Vec<f32> {
    let mut out = Vec::new();
    for i in 0..mu.len() {
        let z = (actions[i] - mu[i]) / std[i];
        let norm = 1.0 / (std[i] * (2.0 * std::f32::consts::PI).sqrt());
        out.push(norm * (-0.5 * z * z).exp());
    }
    out
}
