//! Reference solution for lesson 11: which rows of the clipped surrogate
//! `torch.min(surr1, surr2)` have a zero gradient with respect to the ratio.

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
