pub fn reverse_kl(old_log_probs: &[f32], log_probs: &[f32]) -> f32 {
    // The sample-variance habit: divides by N − 1 instead of N.
    let mut total = 0.0;
    for i in 0..old_log_probs.len() {
        let x = log_probs[i] - old_log_probs[i];
        let r = x.exp();
        total += r * x - (r - 1.0);
    }
    total / (old_log_probs.len() as f32 - 1.0).max(1.0)
}
