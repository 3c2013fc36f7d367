pub fn gaussian_log_prob(mu: &[f32], std: &[f32], actions: &[f32]) -> Vec<f32> {
    let mut out = Vec::new();
    for i in 0..mu.len() {
        let diff = actions[i] - mu[i];
        let term = diff * diff / (2.0 * std[i]);
        out.push(-term - std[i].ln() - 0.918_938_5);
    }
    out
}
