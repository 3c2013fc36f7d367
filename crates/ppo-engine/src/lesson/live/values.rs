//! The live-value table: every name a lesson's `show` list may use, each beside the one
//! function that views it in a [`Snapshot`].
//!
//! [`COMMON`] holds the values every run has: the settings, the weights, the return curve,
//! and the batch and update columns every agent's trace shares (read through
//! [`Snapshot::batch`], so they are written once). Each agent adds its own values next to
//! its live view ([`super::LatestView`], [`super::session::LiveAgent::LIVE_VALUES`]):
//! the discrete policy's probabilities and diagnostics, the Gaussian policy's `μ` and `σ`.
//! [`is_known`] (which the lesson loader checks `show` lists against), [`names`] and
//! [`Snapshot::tensor`] read both, so a name cannot be known without a view.
//!
//! ```
//! use ppo_engine::lesson::AgentKind;
//! use ppo_engine::lesson::live::{is_known, runs_on};
//!
//! assert!(is_known("td_target") && !is_known("td_targets"));
//! assert!(runs_on("td_target", AgentKind::Pendulum) && runs_on("td_target", AgentKind::CartPole));
//! assert!(runs_on("mu", AgentKind::Pendulum) && !runs_on("mu", AgentKind::CartPole));
//! ```

use super::batch::{Actions, Batch, EpochView, Rows};
use super::{Index, Mark, Snapshot, TensorView};
use crate::lesson::AgentKind;

/// One live value every run has: its name in lessons and how to view it in a snapshot.
#[derive(Debug, Clone, Copy)]
pub struct LiveValue {
    /// The name, as in the seed's code (`td_target`, `ratio`, ...).
    pub name: &'static str,
    /// The view of the value named by the first argument; `None` while nothing computed it.
    view: fn(&'static str, &Snapshot) -> Option<TensorView>,
}

impl LiveValue {
    /// This value in `snapshot`, `None` if nothing has been computed for it yet.
    #[must_use]
    pub fn view(&self, snapshot: &Snapshot) -> Option<TensorView> {
        (self.view)(self.name, snapshot)
    }
}

/// The live values every agent's run has, in the seed's order.
pub const COMMON: &[LiveValue] = &[
    LiveValue {
        name: "hyper",
        view: hyper,
    },
    LiveValue {
        name: "weights",
        view: weights,
    },
    LiveValue {
        name: "states",
        view: |n, s| Some(rows(n, s.batch()?.states)),
    },
    LiveValue {
        name: "actions",
        view: |n, s| Some(actions(n, s.batch()?.actions)),
    },
    LiveValue {
        name: "rewards",
        view: |n, s| Some(TensorView::column(n, s.batch()?.rewards)),
    },
    LiveValue {
        name: "next_states",
        view: |n, s| Some(rows(n, s.batch()?.next_states)),
    },
    LiveValue {
        name: "dones",
        view: |n, s| Some(TensorView::flags(n, s.batch()?.dones)),
    },
    LiveValue {
        name: "values",
        view: |n, s| Some(TensorView::column(n, s.batch()?.values)),
    },
    LiveValue {
        name: "next_values",
        view: |n, s| Some(TensorView::column(n, s.batch()?.next_values)),
    },
    LiveValue {
        name: "td_target",
        view: |n, s| Some(TensorView::column(n, s.batch()?.td_target)),
    },
    LiveValue {
        name: "td_delta",
        view: |n, s| Some(signed(TensorView::column(n, s.batch()?.td_delta))),
    },
    LiveValue {
        name: "advantage",
        view: |n, s| Some(signed(TensorView::column(n, s.batch()?.advantage))),
    },
    LiveValue {
        name: "old_log_probs",
        view: |n, s| Some(TensorView::column(n, s.batch()?.old_log_probs)),
    },
    LiveValue {
        name: "log_probs",
        view: |n, s| last_epoch(n, s, |e| e.log_probs),
    },
    LiveValue {
        name: "ratio",
        view: ratio,
    },
    LiveValue {
        name: "surr1",
        view: |n, s| last_epoch(n, s, |e| e.surr1),
    },
    LiveValue {
        name: "surr2",
        view: |n, s| last_epoch(n, s, |e| e.surr2),
    },
    LiveValue {
        name: "actor_loss",
        view: |n, s| epoch_series(n, s, |e| e.actor_loss),
    },
    LiveValue {
        name: "critic_loss",
        view: |n, s| epoch_series(n, s, |e| e.critic_loss),
    },
    LiveValue {
        name: "ratio_min",
        view: |n, s| {
            epoch_series(n, s, |e| {
                e.ratio.iter().copied().fold(f32::INFINITY, f32::min)
            })
        },
    },
    LiveValue {
        name: "ratio_max",
        view: |n, s| {
            epoch_series(n, s, |e| {
                e.ratio.iter().copied().fold(f32::NEG_INFINITY, f32::max)
            })
        },
    },
    LiveValue {
        name: "returns",
        view: |n, s| curve(n, &s.returns),
    },
    LiveValue {
        name: "moving_average",
        view: |n, s| curve(n, &s.moving_average),
    },
];

/// Every live value name: [`COMMON`]'s, then each agent's own not yet listed.
#[must_use]
pub fn names() -> Vec<&'static str> {
    let mut names: Vec<&'static str> = COMMON.iter().map(|v| v.name).collect();
    for agent in AgentKind::ALL {
        for &name in agent.live_values() {
            if !names.contains(&name) {
                names.push(name);
            }
        }
    }
    names
}

