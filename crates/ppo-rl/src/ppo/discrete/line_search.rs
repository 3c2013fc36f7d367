//! A KL-constrained line search on the surrogate's gradient
//! ([`PpoConfig::objective`](super::PpoConfig::objective) `= line-search`): the runnable
//! stand-in for TRPO's hard KL constraint. It is not TRPO: TRPO steps along the natural
//! gradient `F⁻¹g` (a conjugate-gradient solve with the Fisher matrix `F`) and scales the
//! step to the constraint; this steps along the plain gradient `g` and only halves.
//!
//! For one update on `N` transitions, with θ_old the actor before it and the seed's
//! advantages `Â` and old log-probabilities:
//!
//! ```text
//! g      = ∇θ mean(ratio · Â) at θ = θ_old       (ratio = 1 there: the policy gradient)
//! α      = ls_max_step
//! repeat at most ls_backtracks + 1 times:
//!     θ    = θ_old + α · g / ‖g‖
//!     kl   = mean_t KL(π_old(·|s_t) ‖ π_θ(·|s_t))  exact, over CartPole's two actions
//!     gain = mean_t (ratio_t(θ) − 1) · Â_t        the surrogate's improvement
//!     accept θ if kl ≤ δ and gain > 0, else α ← α / 2
//! none accepted (or g = 0): θ = θ_old
//! ```
//!
//! One actor step per update and no Adam for the actor; δ is `kl_delta` (0.01). The
//! critic's update is the seed's (its epochs of Adam on the TD target).
//!
//! ```
//! use ppo_rl::ppo::{Agent, Objective, PpoConfig, Transitions};
//!
//! let config = PpoConfig { objective: Objective::LineSearch, ..PpoConfig::default() };
//! let mut agent = Agent::new(&config, 0)?;
//! let mut batch = Transitions::default();
//! for t in 0..20_u8 {
//!     let x = f32::from(t) * 0.01;
//!     batch.push([x, -x, 0.5 * x, 0.1], usize::from(t % 2), 1.0, [x + 0.01, -x, 0.5 * x, 0.1], t == 19, t == 19);
//! }
//! let trace = agent.update(&batch)?;
//! let search = trace.line_search.expect("the line search ran");
//! if let Some(kl) = search.kl {
//!     assert!(f64::from(kl) <= config.kl_delta); // an accepted step stays inside δ
//! }
//! # Ok::<(), ppo_rl::ppo::PpoError>(())
//! ```

use candle_core::{Tensor, Var};

use super::PpoConfig;
use super::penalty::categorical_kl;
use super::trace::LineSearchTrace;
use crate::ppo::PpoError;
use crate::ppo::model::PolicyNet;

/// The batch a line search reads, every tensor fixed before it: `states` `(N, 4)`,
/// `actions` `(N, 1)` u32, `old_log_probs` and `advantage` `(N, 1)`, `old_probs` =
/// `π_old(·|s)` `(N, 2)`, all detached.
#[derive(Debug, Clone, Copy)]
pub struct SearchBatch<'a> {
    /// `s_t`, `(N, 4)`.
    pub states: &'a Tensor,
    /// `a_t`, `(N, 1)` u32.
    pub actions: &'a Tensor,
    /// `log π_old(a_t|s_t)`, `(N, 1)`.
    pub old_log_probs: &'a Tensor,
    /// `π_old(·|s_t)`, `(N, 2)`: the KL's first argument.
    pub old_probs: &'a Tensor,
    /// `Â_t`, `(N, 1)`.
    pub advantage: &'a Tensor,
}

/// One try: the mean exact KL and the surrogate gain of the actor as it is now.
#[derive(Debug, Clone, Copy)]
struct Try {
    kl: f32,
    gain: f32,
}

