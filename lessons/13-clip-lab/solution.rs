//! Reference solution for lesson 13: CleanRL's `approx_kl`, and Spinning Up's early stopping
//! at a target KL.

/// CleanRL's `approx_kl = ((ratio - 1) - logratio).mean()` with
/// `logratio = log_probs - old_log_probs`: an estimate of KL(π_old ‖ π_θ) that is never
/// negative, row by row, and unbiased over actions sampled from π_old.
pub fn approx_kl(old_log_probs: &[f32], log_probs: &[f32]) -> f32 {
    let mut total = 0.0_f32;
    for (&old, &new) in old_log_probs.iter().zip(log_probs) {
        let log_ratio = new - old;
        total += (log_ratio.exp() - 1.0) - log_ratio;
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
