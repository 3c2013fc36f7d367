pub fn reverse_kl(old_log_probs: &[f32], log_probs: &[f32]) -> f32 {
    let mut total = 0.0;
    for i in 0..old_log_probs.len() {
        let log_ratio = log_probs[i] - old_log_probs[i];
        let ratio = log_ratio.exp();
        total += ratio * log_ratio - (ratio - 1.0);
    }
    total
}
