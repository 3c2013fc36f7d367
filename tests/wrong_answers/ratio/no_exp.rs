pub fn ratio(log_probs: &[f32], old_log_probs: &[f32]) -> Vec<f32> {
    log_probs
        .iter()
        .zip(old_log_probs)
        .map(|(n, o)| n - o)
        .collect()
}
