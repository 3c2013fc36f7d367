pub fn diag_gaussian_log_prob(actions: &[f32], mu: &[f32], log_std: &[f32], dim: usize) -> Vec<f32> {
    let n = actions.len() / dim;
    let mut out = vec![0.0; n];
    for d in 0..dim {
        let std = log_std[d].exp();
        for i in 0..n {
            let diff = actions[d * n + i] - mu[d * n + i];
            out[i] += -(diff * diff) / (2.0 * std * std) - log_std[d] - 0.918_938_5;
        }
    }
    out
}
