pub fn kl_early_stop(old_log_probs: &[f32], log_probs_per_epoch: &[f32], target_kl: f32) -> usize {
    let n = old_log_probs.len();
    let epochs = log_probs_per_epoch.len() / n;
    for e in 0..epochs {
        let row = &log_probs_per_epoch[e * n..(e + 1) * n];
        let kl: f32 = old_log_probs.iter().zip(row).map(|(o, l)| o - l).sum::<f32>() / n as f32;
        // The estimate in units of target_kl.
        if kl / target_kl > 1.5 {
            return e;
        }
    }
    epochs
}
