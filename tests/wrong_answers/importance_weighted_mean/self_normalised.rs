pub fn importance_weighted_mean(
    probs: &[f32],
    n_actions: usize,
    actions: &[usize],
    old_log_probs: &[f32],
    returns: &[f32],
) -> f32 {
    let mut weighted = 0.0;
    let mut weights = 0.0;
    for i in 0..actions.len() {
        let p_new = probs[i * n_actions + actions[i]];
        let w = (p_new.ln() - old_log_probs[i]).exp();
        weighted += w * returns[i];
        weights += w;
    }
    weighted / weights
}
