//! What the live session shows of the book's `PPOContinuous` on Pendulum: the update's
//! trace and the Gaussian policy's `(μ, σ)` over a grid of states after the update, and the
//! live values only this agent computes.

use super::super::batch::{Actions, Batch, EpochView, Rows};
use super::super::session::LiveAgent;
use super::super::{Axes, Axis, LatestView, PolicyMap, Snapshot, TensorView};
use crate::ppo::{
    ContinuousUpdateTrace, EpisodeReport, PpoContinuous, PpoContinuousConfig, PpoError,
};

/// What a Pendulum run shows of its latest episode and update.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct PendulumLatest {
    /// The latest update's batch and intermediates.
    pub trace: ContinuousUpdateTrace,
    /// The Gaussian policy's `(μ, σ)` over a grid of states, after the update.
    pub policy_map: PolicyMap,
}

impl crate::run::IntoLatest for PendulumLatest {
    fn into_latest(self) -> crate::run::Latest {
        crate::run::Latest::Pendulum(Some(Box::new(self)))
    }
}

impl Snapshot {
    /// A Pendulum run's latest episode and update; `None` before the first episode or in
    /// another agent's run.
    #[must_use]
    pub fn pendulum_update(&self) -> Option<&PendulumLatest> {
        match &self.latest {
            crate::run::Latest::Pendulum(latest) => latest.as_deref(),
            _ => None,
        }
    }

    /// A Pendulum run's frame `i` of the latest episode: the angle θ (0 upright) of
    /// observation `i` and the torque chosen there (0 for the observation the episode ended
    /// in); `None` past the end or in another agent's run.
    #[must_use]
    pub fn pendulum_frame(&self, i: usize) -> Option<(f64, f64)> {
        let c = &self.pendulum_update()?.trace;
        let state = match c.states.get(i) {
            Some(state) => *state,
            None if i == c.states.len() => *c.next_states.last()?,
            None => return None,
        };
        let theta = f64::from(state[1]).atan2(f64::from(state[0]));
        let torque = c.actions.get(i).map_or(0.0, |&a| f64::from(a));
        Some((theta, torque))
    }
}

/// The live values only the Gaussian policy's runs have.
const LIVE_VALUES: &[&str] = &["scaled_rewards", "mu", "std", "mu_map", "std_map"];

impl LiveAgent for PpoContinuous {
    type Before = ();
    type Latest = PendulumLatest;
    const LIVE_VALUES: &'static [&'static str] = LIVE_VALUES;

    /// The book's order.
    fn hyper(c: &PpoContinuousConfig, seed: u64) -> Vec<(String, String)> {
        vec![
            ("actor_lr".into(), format!("{}", c.actor_lr)),
            ("critic_lr".into(), format!("{}", c.critic_lr)),
            ("num_episodes".into(), c.num_episodes.to_string()),
            ("hidden_dim".into(), c.hidden_dim.to_string()),
            ("gamma".into(), c.gamma.to_string()),
            ("lmbda".into(), c.lmbda.to_string()),
            ("epochs".into(), c.epochs.to_string()),
            ("eps".into(), c.eps.to_string()),
            ("env_name".into(), crate::env::pendulum::ENV_ID.into()),
            ("seed".into(), seed.to_string()),
        ]
    }

    fn eps_gamma(c: &PpoContinuousConfig) -> (f64, f64) {
        (c.eps, c.gamma)
    }

    fn before_episode(&self) -> Result<(), PpoError> {
        Ok(())
    }

    /// The update's trace and the policy's `(μ, σ)` map after the update.
    fn show(
        &self,
        (): (),
        report: EpisodeReport<ContinuousUpdateTrace>,
    ) -> Result<PendulumLatest, PpoError> {
        Ok(PendulumLatest {
            trace: report.trace,
            policy_map: PolicyMap::of(|state| self.mu_std(state)),
        })
    }
}

