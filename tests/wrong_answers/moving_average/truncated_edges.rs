pub fn moving_average(a: &[f64], window_size: usize) -> Vec<f64> {
    let n = a.len();
    let h = window_size / 2;
    (0..n)
        .map(|i| {
            let lo = i.saturating_sub(h);
            let hi = (i + h + 1).min(n);
            a[lo..hi].iter().sum::<f64>() / (hi - lo) as f64
        })
        .collect()
}
