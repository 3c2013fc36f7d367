//! Reference solution for lesson 12: CleanRL's clipped value loss (`cleanrl/ppo.py`,
//! `clip_vloss`).

/// `0.5 · mean_i max((v_i − R_i)², (v̂_i − R_i)²)` with
/// `v̂_i = old_i + clamp(v_i − old_i, −ε, ε)`: the prediction held within ε of the one made
/// before the update. The max keeps the worse of the two errors, so the clip only takes the
/// gradient away from a row whose move past ε brought it closer to its target.
pub fn clipped_value_loss(values: &[f32], old_values: &[f32], returns: &[f32], eps: f32) -> f32 {
    let mut total = 0.0_f32;
    for ((&v, &old), &ret) in values.iter().zip(old_values).zip(returns) {
        let unclipped = (v - ret) * (v - ret);
        let v_clipped = old + (v - old).clamp(-eps, eps);
        let clipped = (v_clipped - ret) * (v_clipped - ret);
        total += unclipped.max(clipped);
    }
    0.5 * (total / values.len() as f32)
}
