//! Lesson 12 exercise on candle tensors: one epoch's two losses, which the grader then
//! plugs into the agent to train CartPole.
//!
//! Grade: `ppo-tutor grade ppo_losses` (or `g` in the tutor). The grader compiles this file
//! against candle-core and candle-nn (the first time takes a few minutes), compares your
//! losses and their gradients with the seed's, then trains CartPole with your losses.
//! Start over: `ppo-tutor reset ppo_losses`.

use candle_core::{Result, Tensor};

/// One epoch's two losses, the numbers the agent calls `backward()` on: the seed's loop body,
/// from the log-probabilities to both losses, on candle tensors.
///
/// The actor loss is PPO's clipped surrogate, with its sign flipped so that minimising it
/// improves the policy: it makes actions with a positive advantage more likely and those with
/// a negative advantage less likely, but stops rewarding a row once its ratio has left the band
/// `[1 − ε, 1 + ε]` in the direction its advantage wants. The critic loss measures how far the
/// critic's predictions are from their TD targets; minimising it is the critic's regression.
/// You have the pieces: the ratio (lesson 9), the clip and the minimum (lesson 11), the
/// critic's squared error (this lesson). Here you write both losses on tensors for the first
/// time, the whole episode one batch.
///
/// Inputs, for an episode of N steps (N can be 1):
/// - `probs` is `self.actor(states)`, (N, 2) of f32: each row the current policy's
///   probabilities of CartPole's two actions.
/// - `actions` is (N, 1) of u32: the action taken on each step, 0 or 1.
/// - `old_log_probs` is (N, 1) of f32: the log-probability of each action taken under the
///   policy that played the episode. A constant.
/// - `advantage` is (N, 1) of f32: each step's GAE advantage (lesson 8). A constant.
/// - `values` is `self.critic(states)`, (N, 1) of f32: the critic's current predictions.
/// - `td_target` is (N, 1) of f32: the TD targets computed before the epochs (lesson 7).
/// - `eps` is the clip range ε (0.2 in the seed).
///
/// Return `(actor_loss, critic_loss)`, both scalars (shape `[]`), each averaged over the N
/// steps as the seed does. Compute them with tensor operations all the way: the gradients must
/// flow back to `probs` and `values`, and none may flow into `td_target`. The grader compares
/// your losses and their gradients with the seed's, on recorded episodes, random batches and
/// edge cases (a single step, only negative advantages with every ratio outside the band,
/// every ratio exactly 1), then trains CartPole with your function.
///
/// Pass bar: each loss within 1e-5 absolute plus 1e-4 relative of the seed's, and each weight
/// gradient within 1e-5 plus 1e-3 of its parameter's largest gradient, on the recorded PyTorch
/// episodes at epochs 0, 4 and 9, 60 seeded random batches and the edge cases; then, training
/// CartPole with your losses (seed 0, 200 episodes), the mean of the last 20 returns must
/// reach 150. The seed's losses reach about 400 there; losses that push the wrong way stay at a
/// random policy's 9 to 29.
///
/// Taught in lesson 12 (losses), step 1 "The actor loss", step 2 "The critic loss" and step 3
/// "Why the target is detached"; the ratio in lesson 9 (ratio), step 3 "The ratio"; the clip
/// in lesson 11 (clipping), steps 1 to 3, "Two surrogates" to "Taking the minimum".
pub fn ppo_losses(
    probs: &Tensor,
    actions: &Tensor,
    old_log_probs: &Tensor,
    advantage: &Tensor,
    values: &Tensor,
    td_target: &Tensor,
    eps: f64,
) -> Result<(Tensor, Tensor)> {
    // TODO: your code here; `h` in the tutor reveals hints one by one.
    // Which of these inputs are constants for the optimizer, and which must stay in the graph?
    todo!()
}
