//! PPO-Penalty (the book's PPO-惩罚): the actor's loss with a KL term in place of the clip,
//! and the adaptive coefficient β ([`PpoConfig::objective`](super::PpoConfig::objective)
//! `= penalty`).
//!
//! For one update on `N` transitions, with `π_old` the actor before its first step:
//!
//! ```text
//! kl_t        = Σ_a π_old(a|s_t) · (log π_old(a|s_t) − log π_θ(a|s_t))    (N, 1), exact
//! actor_loss  = −mean(ratio · Â) + β · mean(kl)                            scalar, each epoch
//! after the update's last epoch, d = mean_t kl_t under the updated actor, and
//!     β ← β / 2   if d < δ / 1.5
//!     β ← 2 · β   if d > 1.5 · δ
//!     β           otherwise
//! ```
//!
//! β starts at `beta_init` (β₀ = 1) and is the agent's state from update to update; δ is
//! `kl_delta` (0.01). The KL is the exact one between the two categorical distributions over
//! CartPole's two actions, as PyTorch computes it (`log` of the softmax, no floor: a
//! probability that underflowed to 0 makes it NaN there and here, reported as
//! [`PpoError::NonFinite`](crate::ppo::PpoError::NonFinite)). The critic's update is the
//! seed's.
//!
//! ```
//! use ppo_rl::ppo::discrete::penalty::adapt_beta;
//!
//! assert_eq!(adapt_beta(1.0, 0.001, 0.01), 0.5); // far inside: the penalty relaxes
//! assert_eq!(adapt_beta(1.0, 0.01, 0.01), 1.0); // on target: unchanged
//! assert_eq!(adapt_beta(1.0, 0.02, 0.01), 2.0); // too far: the penalty doubles
//! ```

use candle_core::Tensor;

/// The exact `KL(π_old(·|s) ‖ π_θ(·|s))` of each row: `old_probs` and `probs` are `(N, A)`
/// action probabilities, the result `(N, 1)`, `Σ_a old · (log old − log new)` as PyTorch's
/// `torch.sum(old_probs * (torch.log(old_probs) - torch.log(probs)), dim=1, keepdim=True)`.
/// Gradients flow through `probs` (detach `old_probs`).
///
/// # Errors
/// Only if a candle operation fails (shapes that differ).
pub fn categorical_kl(old_probs: &Tensor, probs: &Tensor) -> candle_core::Result<Tensor> {
    // ANCHOR: categorical_kl
    (old_probs * (old_probs.log()? - probs.log()?)?)?.sum_keepdim(1)
    // ANCHOR_END: categorical_kl
}

/// PPO-Penalty's actor loss from `surr1 = ratio · Â` and the rows' `kl`, both `(N, 1)`:
/// `−mean(surr1) + β · mean(kl)`, PyTorch's `-torch.mean(ratio * advantage) + beta *
/// torch.mean(kl)` (before any entropy bonus).
///
/// # Errors
/// Only if a candle operation fails.
pub fn penalty_actor_loss(surr1: &Tensor, kl: &Tensor, beta: f64) -> candle_core::Result<Tensor> {
    // ANCHOR: penalty_loss
    let surrogate = surr1.mean_all()?.neg()?; // −mean(ratio · Â), no clip
    let penalty = (kl.mean_all()? * beta)?; // β · mean(KL)
    surrogate + penalty
    // ANCHOR_END: penalty_loss
}

// ANCHOR: adapt_beta
/// The adaptive β after an update whose mean KL under the updated actor was `kl`, with
/// target `delta` (δ): halved below `δ / 1.5`, doubled above `1.5 · δ`, else kept.
#[must_use]
pub fn adapt_beta(beta: f64, kl: f64, delta: f64) -> f64 {
    if kl < delta / 1.5 {
        beta / 2.0 // the policy barely moved: penalise less
    } else if kl > delta * 1.5 {
        beta * 2.0 // it moved too far: penalise more
    } else {
        beta
    }
}
// ANCHOR_END: adapt_beta

#[cfg(test)]
mod tests {
    use candle_core::Device;

    use super::*;
    use crate::ppo::discrete::{Agent, Objective, PpoConfig, Transitions};
    use crate::ppo::{PpoError, UpdatePath};

    fn penalty() -> PpoConfig {
        PpoConfig {
            objective: Objective::Penalty,
            ..PpoConfig::default()
        }
    }

    /// Twenty made-up transitions, the last one the end of the episode.
    fn batch() -> Transitions {
        let mut batch = Transitions::default();
        for t in 0..20_u8 {
            let x = f32::from(t) * 0.01;
            let state = [x, -x, 0.5 * x, 0.1];
            let next = [x + 0.01, -x, 0.5 * x, 0.1];
            batch.push(state, usize::from(t % 2), 1.0, next, t == 19, t == 19);
        }
        batch
    }

