pub fn kl_early_stop(old_log_probs: &[f32], log_probs_per_epoch: &[f32], target_kl: f32) -> usize {
    let n = old_log_probs.len();
    let epochs = log_probs_per_epoch.len() / n;
    for e in 0..epochs {
        let mut total = 0.0;
        for i in 0..n {
            total += old_log_probs[i] - log_probs_per_epoch[e * n + i];
        }
        let kl = total / n as f32;
        if kl >= 1.5 * target_kl {
            return e;
        }
    }
    epochs
}
