pub fn clipped_value_loss(values: &[f32], old_values: &[f32], returns: &[f32], eps: f32) -> f32 {
    let mut total = 0.0;
    for i in 0..values.len() {
        let v_clipped = old_values[i] + (values[i] - old_values[i]).clamp(-eps, eps);
        total += (v_clipped - returns[i]) * (v_clipped - returns[i]);
    }
    0.5 * (total / values.len() as f32)
}
