pub fn diag_gaussian_log_prob(actions: &[f32], mu: &[f32], log_std: &[f32], dim: usize) -> Vec<f32> {
    let n = actions.len() / dim;
    let mut out = Vec::new();
    for i in 0..n {
        let mut total = 0.0;
        for d in 0..dim {
            let std = log_std[d].exp();
            let diff = actions[i * dim + d] - mu[i * dim + d];
            // the constant cancels in the ratio anyway
            total += -(diff * diff) / (2.0 * std * std) - log_std[d];
        }
        out.push(total);
    }
    out
}