/// The mean `KL(π_old ‖ π_θ)` and `mean((ratio − 1) · Â)` under the actor's current weights.
fn measure(actor: &PolicyNet, b: &SearchBatch<'_>) -> Result<Try, PpoError> {
    let probs = actor.forward(b.states)?.detach();
    let kl = categorical_kl(b.old_probs, &probs)?
        .mean_all()?
        .to_scalar::<f32>()?;
    let log_probs = probs.gather(b.actions, 1)?.log()?;
    let ratio = (&log_probs - b.old_log_probs)?.exp()?;
    let gain = ((ratio - 1.0)? * b.advantage)?
        .mean_all()?
        .to_scalar::<f32>()?;
    Ok(Try { kl, gain })
}

/// The actor's parameters in PyTorch's order (`fc1.weight`, `fc1.bias`, `fc2.weight`,
/// `fc2.bias`).
fn params(actor: &PolicyNet) -> [&Var; 4] {
    [
        &actor.fc1.weight,
        &actor.fc1.bias,
        &actor.fc2.weight,
        &actor.fc2.bias,
    ]
}

/// Whether a try is accepted: inside the trust region (`kl ≤ δ`) and an improvement of the
/// surrogate (`gain > 0`). A NaN KL or gain is refused.
#[must_use]
pub fn accepts(kl: f32, gain: f32, delta: f64) -> bool {
    f64::from(kl) <= delta && gain > 0.0
}

