pub fn categorical_kl(old_probs: &[f32], new_probs: &[f32], n_actions: usize) -> Vec<f32> {
    let n = old_probs.len() / n_actions;
    let mut out = Vec::new();
    for i in 0..n {
        let mut kl = 0.0;
        for a in 0..n_actions {
            let log_ratio = old_probs[i * n_actions + a].ln() - new_probs[i * n_actions + a].ln();
            kl += log_ratio;
        }
        out.push(kl);
    }
    out
}
