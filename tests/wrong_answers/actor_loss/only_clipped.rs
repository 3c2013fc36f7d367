pub fn actor_loss(ratio: &[f32], advantage: &[f32], eps: f32) -> f32 {
    let mut total = 0.0;
    for i in 0..ratio.len() {
        let (r, a) = (ratio[i], advantage[i]);
        let surr2 = r.clamp(1.0 - eps, 1.0 + eps) * a;
        total += -surr2;
    }
    total / ratio.len() as f32
}
