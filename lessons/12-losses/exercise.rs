//! Lesson 12 exercise: CleanRL's clipped value loss, the clip applied to the critic.
//!
//! Grade: `ppo-tutor grade clipped_value_loss` (or `g` in the tutor).
//! Start over: `ppo-tutor reset clipped_value_loss`.

/// The critic's loss as CleanRL computes it when `clip_vloss` is on (its default): the
/// regression of lesson 12, with PPO's clip turned on the critic.
///
/// The seed lets each epoch move a prediction as far towards its target as the gradient
/// takes it. CleanRL treats the critic as PPO treats the actor: a prediction that moves more
/// than `eps` away from the one the critic made before the update gets no credit for the
/// extra distance, and, as in the actor's clipped objective, the loss stays pessimistic: the
/// clip may never make a row look better than it is. Work out what that means row by row.
///
/// - `values[i]` is the current critic's prediction `V(s_i)`, the only input that depends on
///   the weights being trained.
/// - `old_values[i]` is the prediction made for the same state before the update started
///   (CleanRL's `b_values`), fixed during the update.
/// - `returns[i]` is the row's regression target (CleanRL's `b_returns`), fixed too.
/// - `eps` is the clip range (CleanRL reuses the actor's `clip_coef`, 0.2), in the units
///   of the values.
///
/// All three slices have the same length, at least one. Return one number at CleanRL's scale:
/// its `v_loss` keeps a factor ½ in front of the mean over the rows. The grader tries
/// predictions inside and outside the range, targets on either side, and a single row, to
/// 1e-5 absolute and 1e-4 relative.
///
/// Taught in lesson 12 (losses), step 2 "The critic loss", with lesson 11's clip.
pub fn clipped_value_loss(values: &[f32], old_values: &[f32], returns: &[f32], eps: f32) -> f32 {
    // TODO: your code here; `h` in the tutor reveals hints one by one.
    // A prediction moved 3·eps closer to its target: how much of that move should count?
    todo!()
}