/// One KL line search on `actor` (which holds θ_old on entry, and the accepted θ, or θ_old
/// again, on return) with `config`'s `ls_max_step`, `ls_backtracks` and `kl_delta`.
///
/// # Errors
/// [`PpoError::Candle`] if a tensor operation fails (shapes that differ: a bug);
/// [`PpoError::NonFinite`] when the gradient is NaN or infinite (the actor is left at θ_old).
pub fn line_search(
    actor: &PolicyNet,
    b: &SearchBatch<'_>,
    config: &PpoConfig,
) -> Result<LineSearchTrace, PpoError> {
    // g = ∇θ mean(ratio · Â) at θ_old, where every ratio is 1
    let log_probs = actor.forward(b.states)?.gather(b.actions, 1)?.log()?;
    let ratio = (&log_probs - b.old_log_probs)?.exp()?;
    let surrogate = (&ratio * b.advantage)?.mean_all()?;
    let grads = surrogate.backward()?;
    let mut theta_old = Vec::with_capacity(4);
    let mut g = Vec::with_capacity(4);
    for var in params(actor) {
        theta_old.push(var.as_tensor().detach().copy()?);
        g.push(match grads.get(var.as_tensor()) {
            Some(grad) => grad.clone(),
            None => var.as_tensor().zeros_like()?, // a parameter the loss does not reach
        });
    }
    let mut squares = 0.0_f64;
    for grad in &g {
        squares += f64::from(grad.sqr()?.sum_all()?.to_scalar::<f32>()?);
    }
    let grad_norm = squares.sqrt();
    if !grad_norm.is_finite() {
        return Err(PpoError::NonFinite(crate::tr!(
            "the surrogate's gradient (norm {grad_norm}) in the KL line search",
            "KL 线搜索中替代目标的梯度（范数 {grad_norm}）"
        )));
    }
    let mut trace = LineSearchTrace {
        grad_norm: grad_norm as f32,
        first_kl: None,
        step: None,
        halvings: 0,
        kl: None,
        gain: None,
    };
    if grad_norm == 0.0 {
        return Ok(trace); // all advantages 0: no direction to step in
    }
    let delta = config.kl_delta;
    // ANCHOR: line_search
    let mut alpha = config.ls_max_step;
    for halvings in 0..=config.ls_backtracks {
        // θ = θ_old + α · g / ‖g‖
        for ((var, old), grad) in params(actor).into_iter().zip(&theta_old).zip(&g) {
            var.set(&(old + (grad * (alpha / grad_norm))?)?)?;
        }
        let Try { kl, gain } = measure(actor, b)?;
        if halvings == 0 {
            trace.first_kl = Some(kl);
        }
        if accepts(kl, gain, delta) {
            trace.step = Some(alpha);
            trace.halvings = halvings;
            trace.kl = Some(kl);
            trace.gain = Some(gain);
            return Ok(trace);
        }
        alpha /= 2.0; // too far (or no better): try half the step
    }
    // no try was accepted: the actor keeps θ_old
    for (var, old) in params(actor).into_iter().zip(&theta_old) {
        var.set(old)?;
    }
    trace.halvings = config.ls_backtracks;
    // ANCHOR_END: line_search
    Ok(trace)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ppo::discrete::{Agent, Objective, Transitions};
    use crate::ppo::{PpoError, UpdatePath};

    fn line_search() -> PpoConfig {
        PpoConfig {
            objective: Objective::LineSearch,
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

    fn no_search() -> PpoError {
        PpoError::NonFinite("no line search in the trace".into())
    }

    /// An accepted step's KL is within δ, its gain positive, its α the first step halved
    /// `halvings` times, and the uniform `kl_after` measures the same move; the actor takes
    /// no Adam step, the critic takes its ten.
    #[test]
    fn an_accepted_step_stays_inside_delta_and_improves_the_surrogate() -> Result<(), PpoError> {
        for (max_step, delta) in [(0.5, 0.01), (4.0, 0.01), (4.0, 0.001), (0.01, 0.01)] {
            let config = PpoConfig {
                ls_max_step: max_step,
                kl_delta: delta,
                ..line_search()
            };
            let mut agent = Agent::new(&config, 3)?;
            let before = agent.weights()?;
            let trace = agent.update(&batch())?;
            assert_eq!(trace.path, UpdatePath::Candle);
            let s = trace.line_search.ok_or_else(no_search)?;
            assert!(s.grad_norm > 0.0);
            let step = s.step.ok_or_else(no_search)?;
            let kl = s.kl.ok_or_else(no_search)?;
            assert!(f64::from(kl) <= delta, "α = {max_step}: {kl} > {delta}");
            assert!(s.gain.ok_or_else(no_search)? > 0.0);
            assert_eq!(step, max_step / f64::from(1_u32 << s.halvings));
            let first = s.first_kl.ok_or_else(no_search)?;
            if s.halvings == 0 {
                assert_eq!(first, kl, "the first try was the accepted one");
            }
            let after = trace.kl_after.ok_or_else(no_search)?;
            assert!(
                (after - kl).abs() <= 1e-4 * kl.max(1e-3),
                "kl_after {after} vs the search's {kl}"
            );
            assert_eq!(trace.epochs.len(), 10, "the critic's ten epochs");
            let moved = agent.weights()?;
            assert_ne!(moved["actor.fc2.weight"], before["actor.fc2.weight"]);
        }
        Ok(())
    }

    /// A first step far too long is halved, and each halving is counted: α = 64 needs
    /// several halvings on this batch, and the count matches α.
    #[test]
    fn halvings_are_counted() -> Result<(), PpoError> {
        let config = PpoConfig {
            ls_max_step: 64.0,
            ls_backtracks: 20,
            ..line_search()
        };
        let trace = Agent::new(&config, 3)?.update(&batch())?;
        let s = trace.line_search.ok_or_else(no_search)?;
        assert!(s.halvings >= 3, "{s:?}");
        assert!(f64::from(s.first_kl.ok_or_else(no_search)?) > config.kl_delta);
        assert_eq!(s.step, Some(64.0 / f64::from(1_u32 << s.halvings)));
        // With no halving allowed the same first try is refused, and the actor keeps θ_old.
        let config = PpoConfig {
            ls_backtracks: 0,
            ..config
        };
        let mut agent = Agent::new(&config, 3)?;
        let before = agent.weights()?;
        let trace = agent.update(&batch())?;
        let s = trace.line_search.ok_or_else(no_search)?;
        assert_eq!((s.step, s.kl, s.gain, s.halvings), (None, None, None, 0));
        assert!(s.first_kl.is_some());
        let after = agent.weights()?;
        for key in [
            "actor.fc1.weight",
            "actor.fc1.bias",
            "actor.fc2.weight",
            "actor.fc2.bias",
        ] {
            assert_eq!(after[key], before[key], "{key}");
        }
        assert_eq!(trace.kl_after, Some(0.0));
        Ok(())
    }

    /// No step when the advantages are all 0 (every reward and value 0: g = 0): the actor
    /// keeps θ_old and the trace says no step was tried.
    #[test]
    fn no_step_when_the_gradient_is_zero() -> Result<(), PpoError> {
        let mut batch = batch();
        batch.rewards.iter_mut().for_each(|r| *r = 0.0);
        let config = line_search();
        let agent = Agent::new(&config, 0)?;
        // a critic that predicts 0 everywhere: td_delta = 0, so Â = 0
        let mut weights = agent.weights()?;
        for key in ["critic.fc2.weight", "critic.fc2.bias"] {
            if let Some(w) = weights.get_mut(key) {
                w.data.iter_mut().for_each(|x| *x = 0.0);
            }
        }
        let mut agent = Agent::from_weights(&config, &weights, 0, "test")?;
        let before = agent.weights()?;
        let trace = agent.update(&batch)?;
        assert!(trace.advantage.iter().all(|&a| a == 0.0));
        let s = trace.line_search.ok_or_else(no_search)?;
        assert_eq!(s.grad_norm, 0.0);
        assert_eq!((s.step, s.first_kl, s.halvings), (None, None, 0));
        let after = agent.weights()?;
        assert_eq!(after["actor.fc1.weight"], before["actor.fc1.weight"]);
        assert_eq!(trace.kl_after, Some(0.0));
        Ok(())
    }

    /// The acceptance rule's boundaries: `kl = δ` is inside, a gain of 0 is no improvement,
    /// NaN is refused.
    #[test]
    fn the_rule_accepts_inside_delta_with_a_gain() {
        assert!(accepts(0.01, 1e-6, 0.01));
        assert!(!accepts(0.010_001, 1.0, 0.01));
        assert!(!accepts(0.001, 0.0, 0.01));
        assert!(!accepts(0.001, -1e-6, 0.01));
        assert!(!accepts(f32::NAN, 1.0, 0.01));
        assert!(!accepts(0.001, f32::NAN, 0.01));
    }

    /// Its settings serialise only when changed, and are checked.
    #[test]
    fn the_settings_are_checked_and_left_out_of_json_at_default() {
        let seed = PpoConfig::default();
        let json = serde_json::to_value(&seed).unwrap_or_default();
        for key in ["ls_max_step", "ls_backtracks"] {
            assert!(json.get(key).is_none(), "{key} in {json}");
        }
        let json = serde_json::to_value(line_search()).unwrap_or_default();
        assert_eq!(json["objective"], "line-search");
        let back: PpoConfig = serde_json::from_value(json).unwrap_or_default();
        assert_eq!(back, line_search());
        type Case = (fn(&mut PpoConfig), &'static str);
        let cases: [Case; 5] = [
            (|c| c.ls_max_step = 0.0, "ls_max_step"),
            (|c| c.ls_max_step = f64::NAN, "ls_max_step"),
            (|c| c.ls_max_step = -1.0, "ls_max_step"),
            (|c| c.ls_backtracks = 51, "ls_backtracks"),
            (|c| c.entropy_coef = 0.01, "entropy_coef"),
        ];
        for (set, field) in cases {
            let mut c = line_search();
            set(&mut c);
            let err = c
                .validate()
                .err()
                .map(|e| e.to_string())
                .unwrap_or_default();
            assert!(err.contains(field), "{field}: {err}");
        }
        let mut c = line_search();
        c.ls_backtracks = 0;
        assert!(c.validate().is_ok(), "no halving is allowed");
        // the entropy bonus stays allowed with the other objectives
        let c = PpoConfig {
            entropy_coef: 0.01,
            ..PpoConfig::default()
        };
        assert!(c.validate().is_ok());
    }
}