/// The common live value called `name`, if there is one.
#[must_use]
pub fn lookup(name: &str) -> Option<&'static LiveValue> {
    COMMON.iter().find(|v| v.name == name)
}

/// Whether `name` is a live value the tutor can show, in some agent's run.
#[must_use]
pub fn is_known(name: &str) -> bool {
    lookup(name).is_some()
        || AgentKind::ALL
            .iter()
            .any(|a| a.live_values().contains(&name))
}

/// Whether a run of `agent` has the live value `name`: every run has [`COMMON`]'s, an
/// agent's own values only its runs.
#[must_use]
pub fn runs_on(name: &str, agent: AgentKind) -> bool {
    lookup(name).is_some() || agent.live_values().contains(&name)
}

/// Why live value `name` has no value in `snapshot`, as one line for the reader: what the
/// agent says (a value only one of its objectives computes), or nothing trained yet.
#[must_use]
pub fn why_missing(name: &str, snapshot: &Snapshot) -> String {
    snapshot
        .latest
        .view()
        .and_then(|v| v.why_missing(name))
        .unwrap_or_else(|| {
            crate::tr!(
                "{name}: not available yet (train an episode first)",
                "{name}：还没有数值（请先训练一个回合）"
            )
        })
}

/// Rows of states as a float32 `(N, width)` tensor.
pub(super) fn rows(name: &str, rows: Rows<'_>) -> TensorView {
    let values = rows.values.iter().map(|&v| f64::from(v)).collect();
    TensorView::new(name, vec![rows.len(), rows.width], "float32", values)
}

/// The actions as a column: int64 indices of a discrete space, float32 otherwise.
fn actions(name: &str, actions: Actions<'_>) -> TensorView {
    match actions {
        Actions::Discrete(a) => TensorView::new(
            name,
            vec![a.len(), 1],
            "int64",
            a.iter().map(|&a| a as f64).collect(),
        ),
        Actions::Continuous(a) => TensorView::column(name, a),
    }
}

/// A float32 column of the latest update's last epoch.
fn last_epoch(
    name: &'static str,
    s: &Snapshot,
    pick: impl for<'e> Fn(&EpochView<'e>) -> &'e [f32],
) -> Option<TensorView> {
    let batch = s.batch()?;
    Some(TensorView::column(name, pick(batch.epochs.last()?)))
}

