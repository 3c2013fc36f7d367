pub fn importance_weighted_mean(
    probs: &[f32],
    n_actions: usize,
    actions: &[usize],
    old_log_probs: &[f32],
    returns: &[f32],
) -> f32 {
    let mut total = 0.0;
    for i in 0..returns.len() {
        total += returns[i];
    }
    total / returns.len() as f32
}
