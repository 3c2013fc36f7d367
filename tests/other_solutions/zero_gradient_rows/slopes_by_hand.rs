pub fn zero_gradient_rows(ratio: &[f32], advantage: &[f32], eps: f32, c: f32) -> Vec<bool> {
    // Autograd by hand, in f64: the slope in r of each candidate term, then which term the
    // min (and, for a negative advantage, the max) picks, a tie passing half of each.
    let mut out = Vec::new();
    for i in 0..ratio.len() {
        let (r, a, e, c) = (ratio[i] as f64, advantage[i] as f64, eps as f64, c as f64);
        let clamped = r.max(1.0 - e).min(1.0 + e);
        let (surr1, surr2) = (r * a, clamped * a);
        let slope1 = a;
        let slope2 = if r - 1.0 >= -e && r - 1.0 <= e {
            a
        } else {
            0.0
        };
        let (inner, mut slope) = if surr1 < surr2 {
            (surr1, slope1)
        } else if surr2 < surr1 {
            (surr2, slope2)
        } else {
            (surr1, (slope1 + slope2) / 2.0)
        };
        if a < 0.0 {
            let bound = c * a;
            if bound > inner {
                slope = 0.0;
            } else if bound == inner {
                slope /= 2.0;
            }
        }
        out.push(slope == 0.0);
    }
    out
}