/// A per-epoch scalar of the latest update as a vector over epochs (`(epochs,)`).
fn epoch_series(
    name: &'static str,
    s: &Snapshot,
    f: impl Fn(&EpochView<'_>) -> f32,
) -> Option<TensorView> {
    let batch: Batch<'_> = s.batch()?;
    let values: Vec<f64> = batch.epochs.iter().map(|e| f64::from(f(e))).collect();
    Some(TensorView::new(name, vec![values.len()], "float32", values).counting(Index::Epoch))
}

/// The last epoch's ratio, clipped entries marked: where the agent recorded the clip as
/// active, or else outside `[1 − ε, 1 + ε]`.
fn ratio(name: &'static str, s: &Snapshot) -> Option<TensorView> {
    let batch = s.batch()?;
    let epoch = batch.epochs.last()?;
    let mut t = TensorView::column(name, epoch.ratio);
    t.marks = match epoch.clipped {
        Some(clipped) => clip_marks(clipped),
        None => {
            let (lo, hi) = (1.0 - s.eps, 1.0 + s.eps);
            let outside: Vec<bool> = epoch.ratio.iter().map(|&r| r < lo || r > hi).collect();
            clip_marks(&outside)
        }
    };
    Some(t)
}

/// One mark per flag: `Clipped` where it is set.
pub(super) fn clip_marks(clipped: &[bool]) -> Vec<Mark> {
    clipped
        .iter()
        .map(|&c| if c { Mark::Clipped } else { Mark::Plain })
        .collect()
}

/// The hyper-parameters as `name = value` rows (shown even before the first episode).
fn hyper(name: &'static str, s: &Snapshot) -> Option<TensorView> {
    let mut t = TensorView::new(name, vec![s.hyper.len()], "", vec![f64::NAN; s.hyper.len()]);
    t.labels = s.hyper.iter().map(|(k, v)| format!("{k} = {v}")).collect();
    Some(t)
}

/// One row per parameter: its name, shape and Euclidean norm.
fn weights(name: &'static str, s: &Snapshot) -> Option<TensorView> {
    if s.weights.is_empty() {
        return None;
    }
    let mut t = TensorView::new(name, vec![s.weights.len()], "", vec![]);
    for (n, w) in &s.weights {
        let norm = w
            .data
            .iter()
            .map(|v| f64::from(*v).powi(2))
            .sum::<f64>()
            .sqrt();
        let dims: Vec<String> = w.shape.iter().map(ToString::to_string).collect();
        t.labels
            .push(format!("{n} ({}) ‖·‖ = {norm:.4}", dims.join(", ")));
        t.values.push(norm);
        t.marks.push(Mark::Plain);
    }
    t.shape = vec![t.labels.len()];
    Some(t)
}

/// `G_t = r_t + γ·G_{t+1}·(1 − done_t)`, from the last step back: the discounted reward
/// still to come in the episode, REINFORCE's weight on `∇log π(a_t|s_t)`.
#[must_use]
pub fn return_to_go(rewards: &[f32], dones: &[bool], gamma: f64) -> Vec<f64> {
    let mut out = vec![0.0; rewards.len()];
    let mut next = 0.0;
    for t in (0..rewards.len()).rev() {
        let carry = if dones.get(t).copied().unwrap_or(false) {
            0.0
        } else {
            next
        };
        next = f64::from(rewards[t]) + gamma * carry;
        out[t] = next;
    }
    out
}

/// A float64 curve over episodes, `None` before the first episode.
fn curve(name: &'static str, values: &[f64]) -> Option<TensorView> {
    (!values.is_empty()).then(|| {
        TensorView::new(name, vec![values.len()], "float64", values.to_vec())
            .counting(Index::Episode)
    })
}

/// Marks each entry by its sign.
pub(super) fn signed(mut t: TensorView) -> TensorView {
    t.marks = t
        .values
        .iter()
        .map(|&v| {
            if v > 0.0 {
                Mark::Positive
            } else if v < 0.0 {
                Mark::Negative
            } else {
                Mark::Plain
            }
        })
        .collect();
    t
}

/// Rows of `label = value` lines, labels padded to one width, at least `min_width` (a
/// small table of scalars).
pub(super) fn labelled(
    name: &'static str,
    dtype: &'static str,
    (rows, min_width): (&[(&str, f64)], usize),
    format: impl Fn(f64) -> String,
) -> TensorView {
    let width = rows
        .iter()
        .map(|(label, _)| crate::i18n::width(label))
        .max()
        .unwrap_or(0)
        .max(min_width);
    let mut t = TensorView::new(name, vec![rows.len()], dtype, vec![]);
    for &(label, v) in rows {
        let label = crate::i18n::pad_right(label, width);
        t.labels.push(format!("{label} = {}", format(v)));
        t.values.push(v);
        t.marks.push(Mark::Plain);
    }
    t
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::HashSet;

    /// No name is both common and an agent's own, none is listed twice by one agent, and
    /// views are not live values.
    #[test]
    fn names_are_unique_and_known() {
        let common: HashSet<&str> = COMMON.iter().map(|v| v.name).collect();
        assert_eq!(common.len(), COMMON.len(), "a name is listed twice");
        for agent in AgentKind::ALL {
            let own: HashSet<&str> = agent.live_values().iter().copied().collect();
            assert_eq!(
                own.len(),
                agent.live_values().len(),
                "{agent:?} lists a name twice"
            );
            assert!(
                own.is_disjoint(&common),
                "{agent:?} redefines a common value"
            );
        }
        assert!(names().iter().all(|n| is_known(n)));
        assert!(!is_known("td_targets"));
        assert!(!is_known("plot"), "views are not live values");
    }

    #[test]
    fn the_return_to_go_discounts_and_restarts_at_done() {
        let g = return_to_go(&[1.0, 1.0, 1.0, 1.0], &[false, true, false, false], 0.5);
        assert_eq!(g, [1.5, 1.0, 1.5, 1.0]);
    }

    #[test]
    fn every_view_is_named_after_its_row() {
        let snapshot = Snapshot::default();
        for v in COMMON {
            if let Some(t) = v.view(&snapshot) {
                assert_eq!(t.name, v.name);
            }
        }
    }
}
