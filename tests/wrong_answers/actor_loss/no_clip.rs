pub fn actor_loss(ratio: &[f32], advantage: &[f32], eps: f32) -> f32 {
    let mut total = 0.0;
    for i in 0..ratio.len() {
        let (r, a) = (ratio[i], advantage[i]);
        total += -(r * a);
    }
    total / ratio.len() as f32
}
