pub fn categorical_kl(old_logits: &[f32], new_logits: &[f32], n_actions: usize) -> Vec<f32> {
    // log-softmax with the max subtracted, then p * (log p - log q) over every action
    let n = old_logits.len() / n_actions;
    let mut out = Vec::new();
    for i in 0..n {
        let old = &old_logits[i * n_actions..(i + 1) * n_actions];
        let new = &new_logits[i * n_actions..(i + 1) * n_actions];
        let old_max = old.iter().cloned().fold(f32::NEG_INFINITY, f32::max);
        let new_max = new.iter().cloned().fold(f32::NEG_INFINITY, f32::max);
        let mut old_sum = 0.0;
        let mut new_sum = 0.0;
        for a in 0..n_actions {
            old_sum += (old[a] - old_max).exp();
            new_sum += (new[a] - new_max).exp();
        }
        let mut kl = 0.0;
        for a in 0..n_actions {
            let log_p = old[a] - old_max - old_sum.ln();
            let log_q = new[a] - new_max - new_sum.ln();
            kl += log_p.exp() * (log_p - log_q);
        }
        out.push(kl);
    }
    out
}
