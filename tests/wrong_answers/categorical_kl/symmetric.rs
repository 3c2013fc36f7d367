pub fn categorical_kl(old_probs: &[f32], new_probs: &[f32], n_actions: usize) -> Vec<f32> {
    // a distance should not depend on the order: average both directions
    let n = old_probs.len() / n_actions;
    let mut out = Vec::new();
    for i in 0..n {
        let mut forward = 0.0;
        let mut backward = 0.0;
        for a in 0..n_actions {
            let p = old_probs[i * n_actions + a];
            let q = new_probs[i * n_actions + a];
            if p > 0.0 {
                forward += p * (p / q).ln();
            }
            backward += q * (q / p).ln();
        }
        out.push((forward + backward) / 2.0);
    }
    out
}
