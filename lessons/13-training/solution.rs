//! Reference solution for lesson 13: `rl_utils.moving_average(a, window_size)` from the
//! seed, numpy's cumulative sums translated line by line.

/// A centred mean over `window_size` (odd, at most `a.len() + 1`) values, with windows of
/// 1, 3, 5, ... at both ends so the output is as long as the input.
pub fn moving_average(a: &[f64], window_size: usize) -> Vec<f64> {
    let n = a.len();
    let w = window_size;
    // cumulative_sum = np.cumsum(np.insert(a, 0, 0))
    let mut cumulative_sum = vec![0.0; n + 1];
    for i in 0..n {
        cumulative_sum[i + 1] = cumulative_sum[i] + a[i];
    }
    // begin = np.cumsum(a[:window_size-1])[::2] / r, with r = 1, 3, 5, ...
    let mut out = Vec::with_capacity(n);
    let mut sum = 0.0;
    for (i, &x) in a[..w - 1].iter().enumerate() {
        sum += x;
        if i % 2 == 0 {
            out.push(sum / (i + 1) as f64);
        }
    }
    // middle = (cumulative_sum[window_size:] - cumulative_sum[:-window_size]) / window_size
    for i in 0..(n + 1).saturating_sub(w) {
        out.push((cumulative_sum[i + w] - cumulative_sum[i]) / w as f64);
    }
    // end = (np.cumsum(a[:-window_size:-1])[::2] / r)[::-1]
    let mut end = Vec::new();
    sum = 0.0;
    for (i, &x) in a[n + 1 - w..].iter().rev().enumerate() {
        sum += x;
        if i % 2 == 0 {
            end.push(sum / (i + 1) as f64);
        }
    }
    end.reverse();
    out.extend(end);
    out
}
