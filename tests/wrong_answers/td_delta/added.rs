pub fn td_delta(td_target: &[f32], values: &[f32]) -> Vec<f32> {
    td_target.iter().zip(values).map(|(t, v)| t + v).collect()
}
