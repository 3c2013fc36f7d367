pub fn zero_gradient_rows(ratio: &[f32], advantage: &[f32], eps: f32, c: f32) -> Vec<bool> {
    let low = 1.0 - eps;
    let high = 1.0 + eps;
    let mut out = Vec::new();
    for i in 0..ratio.len() {
        let r = ratio[i];
        let a = advantage[i];
        let zero = if a > 0.0 {
            r > high
        } else if a < 0.0 {
            r < low
        } else {
            true
        };
        out.push(zero);
    }
    out
}
