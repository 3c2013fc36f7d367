pub fn ratio(log_probs: &[f32], old_log_probs: &[f32]) -> Vec<f32> {
    let mut out = Vec::new();
    for i in 0..log_probs.len() {
        out.push(log_probs[i] / old_log_probs[i]);
    }
    out
}
