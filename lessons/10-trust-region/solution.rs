//! Reference solution for lesson 10: the exact KL divergence between two categorical
//! policies at each state, from the logits a policy network outputs, with illegal actions
//! masked by a logit of −∞.

/// Per row `s`: `KL(π_old(·|s) ‖ π_new(·|s)) = Σ_a π_old(a|s) · (ln π_old(a|s) − ln π_new(a|s))`,
/// an expectation under the old policy over every action, with each `ln π` the row's
/// log-softmax. An action the old policy masks contributes 0; one it can take but the new
/// policy masks makes the row +∞. Rows are `n_actions` long, row-major.
pub fn categorical_kl(old_logits: &[f32], new_logits: &[f32], n_actions: usize) -> Vec<f32> {
    let mut kl = Vec::with_capacity(old_logits.len() / n_actions);
    for (old_row, new_row) in old_logits
        .chunks(n_actions)
        .zip(new_logits.chunks(n_actions))
    {
        let (log_p, log_q) = (log_softmax(old_row), log_softmax(new_row));
        let mut row = 0.0_f32;
        for (&lp, &lq) in log_p.iter().zip(&log_q) {
            if lp == f32::NEG_INFINITY {
                continue; // never taken by the old policy: p = 0 costs nothing
            }
            if lq == f32::NEG_INFINITY {
                row = f32::INFINITY; // p > 0 where the new policy gives 0
                break;
            }
            row += lp.exp() * (lp - lq);
        }
        kl.push(row);
    }
    kl
}

/// `ln softmax(logits)`: each logit minus the row's largest, minus the log of the sum of
/// the exponentials of those differences (each at most 1, the largest exactly 1, so the sum
/// neither overflows nor is 0). A logit of −∞ stays −∞.
fn log_softmax(logits: &[f32]) -> Vec<f32> {
    let max = logits.iter().copied().fold(f32::NEG_INFINITY, f32::max);
    let log_total = logits.iter().map(|&l| (l - max).exp()).sum::<f32>().ln();
    logits.iter().map(|&l| (l - max) - log_total).collect()
}
