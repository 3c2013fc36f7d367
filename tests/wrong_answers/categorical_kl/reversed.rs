pub fn categorical_kl(old_probs: &[f32], new_probs: &[f32], n_actions: usize) -> Vec<f32> {
    // how far the new policy is from the old one, weighted by the new policy
    let n = old_probs.len() / n_actions;
    let mut out = Vec::new();
    for i in 0..n {
        let mut kl = 0.0;
        for a in 0..n_actions {
            let p = old_probs[i * n_actions + a];
            let q = new_probs[i * n_actions + a];
            kl += q * (q / p).ln();
        }
        out.push(kl);
    }
    out
}
