pub fn zero_gradient_rows(ratio: &[f32], advantage: &[f32], eps: f32) -> Vec<bool> {
    // The ratio's distance from 1 compared with ε, strictly, in f64.
    let mut out = Vec::new();
    for i in 0..ratio.len() {
        let (r, a, e) = (ratio[i] as f64, advantage[i] as f64, eps as f64);
        let flat = if a > 0.0 {
            r - 1.0 > e
        } else if a < 0.0 {
            1.0 - r > e
        } else {
            true
        };
        out.push(flat);
    }
    out
}
