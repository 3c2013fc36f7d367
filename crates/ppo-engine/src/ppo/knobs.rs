//! The settings of a run a learner can change, one notch at a time: [`Knob`].
//!
//! Each agent's settings list their knobs ([`Tunable::KNOBS`]) in the order the sandbox
//! shows them: the agent's own settings, each with how its value is shown and how `+`/`−`
//! changes it (steps, ladders and ranges), and where the run's seed and environment go.
//! [`RunConfig`](crate::run::RunConfig) reaches them without naming the agent
//! ([`RunConfig::knob`](crate::run::RunConfig::knob),
//! [`RunConfig::nudge`](crate::run::RunConfig::nudge)), so the sandbox is written once.
//!
//! ```
//! use ppo_engine::ppo::PpoConfig;
//! use ppo_engine::ppo::knobs::{KnobKind, Tunable};
//!
//! let mut config = PpoConfig::default();
//! let eps = PpoConfig::KNOBS.iter().find(|k| k.id == "eps").map(|k| &k.kind);
//! let Some(KnobKind::Value { show, nudge }) = eps else {
//!     unreachable!("the seed's PPO has an ε knob")
//! };
//! nudge(&mut config, true);
//! assert_eq!(show(&config), "0.25"); // the seed's 0.2, one step of 0.05 up
//! ```

use super::{AgentConfig, Algorithm, PpoConfig, PpoContinuousConfig};
use crate::i18n::t;

/// One editable setting of a run of an agent whose settings are `C`.
pub struct Knob<C> {
    /// The setting's name, as in the configuration (and the `--flag` of `ppo-tutor train`).
    pub id: &'static str,
    /// What it edits.
    pub kind: KnobKind<C>,
}

/// What a [`Knob`] edits.
pub enum KnobKind<C> {
    /// A field of the agent's configuration.
    Value {
        /// The value as the sandbox shows it.
        show: fn(&C) -> String,
        /// Changes it one notch up (`true`) or down, within its valid range.
        nudge: fn(&mut C, bool),
    },
    /// The run's seed, kept beside the configuration.
    Seed,
    /// The run's environment, chosen among
    /// [`RunConfig::choices`](crate::run::RunConfig::choices).
    Environment,
}

impl<C> Knob<C> {
    /// Where the run's seed goes among the agent's knobs.
    pub const SEED: Self = Self {
        id: "seed",
        kind: KnobKind::Seed,
    };

    /// Where the run's environment goes among the agent's knobs.
    pub const ENV: Self = Self {
        id: "env",
        kind: KnobKind::Environment,
    };

    /// A field of the configuration called `id`, shown by `show` and changed by `nudge`.
    #[must_use]
    pub const fn value(id: &'static str, show: fn(&C) -> String, nudge: fn(&mut C, bool)) -> Self {
        Self {
            id,
            kind: KnobKind::Value { show, nudge },
        }
    }
}

impl<C> std::fmt::Debug for Knob<C> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let kind = match self.kind {
            KnobKind::Value { .. } => "Value",
            KnobKind::Seed => "Seed",
            KnobKind::Environment => "Environment",
        };
        f.debug_struct("Knob")
            .field("id", &self.id)
            .field("kind", &kind)
            .finish()
    }
}

/// A knob of a run, read without the agent's type: what
/// [`RunConfig::knob`](crate::run::RunConfig::knob) returns.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum KnobValue {
    /// A setting of the agent, as the sandbox shows it.
    Value(String),
    /// The run's seed (kept outside the configuration).
    Seed,
    /// The run's environment (the configuration's Gymnasium id).
    Environment,
}

impl<C> KnobKind<C> {
    /// What the knob reads on `config`.
    pub fn read(&self, config: &C) -> KnobValue {
        match self {
            Self::Value { show, .. } => KnobValue::Value(show(config)),
            Self::Seed => KnobValue::Seed,
            Self::Environment => KnobValue::Environment,
        }
    }
}

/// The knob of `C` called `id`, if it has one.
#[must_use]
pub fn find<C: Tunable>(id: &str) -> Option<&'static Knob<C>> {
    C::KNOBS.iter().find(|k| k.id == id)
}

/// `v` one step of `by` up or down, kept in `[lo, hi]` and rounded to three decimals (ε,
/// γ, λ).
#[must_use]
pub fn step(v: f64, by: f64, lo: f64, hi: f64, up: bool) -> f64 {
    let moved = (v + if up { by } else { -by }).clamp(lo, hi);
    (moved * 1000.0).round() / 1000.0
}

