//! Reference solution for lesson 17: the log-density of a diagonal Gaussian policy at the
//! actions taken, one number per row however many dimensions an action has, as CleanRL's
//! `ppo_continuous_action.py` computes it:
//! `Normal(action_mean, action_logstd.exp()).log_prob(action).sum(1)`.

/// For each row `i` of the `N × dim` batch (row-major: row `i`, dimension `d` at
/// `i * dim + d`), the sum over the dimensions of the one-dimensional log-density
/// `−(a − μ)²/(2σ²) − log σ − log √(2π)`, with `σ = exp(log_std[d])` shared by every row.
/// The dimensions are independent, so the joint density is their product and its log is
/// the sum: one log-probability per action, not one per dimension.
pub fn diag_gaussian_log_prob(
    actions: &[f32],
    mu: &[f32],
    log_std: &[f32],
    dim: usize,
) -> Vec<f32> {
    let log_sqrt_2pi = (2.0 * std::f64::consts::PI).sqrt().ln() as f32;
    let rows = actions.len() / dim;
    let mut out = Vec::with_capacity(rows);
    for i in 0..rows {
        let mut total = 0.0_f32;
        for d in 0..dim {
            let std = log_std[d].exp();
            let var = std * std;
            let diff = actions[i * dim + d] - mu[i * dim + d];
            total += -(diff * diff) / (2.0 * var) - log_std[d] - log_sqrt_2pi;
        }
        out.push(total);
    }
    out
}
