//! Wrong on purpose: no clipping at all (the vanilla policy-gradient surrogate).

use candle_core::{Result, Tensor};

pub fn ppo_losses(
    probs: &Tensor,
    actions: &Tensor,
    old_log_probs: &Tensor,
    advantage: &Tensor,
    values: &Tensor,
    td_target: &Tensor,
    eps: f64,
) -> Result<(Tensor, Tensor)> {
    let _ = eps;
    let log_probs = probs.gather(actions, 1)?.log()?;
    let ratio = (log_probs - old_log_probs)?.exp()?;
    let actor_loss = (ratio * advantage)?.mean_all()?.neg()?;
    let critic_loss = (values - td_target.detach())?.sqr()?.mean_all()?;
    Ok((actor_loss, critic_loss))
}
