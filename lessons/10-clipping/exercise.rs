//! Lesson 10 exercise: PPO's clipped surrogate loss.
//!
//! Grade: `ppo-tutor grade actor_loss` (or `g` in the tutor).
//! Start over: `ppo-tutor reset actor_loss`.

/// The seed's `actor_loss = torch.mean(-torch.min(surr1, surr2))` with
/// `surr1 = ratio * advantage` and `surr2 = torch.clamp(ratio, 1 - eps, 1 + eps) * advantage`.
pub fn actor_loss(ratio: &[f32], advantage: &[f32], eps: f32) -> f32 {
    // TODO: for each row compute surr1 and surr2 as above, keep the smaller one, flip its
    // sign (the optimizer minimises), and return the mean over the rows.
    todo!()
}
