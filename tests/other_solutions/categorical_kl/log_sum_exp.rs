pub fn categorical_kl(old_logits: &[f32], new_logits: &[f32], n_actions: usize) -> Vec<f32> {
    // log π = logit − logsumexp(row), logsumexp = max + ln Σ exp(logit − max), as PyTorch's
    // logsumexp does it; a masked action is one whose logit is not finite.
    fn log_sum_exp(row: &[f32]) -> f32 {
        let mut max = f32::NEG_INFINITY;
        for &l in row {
            max = max.max(l);
        }
        let mut sum = 0.0;
        for &l in row {
            sum += (l - max).exp();
        }
        max + sum.ln()
    }
    let n = old_logits.len() / n_actions;
    let mut out = Vec::new();
    for i in 0..n {
        let old = &old_logits[i * n_actions..(i + 1) * n_actions];
        let new = &new_logits[i * n_actions..(i + 1) * n_actions];
        let (old_lse, new_lse) = (log_sum_exp(old), log_sum_exp(new));
        let mut kl = 0.0;
        for a in 0..n_actions {
            if !old[a].is_finite() {
                continue;
            }
            if !new[a].is_finite() {
                kl = f32::INFINITY;
                break;
            }
            let log_ratio = (old[a] - old_lse) - (new[a] - new_lse);
            kl += (old[a] - old_lse).exp() * log_ratio;
        }
        out.push(kl);
    }
    out
}
