pub fn reverse_kl(old_log_probs: &[f32], log_probs: &[f32]) -> f32 {
    // KL(π_θ ‖ π_old) is the mean of log π_θ − log π_old.
    let mut total = 0.0;
    for i in 0..old_log_probs.len() {
        total += log_probs[i] - old_log_probs[i];
    }
    total / old_log_probs.len() as f32
}