/// The learning rates' next rung up or down on the 1–2–5 ladder (…, 1e-3, 2e-3, 5e-3, 1e-2,
/// …), kept in `[1e-6, 1]`: three presses make a rate ten times larger or smaller, so the
/// sandbox reaches the rates the lessons compare. A rate between rungs (3e-4, say) moves to
/// the nearest rung in that direction.
#[must_use]
pub fn lr_rung(v: f64, up: bool) -> f64 {
    const LO: f64 = 1e-6;
    const HI: f64 = 1.0;
    if !v.is_finite() || v <= LO {
        return if up { 2e-6 } else { LO };
    }
    // Rungs from 1e-7 to 10, each compared with a relative margin so that a value printed
    // and parsed back (0.001 for 1e-3) counts as on its rung.
    let rungs = (-7..=1).flat_map(|d| [1.0, 2.0, 5.0].map(|m| m * 10f64.powi(d)));
    let next = if up {
        rungs.filter(|r| *r > v * (1.0 + 1e-9)).reduce(f64::min)
    } else {
        rungs.filter(|r| *r < v * (1.0 - 1e-9)).reduce(f64::max)
    };
    next.unwrap_or(v).clamp(LO, HI)
}

/// The epochs' ladder: 1, 2, 3, 5, 10 (the seed), 20 or 40.
pub const EPOCHS: [usize; 7] = [1, 2, 3, 5, 10, 20, 40];

/// The rung of `ladder` after `v` (or before it, for `up == false`), staying on the
/// ladder's ends; a value above every rung counts as the fifth.
#[must_use]
pub fn climb(v: usize, ladder: &[usize], up: bool) -> usize {
    let at = ladder.iter().position(|&e| e >= v).unwrap_or(4);
    let to = if up {
        (at + 1).min(ladder.len().saturating_sub(1))
    } else {
        at.saturating_sub(1)
    };
    ladder.get(to).copied().unwrap_or(v)
}

/// A switch between off (`0`) and `on`, the value its source uses.
#[must_use]
pub fn toggle_amount(v: f64, on: f64) -> f64 {
    if v > 0.0 { 0.0 } else { on }
}

/// A switch between off (`None`) and `Some(on)`, the value its source uses.
#[must_use]
pub fn toggle_option(v: Option<f64>, on: f64) -> Option<f64> {
    if v.is_some() { None } else { Some(on) }
}

/// An optional value as the sandbox shows it: the number, or "off" in the current language.
#[must_use]
pub fn show_option(v: Option<f64>) -> String {
    v.map_or_else(|| t("off", "关").into(), |v| v.to_string())
}

/// A switch as the sandbox shows it: `true`/`false` as in the configuration, 开/关 in Chinese.
#[must_use]
pub fn show_switch(on: bool) -> String {
    if on {
        t("true", "开")
    } else {
        t("false", "关")
    }
    .into()
}

/// A learning rate as the sandbox shows it (`3.00e-4`).
#[must_use]
pub fn show_rate(v: f64) -> String {
    format!("{v:.2e}")
}

/// An agent's settings as the sandbox changes them: the knobs it shows.
pub trait Tunable: AgentConfig {
    /// The settings a learner can change in the sandbox, in the order it shows them, with
    /// where the run's seed and environment go ([`Knob::SEED`], [`Knob::ENV`]).
    const KNOBS: &'static [Knob<Self>];
}

impl Tunable for PpoConfig {
    /// The seed's five numbers, the seed, the CleanRL-style switches, the objective (clip,
    /// PPO-Penalty or the KL line search, with their defaults β₀ = 1, δ = 0.01, α₀ = 0.25 and
    /// 10 halvings) and the algorithm:
    /// the three switches with a value toggle between off and the value their source uses
    /// (an entropy bonus of 0.01, CleanRL's gradient clip of 0.5, Spinning Up's target KL
    /// of 0.01).
    const KNOBS: &'static [Knob<Self>] = &[
        Knob::value(
            "eps",
            |c| c.eps.to_string(),
            |c, up| {
                c.eps = step(c.eps, 0.05, 0.05, 0.95, up);
            },
        ),
        Knob::value(
            "gamma",
            |c| c.gamma.to_string(),
            |c, up| {
                c.gamma = step(c.gamma, 0.01, 0.5, 1.0, up);
            },
        ),
        Knob::value(
            "lmbda",
            |c| c.lmbda.to_string(),
            |c, up| {
                c.lmbda = step(c.lmbda, 0.05, 0.0, 1.0, up);
            },
        ),
        Knob::value(
            "actor_lr",
            |c| show_rate(c.actor_lr),
            |c, up| {
                c.actor_lr = lr_rung(c.actor_lr, up);
            },
        ),
        Knob::value(
            "critic_lr",
            |c| show_rate(c.critic_lr),
            |c, up| {
                c.critic_lr = lr_rung(c.critic_lr, up);
            },
        ),
        Knob::SEED,
        Knob::value(
            "bootstrap_on_truncation",
            |c| show_switch(c.bootstrap_on_truncation),
            |c, _| c.bootstrap_on_truncation = !c.bootstrap_on_truncation,
        ),
        Knob::value(
            "normalize_advantage",
            |c| show_switch(c.normalize_advantage),
            |c, _| c.normalize_advantage = !c.normalize_advantage,
        ),
        Knob::ENV,
        Knob::value(
            "entropy_coef",
            |c| c.entropy_coef.to_string(),
            |c, _| {
                c.entropy_coef = toggle_amount(c.entropy_coef, 0.01);
            },
        ),
        Knob::value(
            "max_grad_norm",
            |c| show_option(c.max_grad_norm),
            |c, _| {
                c.max_grad_norm = toggle_option(c.max_grad_norm, 0.5);
            },
        ),
        Knob::value(
            "target_kl",
            |c| show_option(c.target_kl),
            |c, _| {
                c.target_kl = toggle_option(c.target_kl, 0.01);
            },
        ),
        Knob::value(
            "epochs",
            |c| c.epochs.to_string(),
            |c, up| {
                c.epochs = climb(c.epochs, &EPOCHS, up);
            },
        ),
        Knob::value(
            "no_clip",
            |c| show_switch(c.no_clip),
            |c, _| c.no_clip = !c.no_clip,
        ),
        Knob::value(
            "objective",
            |c| c.objective.as_str().into(),
            |c, _| {
                c.objective = c.objective.next(); // clip → penalty → line-search → clip
            },
        ),
        Knob::value(
            "algorithm",
            |c| c.algorithm.as_str().into(),
            |c, _| {
                c.algorithm = match c.algorithm {
                    Algorithm::Ppo => Algorithm::Reinforce,
                    Algorithm::Reinforce => Algorithm::Ppo,
                };
            },
        ),
    ];
}

