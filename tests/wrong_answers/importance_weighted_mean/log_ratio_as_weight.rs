pub fn importance_weighted_mean(
    probs: &[f32],
    n_actions: usize,
    actions: &[usize],
    old_log_probs: &[f32],
    returns: &[f32],
) -> f32 {
    let n = actions.len();
    let mut total = 0.0;
    for i in 0..n {
        let new_log_prob = probs[i * n_actions + actions[i]].ln();
        let ratio = new_log_prob - old_log_probs[i];
        total += ratio * returns[i];
    }
    total / n as f32
}
