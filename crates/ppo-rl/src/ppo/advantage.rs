//! Generalised advantage estimation (GAE), as the seed's `rl_utils.compute_advantage`.
//!
//! From the TD errors of one episode, `td_delta (N, 1)`, computed in
//! [`Agent::update`](crate::ppo::Agent::update):
//!
//! ```text
//! td_target_t = r_t + γ · V(s_{t+1}) · (1 - done_t)
//! td_delta_t  = td_target_t - V(s_t)
//! advantage_t = Σ_{l≥0} (γλ)^l · td_delta_{t+l}     (within the episode)
//!             = td_delta_t + γλ · advantage_{t+1}    (computed backwards from the end)
//! ```
//!
//! The seed runs the recurrence in numpy on float32 TD errors with a Python float `γλ`;
//! numpy rounds `γλ` to f32 and keeps `advantage` in f32, so this does too: the result
//! matches PyTorch's bit for bit given the same `td_delta`.
//!
//! ```
//! use ppo_rl::ppo::compute_advantage;
//!
//! // γλ = 0.5: [1 + 0.5·(1 + 0.5·1), 1 + 0.5·1, 1]
//! assert_eq!(compute_advantage(1.0, 0.5, &[1.0, 1.0, 1.0]), vec![1.75, 1.5, 1.0]);
//! ```

// ANCHOR: compute_advantage
/// `advantage_t = td_delta_t + γλ · advantage_{t+1}`, backwards over the episode, in f32.
#[must_use]
pub fn compute_advantage(gamma: f64, lmbda: f64, td_delta: &[f32]) -> Vec<f32> {
    // ANCHOR: gae_recursion
    let coef = (gamma * lmbda) as f32; // numpy casts the Python float γλ to float32
    let mut advantage = vec![0.0_f32; td_delta.len()];
    let mut adv = 0.0_f32;
    for (out, &delta) in advantage.iter_mut().zip(td_delta).rev() {
        adv = coef * adv + delta;
        *out = adv;
    }
    advantage
    // ANCHOR_END: gae_recursion
}
// ANCHOR_END: compute_advantage

// ANCHOR: advantage_norm_switch
/// Advantage normalisation (opt-in, not in the seed): `(A - mean A) / (std A + 1e-8)` with
/// the unbiased standard deviation, as `torch.std` and CleanRL. A batch of one is left as is.
#[must_use]
pub fn normalize_advantage(advantage: &[f32]) -> Vec<f32> {
    let n = advantage.len();
    if n < 2 {
        return advantage.to_vec();
    }
    // ANCHOR: normalize_advantage_formula
    let mean = advantage.iter().sum::<f32>() / n as f32;
    let var = advantage
        .iter()
        .map(|a| (a - mean) * (a - mean))
        .sum::<f32>()
        / (n - 1) as f32;
    let std = var.sqrt();
    advantage
        .iter()
        .map(|a| (a - mean) / (std + 1e-8))
        .collect()
    // ANCHOR_END: normalize_advantage_formula
}
// ANCHOR_END: advantage_norm_switch

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gae_rounds_the_coefficient_to_f32() {
        let coef = (0.98_f64 * 0.95) as f32;
        let got = compute_advantage(0.98, 0.95, &[0.25, -0.5]);
        assert_eq!(got, vec![coef * -0.5 + 0.25, -0.5]);
    }

    #[test]
    fn lambda_zero_is_the_td_error() {
        let d = [0.3_f32, -0.2, 5.0];
        assert_eq!(compute_advantage(0.98, 0.0, &d), d.to_vec());
    }

    #[test]
    fn normalised_has_zero_mean_unit_std() {
        let a = normalize_advantage(&[1.0, 2.0, 3.0, 4.0]);
        let mean: f32 = a.iter().sum::<f32>() / 4.0;
        let var: f32 = a.iter().map(|x| (x - mean).powi(2)).sum::<f32>() / 3.0;
        assert!(mean.abs() < 1e-6 && (var - 1.0).abs() < 1e-5);
        assert_eq!(normalize_advantage(&[7.0]), vec![7.0]);
    }
}
