//! Reference solution for lesson 13: KL(π_θ ‖ π_old) estimated from π_old's samples, and
//! Spinning Up's early stopping at a target KL.

/// `mean_i(r·log r − (r − 1))` with `log r = log_probs − old_log_probs`: the importance
/// weight r turns an average under π_θ into one over the actions π_old drew, and r − 1,
/// whose mean under π_old is 0, makes each row's term at least 0 (its minimum is 0, at
/// r = 1) without changing the mean.
pub fn reverse_kl(old_log_probs: &[f32], log_probs: &[f32]) -> f32 {
    let mut total = 0.0_f32;
    for (&old, &new) in old_log_probs.iter().zip(log_probs) {
        let log_ratio = new - old;
        let ratio = log_ratio.exp();
        total += ratio * log_ratio - (ratio - 1.0);
    }
    total / old_log_probs.len() as f32
}

/// Spinning Up's early stopping (`spinup/algos/pytorch/ppo/ppo.py`): before the step of
/// epoch `e`, `kl = mean_i(old_log_probs[i] − log_probs[e][i])` (the plain k1 estimate, not
/// `approx_kl`'s), and `if kl > 1.5 * target_kl` the update ends without that step. Returns
/// the number of steps taken: the first such `e`, or every epoch when none is.
pub fn kl_early_stop(old_log_probs: &[f32], log_probs_per_epoch: &[f32], target_kl: f32) -> usize {
    let n = old_log_probs.len();
    for (epoch, log_probs) in log_probs_per_epoch.chunks(n).enumerate() {
        let mut total = 0.0_f32;
        for (&old, &new) in old_log_probs.iter().zip(log_probs) {
            total += old - new;
        }
        let kl = total / n as f32;
        if kl > 1.5 * target_kl {
            return epoch;
        }
    }
    log_probs_per_epoch.len() / n
}
