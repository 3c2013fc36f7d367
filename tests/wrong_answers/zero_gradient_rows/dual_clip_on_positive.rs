pub fn zero_gradient_rows(ratio: &[f32], advantage: &[f32], eps: f32, c: f32) -> Vec<bool> {
    // max(min(surr1, surr2), c * adv) for every row.
    let low = 1.0 - eps;
    let mut out = Vec::new();
    for i in 0..ratio.len() {
        let r = ratio[i];
        let a = advantage[i];
        let zero = if a >= 0.0 {
            // c * a is at least (1 + eps) * a, so the max always takes the bound.
            true
        } else {
            r < low || r > c
        };
        out.push(zero);
    }
    out
}
