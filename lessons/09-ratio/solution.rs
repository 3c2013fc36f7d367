//! Reference solution for lesson 09: the ratio `π_θ(a|s) / π_θ_old(a|s)` put to the use
//! its name comes from, importance sampling: it reweights returns collected by the old
//! policy so that their mean estimates the new policy's.

/// `mean_i( π_new(a_i|s_i) / π_old(a_i|s_i) · returns[i] )`, with `π_new(a_i|s_i)` read from
/// row `i` of `probs` (row-major, `n_actions` columns) and `π_old(a_i|s_i)` given as a log.
pub fn importance_weighted_mean(
    probs: &[f32],
    n_actions: usize,
    actions: &[usize],
    old_log_probs: &[f32],
    returns: &[f32],
) -> f32 {
    let rows = probs
        .chunks(n_actions)
        .zip(actions)
        .zip(old_log_probs)
        .zip(returns);
    let mut weighted_sum = 0.0_f32;
    for (((row, &action), &log_old), &ret) in rows {
        let log_new = row[action].ln();
        let weight = (log_new - log_old).exp();
        weighted_sum += weight * ret;
    }
    weighted_sum / actions.len() as f32
}
