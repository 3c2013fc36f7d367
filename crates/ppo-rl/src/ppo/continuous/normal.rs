//! The Gaussian policy's log-density, `torch.distributions.Normal(loc, scale).log_prob`.
//!
//! ```text
//! log N(a; μ, σ) = -(a - μ)² / (2σ²) - log σ - log √(2π)
//! ```
//!
//! evaluated as PyTorch writes it, operation by operation, so f32 rounding matches:
//! `var = σ²`, then `-((a - μ)²) / (2 · var) - log(σ) - log(√(2π))`, the constant rounded
//! from f64 to f32 as PyTorch rounds a Python float against a float tensor. All tensors
//! `(N, 1)`; gradients flow to `μ` and `σ` (for `old_log_probs` pass detached ones).
//!
//! ```
//! use candle_core::{Device, Tensor};
//! use ppo_rl::ppo::continuous::{log_prob, normal_log_prob};
//!
//! let dev = &Device::Cpu;
//! let a = Tensor::new(&[[0.5f32], [-1.0]], dev)?;
//! let mu = Tensor::new(&[[0.0f32], [-1.0]], dev)?;
//! let std = Tensor::new(&[[1.0f32], [0.5]], dev)?;
//! let lp = log_prob(&a, &mu, &std)?.flatten_all()?.to_vec1::<f32>()?;
//! // a standard normal at 0.5: -0.125 - 0.9189385
//! assert!((lp[0] - (-1.0439385)).abs() < 1e-6);
//! assert_eq!(lp[1], normal_log_prob(-1.0, -1.0, 0.5));
//! # Ok::<(), candle_core::Error>(())
//! ```

use candle_core::Tensor;

/// `log √(2π)` in f64, as Python's `math.log(math.sqrt(2 * math.pi))`.
pub(crate) const LOG_SQRT_2PI: f64 = 0.918_938_533_204_672_7;

// ANCHOR: log_prob
/// `Normal(mu, std).log_prob(value)`, elementwise over tensors of one shape.
///
/// # Errors
/// When the shapes differ or the tensors are not f32.
pub fn log_prob(value: &Tensor, mu: &Tensor, std: &Tensor) -> candle_core::Result<Tensor> {
    // ANCHOR: log_prob_formula
    let var = std.sqr()?;
    let squared_error = (value - mu)?.sqr()?;
    let scaled = squared_error.neg()?.div(&(var * 2.0)?)?;
    (scaled - std.log()?)? - LOG_SQRT_2PI
    // ANCHOR_END: log_prob_formula
}
// ANCHOR_END: log_prob

/// [`log_prob`] for one number, with the same f32 operations in the same order.
#[must_use]
pub fn normal_log_prob(value: f32, mu: f32, std: f32) -> f32 {
    let var = std * std;
    let d = value - mu;
    -(d * d) / (2.0 * var) - std.ln() - LOG_SQRT_2PI as f32
}

#[cfg(test)]
mod tests {
    use super::*;
    use candle_core::{Device, Var};

    /// The formula in f64 agrees to f32 rounding, and the gradients are the textbook ones:
    /// `∂/∂μ = (a - μ)/σ²`, `∂/∂σ = (a - μ)²/σ³ - 1/σ`.
    #[test]
    fn values_and_gradients() -> candle_core::Result<()> {
        let dev = &Device::Cpu;
        let (a, m, s) = (
            [0.3f32, -1.7, 2.0],
            [0.1f32, -0.2, 1.9],
            [0.8f32, 1.3, 0.05],
        );
        let mu = Var::new(&m, dev)?;
        let std = Var::new(&s, dev)?;
        let value = Tensor::new(&a, dev)?;
        let lp = log_prob(&value, mu.as_tensor(), std.as_tensor())?;
        let got = lp.to_vec1::<f32>()?;
        let grads = lp.sum_all()?.backward()?;
        let g_mu = grads.get(mu.as_tensor()).map(|t| t.to_vec1::<f32>());
        let g_std = grads.get(std.as_tensor()).map(|t| t.to_vec1::<f32>());
        let (g_mu, g_std) = (g_mu.transpose()?, g_std.transpose()?);
        let (g_mu, g_std) = (g_mu.unwrap_or_default(), g_std.unwrap_or_default());
        for i in 0..3 {
            let (a, m, s) = (f64::from(a[i]), f64::from(m[i]), f64::from(s[i]));
            let want = -(a - m).powi(2) / (2.0 * s * s) - s.ln() - LOG_SQRT_2PI;
            assert!((f64::from(got[i]) - want).abs() <= 1e-6 * want.abs().max(1.0));
            assert_eq!(got[i], normal_log_prob(a as f32, m as f32, s as f32));
            let want_mu = (a - m) / (s * s);
            let want_std = (a - m).powi(2) / s.powi(3) - 1.0 / s;
            assert!((f64::from(g_mu[i]) - want_mu).abs() <= 1e-5 * want_mu.abs().max(1.0));
            assert!((f64::from(g_std[i]) - want_std).abs() <= 1e-5 * want_std.abs().max(1.0));
        }
        Ok(())
    }
}
