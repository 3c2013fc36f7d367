//! Reference solution for lesson 10: the clipped surrogate,
//! `actor_loss = torch.mean(-torch.min(surr1, surr2))`.

/// `mean_i -min(ratio[i] * advantage[i], clamp(ratio[i], 1 - eps, 1 + eps) * advantage[i])`.
pub fn actor_loss(ratio: &[f32], advantage: &[f32], eps: f32) -> f32 {
    let mut total = 0.0_f32;
    for (&r, &a) in ratio.iter().zip(advantage) {
        let surr1 = r * a;
        let surr2 = r.clamp(1.0 - eps, 1.0 + eps) * a;
        total += -surr1.min(surr2);
    }
    total / ratio.len() as f32
}
