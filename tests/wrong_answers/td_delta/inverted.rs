pub fn td_delta(td_target: &[f32], values: &[f32]) -> Vec<f32> {
    values.iter().zip(td_target).map(|(v, t)| v - t).collect()
}
