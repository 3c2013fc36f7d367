//! Lesson 11 exercise on candle tensors: one epoch's two losses, which the grader then
//! plugs into the agent to train CartPole.
//!
//! Grade: `ppo-tutor grade ppo_losses` (or `g` in the tutor). The grader compiles this file
//! against candle-core and candle-nn (the first time takes a few minutes), compares your
//! losses and their gradients with the seed's, then trains CartPole with your losses.
//! Start over: `ppo-tutor reset ppo_losses`.

use candle_core::{Result, Tensor};

/// The seed's loop body, from the log-probabilities to both losses:
///
/// ```text
/// log_probs   = torch.log(self.actor(states).gather(1, actions))
/// ratio       = torch.exp(log_probs - old_log_probs)
/// surr1       = ratio * advantage
/// surr2       = torch.clamp(ratio, 1 - self.eps, 1 + self.eps) * advantage
/// actor_loss  = torch.mean(-torch.min(surr1, surr2))
/// critic_loss = torch.mean(F.mse_loss(self.critic(states), td_target.detach()))
/// ```
///
/// Shapes, for an episode of N steps: `probs = self.actor(states)` is (N, 2); `actions` is
/// (N, 1) of u32; `values = self.critic(states)` and the other columns are (N, 1) of f32.
/// Return `(actor_loss, critic_loss)`, both scalars (shape `[]`). The agent calls
/// `backward()` on each, so compute them with tensor operations all the way: gradients must
/// flow back to `probs` and `values`, and not into `td_target`.
pub fn ppo_losses(
    probs: &Tensor,
    actions: &Tensor,
    old_log_probs: &Tensor,
    advantage: &Tensor,
    values: &Tensor,
    td_target: &Tensor,
    eps: f64,
) -> Result<(Tensor, Tensor)> {
    // TODO: log_probs, (N, 1): each row's probability of the action taken (gather along
    // dimension 1), then its log.
    // TODO: ratio = exp(log_probs - old_log_probs); surr1 = ratio · advantage; surr2 = the
    // ratio clamped to [1 - eps, 1 + eps], times the advantage.
    // TODO: actor_loss, a scalar: the mean over the rows of -min(surr1, surr2).
    // TODO: critic_loss, a scalar: the mean over the rows of (values - td_target)², with the
    // target detached so no gradient flows into it.
    todo!()
}
