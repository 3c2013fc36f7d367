pub fn moving_average(a: &[f64], window_size: usize) -> Vec<f64> {
    let mut out = Vec::new();
    for i in 0..=a.len() - window_size {
        out.push(a[i..i + window_size].iter().sum::<f64>() / window_size as f64);
    }
    out
}
