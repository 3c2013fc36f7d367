//! Reference solution for lesson 12's candle exercise: the seed's loop body, from the
//! log-probabilities to both losses, on candle tensors.

use candle_core::{Result, Tensor};

/// The seed's
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
/// with `probs = self.actor(states)` and `values = self.critic(states)`.
pub fn ppo_losses(
    probs: &Tensor,
    actions: &Tensor,
    old_log_probs: &Tensor,
    advantage: &Tensor,
    values: &Tensor,
    td_target: &Tensor,
    eps: f64,
) -> Result<(Tensor, Tensor)> {
    let log_probs = probs.gather(actions, 1)?.log()?;
    let ratio = (&log_probs - old_log_probs)?.exp()?;
    let surr1 = (&ratio * advantage)?;
    let surr2 = (ratio.clamp(1.0 - eps, 1.0 + eps)? * advantage)?;
    let actor_loss = surr1.minimum(&surr2)?.neg()?.mean_all()?;
    let critic_loss = (values - td_target.detach())?.sqr()?.mean_all()?;
    Ok((actor_loss, critic_loss))
}
