pub fn categorical_kl(old_logits: &[f32], new_logits: &[f32], n_actions: usize) -> Vec<f32> {
    // p from a stable softmax; ln(p / q) taken as the difference of the logits
    let n = old_logits.len() / n_actions;
    let mut out = Vec::new();
    for i in 0..n {
        let old = &old_logits[i * n_actions..(i + 1) * n_actions];
        let new = &new_logits[i * n_actions..(i + 1) * n_actions];
        let mut max = f32::NEG_INFINITY;
        for a in 0..n_actions {
            if old[a] > max {
                max = old[a];
            }
        }
        let mut sum = 0.0;
        for a in 0..n_actions {
            sum += (old[a] - max).exp();
        }
        let mut kl = 0.0;
        for a in 0..n_actions {
            if old[a] == f32::NEG_INFINITY {
                continue;
            }
            let p = (old[a] - max).exp() / sum;
            kl += p * (old[a] - new[a]);
        }
        out.push(kl);
    }
    out
}
