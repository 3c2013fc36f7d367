pub fn diag_gaussian_log_prob(actions: &[f32], mu: &[f32], log_std: &[f32], dim: usize) -> Vec<f32> {
    let n = actions.len() / dim;
    let mut out = Vec::new();
    for i in 0..n {
        let a = actions[i * dim];
        let m = mu[i * dim];
        let std = log_std[0].exp();
        let z = (a - m) / std;
        out.push(-0.5 * z * z - log_std[0] - 0.918_938_5);
    }
    out
}
