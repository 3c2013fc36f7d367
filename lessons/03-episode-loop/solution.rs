//! Reference solution for lesson 03: sampling an action as
//! `torch.distributions.Categorical(probs).sample()` does, by the inverse CDF.

/// The first action whose cumulative probability exceeds `u` (uniform in `[0, 1)`); the
/// last action if rounding leaves the total a hair below `u`.
pub fn sample_action(probs: &[f32], u: f32) -> usize {
    let mut cumulative = 0.0_f32;
    for (action, &p) in probs.iter().enumerate() {
        cumulative += p;
        if u < cumulative {
            return action;
        }
    }
    probs.len().saturating_sub(1)
}
