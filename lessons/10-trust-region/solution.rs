//! Reference solution for lesson 10: the exact KL divergence between two categorical
//! policies at each state, the quantity PPO-Penalty's β multiplies and a trust region bounds.

/// Per row `s`: `KL(π_old(·|s) ‖ π_new(·|s)) = Σ_a π_old(a|s) · ln(π_old(a|s) / π_new(a|s))`,
/// an expectation under the old policy over every action; an action with `π_old(a|s) = 0`
/// contributes 0 (the limit of `p · ln p` as `p → 0`). Rows are `n_actions` long, row-major.
pub fn categorical_kl(old_probs: &[f32], new_probs: &[f32], n_actions: usize) -> Vec<f32> {
    let mut kl = Vec::with_capacity(old_probs.len() / n_actions);
    for (old_row, new_row) in old_probs.chunks(n_actions).zip(new_probs.chunks(n_actions)) {
        let mut row = 0.0_f32;
        for (&p, &q) in old_row.iter().zip(new_row) {
            if p > 0.0 {
                row += p * (p.ln() - q.ln());
            }
        }
        kl.push(row);
    }
    kl
}