impl LatestView for PendulumLatest {
    fn batch(&self) -> Batch<'_> {
        let t = &self.trace;
        Batch {
            states: Rows::of(&t.states),
            next_states: Rows::of(&t.next_states),
            actions: Actions::Continuous(&t.actions),
            rewards: &t.rewards,
            dones: &t.dones,
            values: &t.values,
            next_values: &t.next_values,
            td_target: &t.td_target,
            td_delta: &t.td_delta,
            advantage: &t.advantage,
            old_log_probs: &t.old_log_probs,
            epochs: t
                .epochs
                .iter()
                .map(|e| EpochView {
                    log_probs: &e.log_probs,
                    ratio: &e.ratio,
                    surr1: &e.surr1,
                    surr2: &e.surr2,
                    clipped: None,
                    actor_loss: e.actor_loss,
                    critic_loss: e.critic_loss,
                })
                .collect(),
        }
    }

    fn tensor(&self, n: &'static str, _: &Snapshot) -> Option<TensorView> {
        Some(match n {
            "scaled_rewards" => TensorView::column(n, &self.trace.scaled_rewards),
            "mu" => TensorView::column(n, &self.trace.mu),
            "std" => TensorView::column(n, &self.trace.std),
            "mu_map" => map_view(n, &self.policy_map, &self.policy_map.mu),
            "std_map" => map_view(n, &self.policy_map, &self.policy_map.std),
            _ => return None,
        })
    }
}

/// `μ` or `σ` over the policy map's grid, `(θ̇ rows, θ columns)`.
fn map_view(name: &'static str, map: &PolicyMap, values: &[f32]) -> TensorView {
    let values = values.iter().map(|&v| f64::from(v)).collect();
    let mut t = TensorView::new(
        name,
        vec![map.theta_dots.len(), map.thetas.len()],
        "float32",
        values,
    );
    t.axes = Some(Axes {
        rows: Axis {
            name: "θ̇",
            ticks: map.theta_dots.iter().map(|&v| tick(v)).collect(),
        },
        columns: Axis {
            name: "θ",
            ticks: map.thetas.iter().map(|&v| angle_tick(v)).collect(),
        },
    });
    t
}

/// An axis value as a short label: `8`, `-2`, `0.5`.
fn tick(v: f32) -> String {
    if v.fract() == 0.0 {
        format!("{v:.0}")
    } else {
        format!("{v:.2}")
    }
}

/// An angle as a multiple of π/4 where it is one (`-π`, `-3π/4`, `0`, `π/2`), else in radians.
fn angle_tick(v: f32) -> String {
    let quarters = v / std::f32::consts::FRAC_PI_4;
    let k = quarters.round();
    if (quarters - k).abs() > 1e-3 {
        return tick(v);
    }
    let sign = if k < 0.0 { "-" } else { "" };
    match k.abs() as u32 {
        0 => "0".into(),
        1 => format!("{sign}π/4"),
        2 => format!("{sign}π/2"),
        4 => format!("{sign}π"),
        n if n % 4 == 0 => format!("{sign}{}π", n / 4),
        n if n % 2 == 0 => format!("{sign}{}π/2", n / 2),
        n => format!("{sign}{n}π/4"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The policy maps carry their axes, θ̇ down the rows and θ across.
    #[test]
    fn the_policy_maps_name_both_axes() -> Result<(), &'static str> {
        let snapshot = Snapshot {
            latest: crate::run::IntoLatest::into_latest(PendulumLatest {
                trace: ContinuousUpdateTrace::default(),
                policy_map: PolicyMap::of(|_| (0.0, 1.0)),
            }),
            ..Snapshot::default()
        };
        let map = snapshot.tensor("mu_map").ok_or("no mu_map")?;
        let axes = map.axes.ok_or("no axes")?;
        assert_eq!((axes.rows.name, axes.columns.name), ("θ̇", "θ"));
        assert_eq!(axes.rows.ticks.first().map(String::as_str), Some("8"));
        assert_eq!(axes.rows.ticks.last().map(String::as_str), Some("-8"));
        assert_eq!(
            axes.columns.ticks,
            [
                "-π", "-3π/4", "-π/2", "-π/4", "0", "π/4", "π/2", "3π/4", "π"
            ]
        );
        assert_eq!(angle_tick(0.5), "0.50");
        assert!(snapshot.tensor("std_map").is_some_and(|t| t.axes.is_some()));
        assert!(
            snapshot.tensor("probs").is_none(),
            "the discrete policy's value"
        );
        Ok(())
    }
}
