pub fn categorical_kl(old_probs: &[f32], new_probs: &[f32], n_actions: usize) -> Vec<f32> {
    let n = old_probs.len() / n_actions;
    let mut out = Vec::new();
    for i in 0..n {
        let mut kl = 0.0;
        for a in 0..n_actions {
            let p = old_probs[i * n_actions + a];
            let q = new_probs[i * n_actions + a];
            kl += p * (p.ln() - q.ln());
        }
        out.push(kl);
    }
    out
}
