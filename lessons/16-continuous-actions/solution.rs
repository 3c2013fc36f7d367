//! Reference solution for lesson 16: the log-density of the Gaussian policy at the actions
//! taken, as PyTorch's `torch.distributions.Normal(mu, std).log_prob(actions)` computes it.

/// `log N(a; μ, σ) = −(a − μ)²/(2σ²) − log σ − log √(2π)` for each row, in PyTorch's order of
/// operations: `var = σ²`, then `−((a − μ)²) / (2·var) − log σ − log √(2π)`, the constant
/// computed in f64 and rounded to f32 (as PyTorch rounds a Python float against a float
/// tensor).
pub fn gaussian_log_prob(mu: &[f32], std: &[f32], actions: &[f32]) -> Vec<f32> {
    let log_sqrt_2pi = (2.0 * std::f64::consts::PI).sqrt().ln() as f32;
    mu.iter()
        .zip(std)
        .zip(actions)
        .map(|((&mu, &std), &action)| {
            let var = std * std;
            let diff = action - mu;
            -(diff * diff) / (2.0 * var) - std.ln() - log_sqrt_2pi
        })
        .collect()
}
