//! Wrong on purpose: the ratio computed in plain Rust and put back, so no gradient reaches the actor.

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
    let picked = probs.gather(actions, 1)?.flatten_all()?.to_vec1::<f32>()?;
    let old = old_log_probs.flatten_all()?.to_vec1::<f32>()?;
    let ratios: Vec<f32> = picked
        .iter()
        .zip(&old)
        .map(|(p, o)| (p.ln() - o).exp())
        .collect();
    let n = ratios.len();
    let ratio = Tensor::from_vec(ratios, (n, 1), probs.device())?;
    let surr1 = (&ratio * advantage)?;
    let surr2 = (ratio.clamp(1.0 - eps, 1.0 + eps)? * advantage)?;
    let actor_loss = surr1.minimum(&surr2)?.neg()?.mean_all()?;
    let critic_loss = (values - td_target.detach())?.sqr()?.mean_all()?;
    Ok((actor_loss, critic_loss))
}
