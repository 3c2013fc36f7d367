pub fn diag_gaussian_log_prob(actions: &[f32], mu: &[f32], log_std: &[f32], dim: usize) -> Vec<f32> {
    let n = actions.len() / dim;
    let log_sqrt_2pi = 0.5 * (2.0 * std::f32::consts::PI).ln();
    let mut out = Vec::new();
    for i in 0..n {
        let mut total = 0.0;
        for d in 0..dim {
            let std = log_std[d].exp();
            let diff = actions[i * dim + d] - mu[i * dim + d];
            total += -(diff * diff) / (2.0 * std * std) - log_std[d];
        }
        out.push(total - log_sqrt_2pi);
    }
    out
}
