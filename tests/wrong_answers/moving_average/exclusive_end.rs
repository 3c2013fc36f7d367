pub fn moving_average(a: &[f64], window_size: usize) -> Vec<f64> {
    let n = a.len();
    let mut out = Vec::new();
    for i in 0..n {
        let h = (window_size / 2).min(i).min(n - 1 - i);
        let window = &a[i - h..i + h];
        out.push(window.iter().sum::<f64>() / (2 * h + 1) as f64);
    }
    out
}
