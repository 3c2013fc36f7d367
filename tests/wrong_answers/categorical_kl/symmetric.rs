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

fn kl_one_way(lp: &[f32], lq: &[f32]) -> f32 {
    let mut kl = 0.0;
    for a in 0..lp.len() {
        if lp[a] == f32::NEG_INFINITY {
            continue;
        }
        if lq[a] == f32::NEG_INFINITY {
            return f32::INFINITY;
        }
        kl += lp[a].exp() * (lp[a] - lq[a]);
    }
    kl
}

pub fn categorical_kl(old_logits: &[f32], new_logits: &[f32], n_actions: usize) -> Vec<f32> {
    // a distance should not depend on the order: average both directions
    let n = old_logits.len() / n_actions;
    let mut out = Vec::new();
    for i in 0..n {
        let lp = log_softmax(&old_logits[i * n_actions..(i + 1) * n_actions]);
        let lq = log_softmax(&new_logits[i * n_actions..(i + 1) * n_actions]);
        out.push(0.5 * (kl_one_way(&lp, &lq) + kl_one_way(&lq, &lp)));
    }
    out
}
