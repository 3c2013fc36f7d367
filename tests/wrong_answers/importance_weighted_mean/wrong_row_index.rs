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
        // one block of n entries per action
        let p_new = probs[actions[i] * n + i];
        let ratio = p_new / old_log_probs[i].exp();
        total += ratio * returns[i];
    }
    total / n as f32
}