    /// β starts at `beta_init` and each update starts from where the last one left it; the
    /// trace records the KL per row and per epoch, and the loss is the penalty's.
    #[test]
    fn beta_is_the_agents_state_from_update_to_update() -> Result<(), PpoError> {
        let config = PpoConfig {
            beta_init: 0.5,
            ..penalty()
        };
        let mut agent = Agent::new(&config, 0)?;
        assert_eq!(agent.beta(), 0.5);
        let batch = batch();
        let mut beta = 0.5;
        for _ in 0..3 {
            let trace = agent.update(&batch)?;
            assert_eq!(trace.path, UpdatePath::Candle, "PPO-Penalty runs on candle");
            let p = trace
                .penalty
                .ok_or(PpoError::NonFinite("no penalty".into()))?;
            assert_eq!(p.beta_before, beta);
            assert_eq!(
                p.beta_after,
                adapt_beta(beta, f64::from(p.kl_after), config.kl_delta)
            );
            assert!(p.kl_after > 0.0);
            beta = p.beta_after;
            assert_eq!(agent.beta(), beta);
            for e in &trace.epochs {
                assert_eq!(e.kl.len(), batch.len());
                let kl_mean = e.kl_mean.unwrap_or(f32::NAN);
                let mean = e.kl.iter().sum::<f32>() / e.kl.len() as f32;
                assert!((kl_mean - mean).abs() <= 1e-6 * mean.abs().max(1e-3));
                let surrogate = -e.surr1.iter().sum::<f32>() / e.surr1.len() as f32;
                let want = surrogate + p.beta_before as f32 * kl_mean;
                assert!(
                    (e.actor_loss - want).abs() < 1e-5,
                    "{} vs {want}",
                    e.actor_loss
                );
            }
            assert!(trace.epochs[0].kl.iter().all(|&k| k == 0.0), "π = π_old");
        }
        // the clip records none of it
        let trace = Agent::new(&PpoConfig::default(), 0)?.update(&batch)?;
        assert!(trace.penalty.is_none());
        assert!(
            trace
                .epochs
                .iter()
                .all(|e| e.kl.is_empty() && e.kl_mean.is_none())
        );
        Ok(())
    }

    /// The seed's configuration serialises as before (no new keys), so saved settings and
    /// JSON outputs are unchanged; PPO-Penalty's settings are checked.
    #[test]
    fn the_switch_defaults_to_the_clip_and_its_settings_are_checked() {
        let seed = PpoConfig::default();
        assert_eq!(seed.objective, Objective::Clip);
        let json = serde_json::to_value(&seed).unwrap_or_default();
        for key in ["objective", "beta_init", "kl_delta"] {
            assert!(json.get(key).is_none(), "{key} in {json}");
        }
        let back: PpoConfig = serde_json::from_value(json).unwrap_or_default();
        assert_eq!(back, seed);
        let json = serde_json::to_value(penalty()).unwrap_or_default();
        assert_eq!(json["objective"], "penalty");
        let back: PpoConfig = serde_json::from_value(json).unwrap_or_default();
        assert_eq!(back, penalty());
        for (field, value) in [
            ("beta_init", 0.0),
            ("beta_init", f64::INFINITY),
            ("kl_delta", -0.01),
            ("kl_delta", f64::NAN),
        ] {
            let mut c = penalty();
            match field {
                "beta_init" => c.beta_init = value,
                _ => c.kl_delta = value,
            }
            let err = c
                .validate()
                .err()
                .map(|e| e.to_string())
                .unwrap_or_default();
            assert!(err.contains(field), "{field} = {value}: {err}");
        }
        let mut agent = Agent::new(&penalty(), 0).ok();
        let refused = agent.as_mut().map(|a| a.set_beta(-1.0).is_err());
        assert_eq!(refused, Some(true));
    }

    /// Each branch, and each boundary on the side the rule puts it (`<` and `>` are strict).
    #[test]
    fn beta_halves_below_doubles_above_and_keeps_between() {
        let delta = 0.01;
        let low = delta / 1.5;
        let high = delta * 1.5;
        let below = |x: f64| f64::from_bits(x.to_bits() - 1);
        let above = |x: f64| f64::from_bits(x.to_bits() + 1);
        for (kl, want) in [
            (0.0, 0.5),
            (below(low), 0.5),
            (low, 1.0),
            (delta, 1.0),
            (high, 1.0),
            (above(high), 2.0),
            (1.0, 2.0),
        ] {
            assert_eq!(adapt_beta(1.0, kl, delta), want, "kl = {kl:e}");
        }
        // β is the agent's state: it moves from wherever it is.
        assert_eq!(adapt_beta(0.25, 0.0, delta), 0.125);
        assert_eq!(adapt_beta(0.25, 0.5, delta), 0.5);
        assert_eq!(adapt_beta(3.0, 0.009, 0.009), 3.0);
        // NaN is neither below nor above: β stays (the update reports the NaN itself).
        assert_eq!(adapt_beta(1.0, f64::NAN, delta), 1.0);
    }

    #[test]
    fn the_kl_is_zero_for_the_same_policy_and_the_formula_otherwise()
    -> Result<(), Box<dyn std::error::Error>> {
        let dev = &Device::Cpu;
        let old = Tensor::new(&[[0.5_f32, 0.5], [0.9, 0.1]], dev)?;
        let same = categorical_kl(&old, &old)?
            .flatten_all()?
            .to_vec1::<f32>()?;
        assert_eq!(same, [0.0, 0.0]);
        let new = Tensor::new(&[[0.25_f32, 0.75], [0.5, 0.5]], dev)?;
        let kl = categorical_kl(&old, &new)?;
        assert_eq!(kl.dims(), [2, 1]);
        let kl = kl.flatten_all()?.to_vec1::<f32>()?;
        let want = |p: [f64; 2], q: [f64; 2]| {
            p[0] * (p[0].ln() - q[0].ln()) + p[1] * (p[1].ln() - q[1].ln())
        };
        for (got, want) in kl
            .iter()
            .zip([want([0.5, 0.5], [0.25, 0.75]), want([0.9, 0.1], [0.5, 0.5])])
        {
            assert!((f64::from(*got) - want).abs() < 1e-6, "{got} vs {want}");
            assert!(*got > 0.0);
        }
        Ok(())
    }
}
