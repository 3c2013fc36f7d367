pub fn clipped_value_loss(values: &[f32], old_values: &[f32], returns: &[f32], eps: f32) -> f32 {
    let mut total = 0.0;
    for i in 0..values.len() {
        let unclipped = (values[i] - returns[i]) * (values[i] - returns[i]);
        let v_clipped = values[i].clamp(-eps, eps);
        let clipped = (v_clipped - returns[i]) * (v_clipped - returns[i]);
        total += unclipped.max(clipped);
    }
    0.5 * (total / values.len() as f32)
}
