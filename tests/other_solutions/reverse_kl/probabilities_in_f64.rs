pub fn reverse_kl(old_log_probs: &[f32], log_probs: &[f32]) -> f32 {
    // From the probabilities themselves, in f64: r = π_θ / π_old, and the term factored as
    // r·(log r − 1) + 1.
    let mut total = 0.0_f64;
    for (&old, &new) in old_log_probs.iter().zip(log_probs) {
        let (p_old, p_new) = (f64::from(old).exp(), f64::from(new).exp());
        let r = p_new / p_old;
        total += r * (r.ln() - 1.0) + 1.0;
    }
    (total / old_log_probs.len() as f64) as f32
}