impl Tunable for PpoContinuousConfig {
    /// The discrete PPO's five numbers, steps and ranges, the seed, and the epochs; the
    /// discrete PPO's switches do not apply.
    const KNOBS: &'static [Knob<Self>] = &[
        Knob::value(
            "eps",
            |c| c.eps.to_string(),
            |c, up| {
                c.eps = step(c.eps, 0.05, 0.05, 0.95, up);
            },
        ),
        Knob::value(
            "gamma",
            |c| c.gamma.to_string(),
            |c, up| {
                c.gamma = step(c.gamma, 0.01, 0.5, 1.0, up);
            },
        ),
        Knob::value(
            "lmbda",
            |c| c.lmbda.to_string(),
            |c, up| {
                c.lmbda = step(c.lmbda, 0.05, 0.0, 1.0, up);
            },
        ),
        Knob::value(
            "actor_lr",
            |c| show_rate(c.actor_lr),
            |c, up| {
                c.actor_lr = lr_rung(c.actor_lr, up);
            },
        ),
        Knob::value(
            "critic_lr",
            |c| show_rate(c.critic_lr),
            |c, up| {
                c.critic_lr = lr_rung(c.critic_lr, up);
            },
        ),
        Knob::SEED,
        Knob::ENV,
        Knob::value(
            "epochs",
            |c| c.epochs.to_string(),
            |c, up| {
                c.epochs = climb(c.epochs, &EPOCHS, up);
            },
        ),
    ];
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn steps_and_ladders_stay_in_range() {
        assert_eq!(step(0.2, 0.05, 0.05, 0.95, true), 0.25);
        assert_eq!(step(0.05, 0.05, 0.05, 0.95, false), 0.05);
        assert_eq!(lr_rung(1e-6, false), 1e-6);
        assert_eq!(lr_rung(1.0, true), 1.0);
        let mut lr = 1e-2;
        for want in [5e-3, 2e-3, 1e-3] {
            lr = lr_rung(lr, false);
            assert!(
                (lr - want).abs() < 1e-12,
                "{lr} after halving towards {want}"
            );
        }
        for want in [2e-3, 5e-3, 1e-2] {
            lr = lr_rung(lr, true);
            assert!((lr - want).abs() < 1e-12, "{lr} on the way up to {want}");
        }
        assert!(
            (lr_rung(3e-4, true) - 5e-4).abs() < 1e-12,
            "off the ladder, up"
        );
        assert!(
            (lr_rung(3e-4, false) - 2e-4).abs() < 1e-12,
            "off the ladder, down"
        );
        assert_eq!(climb(10, &EPOCHS, true), 20);
        assert_eq!(climb(40, &EPOCHS, true), 40);
        assert_eq!(climb(1, &EPOCHS, false), 1);
        assert_eq!(
            climb(4, &EPOCHS, false),
            3,
            "off the ladder: from the next rung"
        );
        assert_eq!(
            climb(99, &EPOCHS, true),
            20,
            "above the ladder: from the fifth"
        );
        assert_eq!(toggle_amount(0.0, 0.01), 0.01);
        assert_eq!(toggle_option(Some(0.5), 0.5), None);
    }
}
