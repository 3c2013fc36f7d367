//! Typical wrong answers to `ppo_losses`, each a complete losses function (the hints that
//! name them are in `lessons/12-losses/exercise.toml`). A mistake concerns one of the two losses (its [`Part`]) and computes the
//! other one right, so the grader can name a mistake in each loss separately.

use candle_core::{Result, Tensor};

use crate::solutions::losses_candle::ppo_losses as reference;

use super::protocol::LossesFn;

/// Which loss a mistake gets wrong.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Part {
    /// The actor loss (and its gradient into the actor).
    Actor,
    /// The critic loss (and its gradient into the critic).
    Critic,
}

impl Part {
    /// Both, in the judge's order.
    pub const BOTH: [Self; 2] = [Self::Actor, Self::Critic];

    /// The judge's index of the part.
    #[must_use]
    pub const fn index(self) -> usize {
        match self {
            Self::Actor => 0,
            Self::Critic => 1,
        }
    }
}

/// A typical wrong answer.
#[derive(Debug, Clone, Copy)]
pub struct LossesMistake {
    /// A stable id (the file stem of its wrong answer in `tests/wrong_answers/ppo_losses/`).
    pub id: &'static str,
    /// The loss it gets wrong.
    pub part: Part,
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
pub const MISTAKES: &[LossesMistake] = &[
    LossesMistake {
        id: "no_minus_sign",
        part: Part::Actor,
        answer: actor_mistake!(|r, p, a, o, adv, eps| {
            let surr1 = (&r * adv)?;
            let surr2 = (r.clamp(1.0 - eps, 1.0 + eps)? * adv)?;
            surr1.minimum(&surr2)?.mean_all()?
        }),
    },
    LossesMistake {
        id: "max_instead_of_min",
        part: Part::Actor,
        answer: actor_mistake!(|r, p, a, o, adv, eps| {
            let surr1 = (&r * adv)?;
            let surr2 = (r.clamp(1.0 - eps, 1.0 + eps)? * adv)?;
            surr1.maximum(&surr2)?.neg()?.mean_all()?
        }),
    },
    LossesMistake {
        id: "clamp_on_advantage",
        part: Part::Actor,
        answer: actor_mistake!(|r, p, a, o, adv, eps| {
            let surr1 = (&r * adv)?;
            let surr2 = (&r * adv.clamp(1.0 - eps, 1.0 + eps)?)?;
            surr1.minimum(&surr2)?.neg()?.mean_all()?
        }),
    },
    LossesMistake {
        id: "unclipped",
        part: Part::Actor,
        answer: actor_mistake!(|r, p, a, o, adv, eps| (&r * adv)?.neg()?.mean_all()?),
    },
    LossesMistake {
        id: "ratio_without_exp",
        part: Part::Actor,
        answer: actor_mistake!(|r, p, a, o, adv, eps| {
            let ratio = (log_probs(p, a)? - o)?;
            clipped_loss(&ratio, adv, eps)?
        }),
    },
    LossesMistake {
        id: "ratio_inverted",
        part: Part::Actor,
        answer: actor_mistake!(|r, p, a, o, adv, eps| {
            let ratio = (o - log_probs(p, a)?)?.exp()?;
            clipped_loss(&ratio, adv, eps)?
        }),
    },
    LossesMistake {
        id: "no_log",
        part: Part::Actor,
        answer: actor_mistake!(|r, p, a, o, adv, eps| {
            let ratio = (p.gather(a, 1)? - o)?.exp()?;
            clipped_loss(&ratio, adv, eps)?
        }),
    },
    LossesMistake {
        id: "actor_sum",
        part: Part::Actor,
        answer: actor_mistake!(|r, p, a, o, adv, eps| {
            let surr1 = (&r * adv)?;
            let surr2 = (r.clamp(1.0 - eps, 1.0 + eps)? * adv)?;
            surr1.minimum(&surr2)?.neg()?.sum_all()?
        }),
    },
    LossesMistake {
        id: "ratio_detached",
        part: Part::Actor,
        answer: actor_mistake!(|r, p, a, o, adv, eps| clipped_loss(&r.detach(), adv, eps)?),
    },
    LossesMistake {
        id: "target_not_detached",
        part: Part::Critic,
        answer: critic_mistake!(|v, td| (v - td)?.sqr()?.mean_all()?),
    },
    LossesMistake {
        id: "critic_rms",
        part: Part::Critic,
        answer: critic_mistake!(|v, td| (v - td.detach())?.sqr()?.mean_all()?.sqrt()?),
    },
    LossesMistake {
        id: "critic_sum",
        part: Part::Critic,
        answer: critic_mistake!(|v, td| (v - td.detach())?.sqr()?.sum_all()?),
    },
    LossesMistake {
        id: "critic_half",
        part: Part::Critic,
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
