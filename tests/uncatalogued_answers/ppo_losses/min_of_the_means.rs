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
    let log_probs = probs.gather(actions, 1)?.log()?;
    let ratio = (&log_probs - old_log_probs)?.exp()?;
    let surr1 = (&ratio * advantage)?;
    let surr2 = (ratio.clamp(1.0 - eps, 1.0 + eps)? * advantage)?;
    // The minimum of the two batch means, not the mean of the rows' minima.
    let actor_loss = surr1.mean_all()?.minimum(&surr2.mean_all()?)?.neg()?;
    let critic_loss = (values - td_target.detach())?.sqr()?.mean_all()?;
    Ok((actor_loss, critic_loss))
}
