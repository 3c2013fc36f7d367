pub fn moving_average(a: &[f64], window_size: usize) -> Vec<f64> {
    let n = a.len();
    let h = window_size / 2;
    let mut out = a.to_vec();
    for i in h..n.saturating_sub(h) {
        out[i] = a[i - h..=i + h].iter().sum::<f64>() / window_size as f64;
    }
    out
}
