//! Typical wrong answers to `ppo_losses`, each a complete losses function with the hint
//! that names it. A mistake concerns one of the two losses (its [`Part`]) and computes the
//! other one right, so the grader can name a mistake in each loss separately.

use candle_core::{Result, Tensor};

use crate::grade::solutions::losses_candle::ppo_losses as reference;

use super::protocol::LossesFn;

/// Which loss a mistake gets wrong.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Part {
    /// The actor loss (and its gradient into the actor).
    Actor,
    /// The critic loss (and its gradient into the critic).
    Critic,
}

/// A typical wrong answer and the hint that names it.
#[derive(Debug, Clone, Copy)]
pub struct Mistake {
    /// A stable id (the file stem of its wrong answer in `tests/wrong_answers/ppo_losses/`).
    pub id: &'static str,
    /// The loss it gets wrong.
    pub part: Part,
    /// The hint, starting with the mistake's name.
    pub hint: &'static str,
    /// The wrong function.
    pub answer: LossesFn,
}

fn log_probs(probs: &Tensor, actions: &Tensor) -> Result<Tensor> {
    probs.gather(actions, 1)?.log()
}

fn seed_ratio(probs: &Tensor, actions: &Tensor, old_log_probs: &Tensor) -> Result<Tensor> {
    (log_probs(probs, actions)? - old_log_probs)?.exp()
}

fn seed_critic(values: &Tensor, td_target: &Tensor) -> Result<Tensor> {
    (values - td_target.detach())?.sqr()?.mean_all()
}

/// `mean(-min(ratio·Â, clamp(ratio, 1 − ε, 1 + ε)·Â))` for a given (possibly wrong) ratio.
fn clipped_loss(ratio: &Tensor, advantage: &Tensor, eps: f64) -> Result<Tensor> {
    let surr1 = (ratio * advantage)?;
    let surr2 = (ratio.clamp(1.0 - eps, 1.0 + eps)? * advantage)?;
    surr1.minimum(&surr2)?.neg()?.mean_all()
}

/// The seed's critic loss with a wrong actor loss from `actor(ratio, advantage, eps)`.
macro_rules! actor_mistake {
    (|$r:ident, $probs:ident, $actions:ident, $old:ident, $adv:ident, $eps:ident| $body:expr) => {
        |$probs, $actions, $old, $adv, values, td_target, $eps| {
            let _ = (&$probs, &$actions, &$old, &$adv, &$eps);
            let $r = seed_ratio($probs, $actions, $old)?;
            let _ = &$r;
            Ok(($body, seed_critic(values, td_target)?))
        }
    };
}

/// The seed's actor loss with a wrong critic loss `body` of `values` and `td_target`.
macro_rules! critic_mistake {
    (|$values:ident, $td:ident| $body:expr) => {
        |probs, actions, old, adv, $values, $td, eps| {
            let (actor, _) = reference(probs, actions, old, adv, $values, $td, eps)?;
            Ok((actor, $body))
        }
    };
}

