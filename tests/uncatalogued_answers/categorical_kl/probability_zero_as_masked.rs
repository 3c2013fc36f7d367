pub fn categorical_kl(old_logits: &[f32], new_logits: &[f32], n_actions: usize) -> Vec<f32> {
    // stable softmax first, then PyTorch's rule on the probabilities: p = 0 counts 0,
    // q = 0 where p > 0 makes the row infinite
    fn softmax(row: &[f32]) -> Vec<f32> {
        let mut max = f32::NEG_INFINITY;
        for &l in row {
            max = max.max(l);
        }
        let mut sum = 0.0;
        for &l in row {
            sum += (l - max).exp();
        }
        row.iter().map(|&l| (l - max).exp() / sum).collect()
    }
    let n = old_logits.len() / n_actions;
    let mut out = Vec::new();
    for i in 0..n {
        let p = softmax(&old_logits[i * n_actions..(i + 1) * n_actions]);
        let q = softmax(&new_logits[i * n_actions..(i + 1) * n_actions]);
        let mut kl = 0.0;
        for a in 0..n_actions {
            if p[a] == 0.0 {
                continue;
            }
            if q[a] == 0.0 {
                kl = f32::INFINITY;
                break;
            }
            kl += p[a] * (p[a].ln() - q[a].ln());
        }
        out.push(kl);
    }
    out
}
