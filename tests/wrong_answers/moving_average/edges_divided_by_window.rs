pub fn moving_average(a: &[f64], window_size: usize) -> Vec<f64> {
    let n = a.len();
    let h = window_size / 2;
    let mut out = Vec::new();
    for i in 0..n {
        let lo = if i >= h { i - h } else { 0 };
        let hi = if i + h < n { i + h } else { n - 1 };
        let mut sum = 0.0;
        for j in lo..=hi {
            sum += a[j];
        }
        out.push(sum / window_size as f64);
    }
    out
}
