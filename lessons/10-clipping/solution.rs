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

/// Whether each row's term `min(r·Â, clamp(r, 1 − ε, 1 + ε)·Â)` has zero derivative with
/// respect to `r`, following PyTorch's autograd: `clamp` passes the gradient at its bounds,
/// and `min` of two equal values passes half to each.
pub fn zero_gradient_rows(ratio: &[f32], advantage: &[f32], eps: f32) -> Vec<bool> {
    let (low, high) = (1.0 - eps, 1.0 + eps);
    ratio
        .iter()
        .zip(advantage)
        .map(|(&r, &a)| {
            // A zero advantage makes both surrogates flat in r. Otherwise the min picks the
            // clipped term, whose clamp is flat, only past the bound on the advantage's side.
            a == 0.0 || (a > 0.0 && r > high) || (a < 0.0 && r < low)
        })
        .collect()
}
