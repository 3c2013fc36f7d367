pub fn importance_weighted_mean(
    probs: &[f32],
    n_actions: usize,
    actions: &[usize],
    old_log_probs: &[f32],
    returns: &[f32],
) -> f32 {
    // weight each return by how likely the new policy makes its action
    let n = actions.len();
    let mut total = 0.0;
    for i in 0..n {
        let p = probs[i * n_actions + actions[i]];
        total += p * returns[i];
    }
    total / n as f32
}
