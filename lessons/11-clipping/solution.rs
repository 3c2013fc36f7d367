//! Reference solution for lesson 11: which rows of dual-clip PPO's objective (Ye et al.
//! 2020) have a zero gradient with respect to the ratio.

/// Whether each row's term has zero derivative with respect to `r`, following PyTorch's
/// autograd. For Â ≥ 0 the term is PPO's `min(r·Â, clamp(r, 1 − ε, 1 + ε)·Â)`; for Â < 0
/// the dual clip bounds it from below, `max(min(r·Â, clamp(r, 1 − ε, 1 + ε)·Â), c·Â)`.
/// `clamp` passes the gradient at its bounds, and `max` of two equal values passes half
/// to each.
pub fn zero_gradient_rows(ratio: &[f32], advantage: &[f32], eps: f32, c: f32) -> Vec<bool> {
    let (low, high) = (1.0 - eps, 1.0 + eps);
    ratio
        .iter()
        .zip(advantage)
        .map(|(&r, &a)| {
            // A zero advantage makes every term flat in r. For a positive one the min picks
            // the constant clipped term above the band. For a negative one the min is
            // constant below the band, and past r = c the max picks the constant bound c·Â
            // (at r = c exactly the tie still passes half of r·Â's slope).
            a == 0.0 || (a > 0.0 && r > high) || (a < 0.0 && (r < low || r > c))
        })
        .collect()
}
