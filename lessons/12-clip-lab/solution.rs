//! Reference solution for lesson 12: the two diagnostics CleanRL logs every update.

/// CleanRL's `approx_kl = ((ratio - 1) - logratio).mean()` with
/// `logratio = log_probs - old_log_probs`: an estimate of KL(π_old ‖ π_θ) that is never
/// negative, row by row, and unbiased over actions sampled from π_old.
pub fn approx_kl(old_log_probs: &[f32], log_probs: &[f32]) -> f32 {
    let mut total = 0.0_f32;
    for (&old, &new) in old_log_probs.iter().zip(log_probs) {
        let log_ratio = new - old;
        total += (log_ratio.exp() - 1.0) - log_ratio;
    }
    total / old_log_probs.len() as f32
}

/// CleanRL's `((ratio - 1.0).abs() > clip_coef).float().mean()`: the fraction of rows whose
/// ratio lies outside `[1 − ε, 1 + ε]`, computed in float32.
pub fn clip_fraction(ratio: &[f32], eps: f32) -> f32 {
    let clipped = ratio.iter().filter(|&&r| (r - 1.0).abs() > eps).count();
    clipped as f32 / ratio.len() as f32
}
