pub fn categorical_kl(old_logits: &[f32], new_logits: &[f32], n_actions: usize) -> Vec<f32> {
    // softmax straight from the formula: exp of each logit over the sum of the exps
    let n = old_logits.len() / n_actions;
    let mut out = Vec::new();
    for i in 0..n {
        let old = &old_logits[i * n_actions..(i + 1) * n_actions];
        let new = &new_logits[i * n_actions..(i + 1) * n_actions];
        let mut old_sum = 0.0;
        let mut new_sum = 0.0;
        for a in 0..n_actions {
            old_sum += old[a].exp();
            new_sum += new[a].exp();
        }
        let mut kl = 0.0;
        for a in 0..n_actions {
            if old[a] == f32::NEG_INFINITY {
                continue;
            }
            if new[a] == f32::NEG_INFINITY {
                kl = f32::INFINITY;
                break;
            }
            let p = old[a].exp() / old_sum;
            let q = new[a].exp() / new_sum;
            kl += p * (p.ln() - q.ln());
        }
        out.push(kl);
    }
    out
}
