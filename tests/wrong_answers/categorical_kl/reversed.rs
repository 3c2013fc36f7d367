fn log_softmax(logits: &[f32]) -> Vec<f32> {
    let mut max = f32::NEG_INFINITY;
    for &l in logits {
        if l > max {
            max = l;
        }
    }
    let mut sum = 0.0;
    for &l in logits {
        sum += (l - max).exp();
    }
    let mut out = Vec::new();
    for &l in logits {
        out.push(l - max - sum.ln());
    }
    out
}

pub fn categorical_kl(old_logits: &[f32], new_logits: &[f32], n_actions: usize) -> Vec<f32> {
    // how far the new policy is from the old one, weighted by the new policy
    let n = old_logits.len() / n_actions;
    let mut out = Vec::new();
    for i in 0..n {
        let lp = log_softmax(&old_logits[i * n_actions..(i + 1) * n_actions]);
        let lq = log_softmax(&new_logits[i * n_actions..(i + 1) * n_actions]);
        let mut kl = 0.0;
        for a in 0..n_actions {
            if lq[a] == f32::NEG_INFINITY {
                continue;
            }
            if lp[a] == f32::NEG_INFINITY {
                kl = f32::INFINITY;
                break;
            }
            kl += lq[a].exp() * (lq[a] - lp[a]);
        }
        out.push(kl);
    }
    out
}
