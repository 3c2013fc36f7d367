//! Lesson 11 exercise: the critic's loss.
//!
//! Grade: `ppo-tutor grade critic_loss` (or `g` in the tutor).
//! Start over: `ppo-tutor reset critic_loss`.

/// The seed's `torch.mean(F.mse_loss(self.critic(states), td_target.detach()))`, where
/// `values[i]` is `V(s_i)`.
pub fn critic_loss(values: &[f32], td_target: &[f32]) -> f32 {
    // TODO: the mean over the rows of the squared difference between the critic's
    // prediction and the TD target.
    todo!()
}
