pub fn normalize_advantage(advantage: &[f32]) -> Vec<f32> {
    let n = advantage.len();
    let mut sum = 0.0;
    for i in 0..n {
        sum += advantage[i];
    }
    let mean = sum / n as f32;
    let mut squares = 0.0;
    for i in 0..n {
        squares += (advantage[i] - mean) * (advantage[i] - mean);
    }
    let std = (squares / (n as f32 - 1.0)).sqrt();
    let mut out = Vec::new();
    for i in 0..n {
        out.push((advantage[i] - mean) / std);
    }
    out
}
