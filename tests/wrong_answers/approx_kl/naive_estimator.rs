pub fn approx_kl(old_log_probs: &[f32], log_probs: &[f32]) -> f32 {
    let mut total = 0.0;
    for i in 0..old_log_probs.len() {
        total += old_log_probs[i] - log_probs[i];
    }
    total / old_log_probs.len() as f32
}
