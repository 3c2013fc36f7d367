pub fn diag_gaussian_log_prob(actions: &[f32], mu: &[f32], log_std: &[f32], dim: usize) -> Vec<f32> {
    let n = actions.len() / dim;
    let mut out = Vec::new();
    for i in 0..n {
        let mut total = 0.0;
        for d in 0..dim {
            let std = log_std[d].exp();
            let diff = actions[i * dim + d] - mu[i * dim + d];
            total += -(diff * diff) / (2.0 * std * std) - log_std[d] - 0.5 * (2.0 * std::f32::consts::PI).ln();
        }
        // average the dimensions so the value does not depend on how many there are
        out.push(total / dim as f32);
    }
    out
}
