pub fn critic_loss(values: &[f32], td_target: &[f32]) -> f32 {
    let mut total = 0.0;
    for i in 0..values.len() {
        let error = values[i] - td_target[i];
        total += error;
    }
    total / values.len() as f32
}