/// The catalogue, actor mistakes first.
pub const MISTAKES: &[Mistake] = &[
    Mistake {
        id: "no_minus_sign",
        part: Part::Actor,
        hint: "The actor loss without its minus sign: PPO maximises mean(min(surr1, surr2)) \
               and the optimizer minimises, so the loss is mean(-min(surr1, surr2)); without \
               the minus, training makes good actions less likely.",
        answer: actor_mistake!(|r, p, a, o, adv, eps| {
            let surr1 = (&r * adv)?;
            let surr2 = (r.clamp(1.0 - eps, 1.0 + eps)? * adv)?;
            surr1.minimum(&surr2)?.mean_all()?
        }),
    },
    Mistake {
        id: "max_instead_of_min",
        part: Part::Actor,
        hint: "max instead of min: the clipped surrogate is the pessimistic one, \
               min(surr1, surr2) (minimum), so a ratio that ran past the band in the \
               advantage's favour gets no further reward.",
        answer: actor_mistake!(|r, p, a, o, adv, eps| {
            let surr1 = (&r * adv)?;
            let surr2 = (r.clamp(1.0 - eps, 1.0 + eps)? * adv)?;
            surr1.maximum(&surr2)?.neg()?.mean_all()?
        }),
    },
    Mistake {
        id: "clamp_on_advantage",
        part: Part::Actor,
        hint: "The clamp is applied to the advantage instead of the ratio: surr2 = \
               clamp(ratio, 1 - eps, 1 + eps) * advantage.",
        answer: actor_mistake!(|r, p, a, o, adv, eps| {
            let surr1 = (&r * adv)?;
            let surr2 = (&r * adv.clamp(1.0 - eps, 1.0 + eps)?)?;
            surr1.minimum(&surr2)?.neg()?.mean_all()?
        }),
    },
    Mistake {
        id: "unclipped",
        part: Part::Actor,
        hint: "No clipping: the loss uses surr1 = ratio * advantage alone; PPO takes \
               min(surr1, surr2) with surr2 = clamp(ratio, 1 - eps, 1 + eps) * advantage.",
        answer: actor_mistake!(|r, p, a, o, adv, eps| (&r * adv)?.neg()?.mean_all()?),
    },
    Mistake {
        id: "ratio_without_exp",
        part: Part::Actor,
        hint: "The ratio without exp: log_probs - old_log_probs is the log of the ratio; \
               ratio = exp(log_probs - old_log_probs), which is π/π_old.",
        answer: actor_mistake!(|r, p, a, o, adv, eps| {
            let ratio = (log_probs(p, a)? - o)?;
            clipped_loss(&ratio, adv, eps)?
        }),
    },
    Mistake {
        id: "ratio_inverted",
        part: Part::Actor,
        hint: "The ratio is inverted: exp(old_log_probs - log_probs) is π_old/π; the ratio \
               is exp(log_probs - old_log_probs), the new policy over the old one.",
        answer: actor_mistake!(|r, p, a, o, adv, eps| {
            let ratio = (o - log_probs(p, a)?)?.exp()?;
            clipped_loss(&ratio, adv, eps)?
        }),
    },
    Mistake {
        id: "no_log",
        part: Part::Actor,
        hint: "The log is missing: gather picks the action's probability, and \
               log_probs = log(gather(probs)); old_log_probs is a log too.",
        answer: actor_mistake!(|r, p, a, o, adv, eps| {
            let ratio = (p.gather(a, 1)? - o)?.exp()?;
            clipped_loss(&ratio, adv, eps)?
        }),
    },
    Mistake {
        id: "actor_sum",
        part: Part::Actor,
        hint: "sum instead of mean in the actor loss: the seed averages over the steps \
               (torch.mean), so the step size does not grow with the episode's length.",
        answer: actor_mistake!(|r, p, a, o, adv, eps| {
            let surr1 = (&r * adv)?;
            let surr2 = (r.clamp(1.0 - eps, 1.0 + eps)? * adv)?;
            surr1.minimum(&surr2)?.neg()?.sum_all()?
        }),
    },
    Mistake {
        id: "ratio_detached",
        part: Part::Actor,
        hint: "No gradient reaches the actor: the loss has the right value, but the ratio \
               was cut from the graph (detach, or numbers taken out with to_vec and put \
               back); compute it from probs with tensor operations all the way.",
        answer: actor_mistake!(|r, p, a, o, adv, eps| clipped_loss(&r.detach(), adv, eps)?),
    },
    Mistake {
        id: "target_not_detached",
        part: Part::Critic,
        hint: "td_target is not detached: the loss has the right value, but its gradient \
               also moves V(s_{t+1}) inside the target towards V(s_t); use \
               td_target.detach(), as the seed does.",
        answer: critic_mistake!(|v, td| (v - td)?.sqr()?.mean_all()?),
    },
    Mistake {
        id: "critic_rms",
        part: Part::Critic,
        hint: "A root-mean-square critic loss: F.mse_loss is the mean of the squared \
               errors, with no square root.",
        answer: critic_mistake!(|v, td| (v - td.detach())?.sqr()?.mean_all()?.sqrt()?),
    },
    Mistake {
        id: "critic_sum",
        part: Part::Critic,
        hint: "sum instead of mean in the critic loss: F.mse_loss averages the squared \
               errors over the steps.",
        answer: critic_mistake!(|v, td| (v - td.detach())?.sqr()?.sum_all()?),
    },
    Mistake {
        id: "critic_half",
        part: Part::Critic,
        hint: "Half the mean squared error (CleanRL's 0.5 * v_loss): the seed's F.mse_loss \
               has no 1/2, and the critic's steps would be half the size.",
        answer: critic_mistake!(|v, td| ((v - td.detach())?.sqr()?.mean_all()? * 0.5)?),
    },
];

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ids_are_unique() {
        let mut ids: Vec<&str> = MISTAKES.iter().map(|m| m.id).collect();
        ids.sort_unstable();
        ids.dedup();
        assert_eq!(ids.len(), MISTAKES.len());
    }

    #[test]
    fn the_seed_ratio_and_critic_are_the_reference() -> Result<()> {
        let dev = &candle_core::Device::Cpu;
        let probs = Tensor::new(&[[0.3_f32, 0.7], [0.6, 0.4]], dev)?;
        let actions = Tensor::new(&[[1_u32], [0]], dev)?;
        let old = Tensor::new(&[[-0.5_f32], [-0.4]], dev)?;
        let adv = Tensor::new(&[[1.0_f32], [-2.0]], dev)?;
        let values = Tensor::new(&[[3.0_f32], [1.0]], dev)?;
        let td = Tensor::new(&[[2.5_f32], [1.5]], dev)?;
        let (a, c) = reference(&probs, &actions, &old, &adv, &values, &td, 0.2)?;
        let r = seed_ratio(&probs, &actions, &old)?;
        assert_eq!(
            clipped_loss(&r, &adv, 0.2)?.to_scalar::<f32>()?,
            a.to_scalar::<f32>()?
        );
        assert_eq!(
            seed_critic(&values, &td)?.to_scalar::<f32>()?,
            c.to_scalar::<f32>()?
        );
        Ok(())
    }
}
