//! The live-value table: every name a lesson's `show` list may use, each beside the one
//! function that views it in a [`Snapshot`].
//!
//! [`LIVE`] is the only place a live value is named: [`NAMES`], [`is_known`] (which the lesson
//! loader checks `show` lists against) and [`Snapshot::tensor`] all read it, so a name cannot
//! be known without a view, or viewed without being known.
//!
//! ```
//! use ppo_engine::lesson::live::{LIVE, NAMES, is_known, lookup};
//!
//! assert_eq!(NAMES.len(), LIVE.len());
//! assert!(is_known("td_target") && !is_known("td_targets"));
//! assert_eq!(lookup("ratio").map(|v| v.name), Some("ratio"));
//! ```

use super::{Axes, Axis, Index, Mark, Snapshot, TensorView};
use crate::lesson::AgentKind;
use crate::ppo::{ContinuousEpochTrace, ContinuousUpdateTrace, EpochTrace, UpdateTrace};

/// One live value: its name in lessons and how to view it in a snapshot.
#[derive(Debug, Clone, Copy)]
pub struct LiveValue {
    /// The name, as in the seed's code (`td_target`, `ratio`, ...).
    pub name: &'static str,
    /// The view of the value named by the first argument; `None` while nothing computed it.
    view: fn(&'static str, &Snapshot) -> Option<TensorView>,
}

impl LiveValue {
    /// Whether a run on `env` has this value: the Gaussian policy's values only exist in
    /// Pendulum runs, the discrete policy's (probabilities, gradients, diagnostics) only
    /// in CartPole runs, the rest in both.
    #[must_use]
    pub fn runs_on(&self, env: AgentKind) -> bool {
        if PENDULUM_ONLY.contains(&self.name) {
            env == AgentKind::Pendulum
        } else {
            env == AgentKind::CartPole || IN_BOTH.contains(&self.name)
        }
    }

    /// This value in `snapshot`, `None` if nothing has been computed for it yet.
    #[must_use]
    pub fn view(&self, snapshot: &Snapshot) -> Option<TensorView> {
        (self.view)(self.name, snapshot)
    }
}

/// Live values of the Gaussian policy, shown in Pendulum runs only.
pub const PENDULUM_ONLY: [&str; 5] = ["scaled_rewards", "mu", "std", "mu_map", "std_map"];

/// Live values with the same meaning in both runs: a Pendulum snapshot views them from the
/// continuous update's trace.
pub const IN_BOTH: [&str; 23] = [
    "hyper",
    "weights",
    "states",
    "actions",
    "rewards",
    "next_states",
    "dones",
    "values",
    "next_values",
    "td_target",
    "td_delta",
    "advantage",
    "old_log_probs",
    "log_probs",
    "ratio",
    "surr1",
    "surr2",
    "actor_loss",
    "critic_loss",
    "ratio_min",
    "ratio_max",
    "returns",
    "moving_average",
];

/// Live values that only PPO-Penalty's update computes (`objective = "penalty"`): in a run
/// of another objective they stay empty ([`why_missing`] says so).
pub const PENALTY_ONLY: [&str; 2] = ["kl_mean", "beta"];

/// Why live value `name` has no value in `snapshot`, as one line for the reader: a
/// penalty-only value in a run of another objective, or nothing trained yet.
#[must_use]
pub fn why_missing(name: &str, snapshot: &Snapshot) -> String {
    if PENALTY_ONLY.contains(&name) && snapshot.trace.is_some() {
        crate::tr!(
            "{name}: only PPO-Penalty computes it (objective = penalty); this run's objective is another",
            "{name}：只有 PPO-惩罚才计算它（objective = penalty），这次运行用的是别的目标"
        )
    } else {
        crate::tr!(
            "{name}: not available yet (train an episode first)",
            "{name}：还没有数值（请先训练一个回合）"
        )
    }
}

/// Every live value a lesson may show, in the seed's order (views such as `plot` are listed
/// in [`crate::lesson::VIEWS`]).
pub const LIVE: &[LiveValue] = &[
    LiveValue {
        name: "hyper",
        view: hyper,
    },
    LiveValue {
        name: "weights",
        view: weights,
    },
    LiveValue {
        name: "probs",
        view: probs,
    },
    LiveValue {
        name: "obs",
        view: |n, s| Some(TensorView::rows(n, &trace(s)?.next_states)),
    },
    LiveValue {
        name: "states",
        view: |n, s| match cont(s) {
            Some(c) => Some(TensorView::rows(n, &c.states)),
            None => Some(TensorView::rows(n, &trace(s)?.states)),
        },
    },
    LiveValue {
        name: "actions",
        view: actions,
    },
    LiveValue {
        name: "rewards",
        view: |n, s| column(n, s, |t| &t.rewards, |c| &c.rewards),
    },
    LiveValue {
        name: "next_states",
        view: |n, s| match cont(s) {
            Some(c) => Some(TensorView::rows(n, &c.next_states)),
            None => Some(TensorView::rows(n, &trace(s)?.next_states)),
        },
    },
    LiveValue {
        name: "dones",
        view: |n, s| match cont(s) {
            Some(c) => Some(TensorView::flags(n, &c.dones)),
            None => Some(TensorView::flags(n, &trace(s)?.dones)),
        },
    },
    LiveValue {
        name: "terminated",
        view: |n, s| (!s.terminated.is_empty()).then(|| TensorView::flags(n, &s.terminated)),
    },
    LiveValue {
        name: "truncated",
        view: |n, s| (!s.truncated.is_empty()).then(|| TensorView::flags(n, &s.truncated)),
    },
    LiveValue {
        name: "values",
        view: |n, s| column(n, s, |t| &t.values, |c| &c.values),
    },
    LiveValue {
        name: "next_values",
        view: |n, s| column(n, s, |t| &t.next_values, |c| &c.next_values),
    },
    LiveValue {
        name: "td_target",
        view: |n, s| column(n, s, |t| &t.td_target, |c| &c.td_target),
    },
    LiveValue {
        name: "td_delta",
        view: |n, s| column(n, s, |t| &t.td_delta, |c| &c.td_delta).map(signed),
    },
    LiveValue {
        name: "advantage",
        view: |n, s| column(n, s, |t| &t.advantage, |c| &c.advantage).map(signed),
    },
    LiveValue {
        name: "return_to_go",
        view: |n, s| {
            let t = trace(s)?;
            let g: Vec<f32> = return_to_go(&t.rewards, &t.dones, s.gamma)
                .into_iter()
                .map(|x| x as f32)
                .collect();
            Some(TensorView::column(n, &g))
        },
    },
    LiveValue {
        name: "lambda_return",
        view: |n, s| Some(TensorView::column(n, &trace(s)?.lambda_return)),
    },
    LiveValue {
        name: "old_log_probs",
        view: |n, s| column(n, s, |t| &t.old_log_probs, |c| &c.old_log_probs),
    },
    LiveValue {
        name: "log_probs",
        view: |n, s| epoch_column(n, s, |e| &e.log_probs, |e| &e.log_probs),
    },
    LiveValue {
        name: "ratio",
        view: ratio,
    },
    LiveValue {
        name: "surr1",
        view: |n, s| epoch_column(n, s, |e| &e.surr1, |e| &e.surr1),
    },
    LiveValue {
        name: "surr2",
        view: |n, s| epoch_column(n, s, |e| &e.surr2, |e| &e.surr2),
    },
    LiveValue {
        name: "clipped",
        view: clipped,
    },
    LiveValue {
        name: "actor_loss",
        view: |n, s| match cont(s) {
            Some(c) => Some(continuous_series(n, c, |e| e.actor_loss)),
            None => epoch_series(n, s, |e| e.actor_loss),
        },
    },
    LiveValue {
        name: "critic_loss",
        view: |n, s| match cont(s) {
            Some(c) => Some(continuous_series(n, c, |e| e.critic_loss)),
            None => epoch_series(n, s, |e| e.critic_loss),
        },
    },
    LiveValue {
        name: "approx_kl",
        view: |n, s| epoch_series(n, s, |e| e.approx_kl),
    },
    LiveValue {
        name: "kl_mean",
        view: |n, s| {
            let t = trace(s)?;
            t.penalty?;
            let values: Vec<f64> = t
                .epochs
                .iter()
                .map(|e| e.kl_mean.map_or(f64::NAN, f64::from))
                .collect();
            Some(TensorView::new(n, vec![values.len()], "float32", values).counting(Index::Epoch))
        },
    },
    LiveValue {
        name: "beta",
        view: |n, s| {
            let p = trace(s)?.penalty?;
            let mut t = TensorView::new(n, vec![3], "float64", vec![]);
            for (label, v) in [
                (
                    crate::i18n::t("β in this update's loss", "本次更新损失中的 β"),
                    p.beta_before,
                ),
                (
                    crate::i18n::t("d, the KL after it", "d，更新后的 KL"),
                    f64::from(p.kl_after),
                ),
                (
                    crate::i18n::t("β for the next update", "下一次更新的 β"),
                    p.beta_after,
                ),
            ] {
                let label = crate::i18n::pad_right(label, 23);
                t.labels.push(format!("{label} = {v:.4e}"));
                t.values.push(v);
                t.marks.push(Mark::Plain);
            }
            Some(t)
        },
    },
    LiveValue {
        name: "kl_after",
        view: |n, s| {
            let kl = trace(s)?.kl_after?;
            Some(TensorView::new(n, vec![1], "float32", vec![f64::from(kl)]))
        },
    },
    LiveValue {
        name: "clip_frac",
        view: |n, s| epoch_series(n, s, |e| e.clip_fraction),
    },
    LiveValue {
        name: "ratio_min",
        view: |n, s| match cont(s) {
            Some(c) => Some(continuous_series(n, c, |e| {
                e.ratio.iter().copied().fold(f32::INFINITY, f32::min)
            })),
            None => epoch_series(n, s, |e| {
                e.ratio.iter().copied().fold(f32::INFINITY, f32::min)
            }),
        },
    },
    LiveValue {
        name: "ratio_max",
        view: |n, s| match cont(s) {
            Some(c) => Some(continuous_series(n, c, |e| {
                e.ratio.iter().copied().fold(f32::NEG_INFINITY, f32::max)
            })),
            None => epoch_series(n, s, |e| {
                e.ratio.iter().copied().fold(f32::NEG_INFINITY, f32::max)
            }),
        },
    },
    LiveValue {
        name: "entropy",
        view: |n, s| epoch_series(n, s, |e| e.entropy),
    },
    LiveValue {
        name: "epochs_run",
        view: |n, s| {
            let t = trace(s)?;
            Some(TensorView::new(
                n,
                vec![1],
                "int64",
                vec![t.epochs_run() as f64],
            ))
        },
    },
    LiveValue {
        name: "explained_variance",
        view: |n, s| {
            let ev = trace(s)?.explained_variance.map_or(f64::NAN, f64::from);
            Some(TensorView::new(n, vec![1], "float32", vec![ev]))
        },
    },
    LiveValue {
        name: "grad_surrogate",
        view: |n, s| gradient(n, s, |g| &g.surrogate),
    },
    LiveValue {
        name: "grad_log_prob",
        view: |n, s| gradient(n, s, |g| &g.log_prob),
    },
    LiveValue {
        name: "grad_max_diff",
        view: |n, s| {
            let g = s.gradients.as_ref()?;
            let mut t = TensorView::new(n, vec![2], "float32", vec![]);
            let rows = [
                (
                    crate::i18n::t("max |surrogate − log π|", "两个梯度之差的最大绝对值"),
                    g.max_abs_diff(),
                ),
                (
                    crate::i18n::t("max |log π gradient|", "log π 梯度的最大绝对值"),
                    g.max_abs(),
                ),
            ];
            let width = rows
                .iter()
                .map(|(label, _)| crate::i18n::width(label))
                .max()
                .unwrap_or(0);
            for (label, v) in rows {
                let label = crate::i18n::pad_right(label, width);
                t.labels.push(format!("{label} = {v:.3e}"));
                t.values.push(f64::from(v));
                t.marks.push(Mark::Plain);
            }
            Some(t)
        },
    },
    LiveValue {
        name: "scaled_rewards",
        view: |n, s| Some(TensorView::column(n, &cont(s)?.scaled_rewards)),
    },
    LiveValue {
        name: "mu",
        view: |n, s| Some(TensorView::column(n, &cont(s)?.mu)),
    },
    LiveValue {
        name: "std",
        view: |n, s| Some(TensorView::column(n, &cont(s)?.std)),
    },
    LiveValue {
        name: "mu_map",
        view: |n, s| policy_map(n, s, |m| &m.mu),
    },
    LiveValue {
        name: "std_map",
        view: |n, s| policy_map(n, s, |m| &m.std),
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

/// Every live value name, in [`LIVE`]'s order.
pub const NAMES: [&str; LIVE.len()] = {
    let mut names = [""; LIVE.len()];
    let mut i = 0;
    while i < LIVE.len() {
        names[i] = LIVE[i].name;
        i += 1;
    }
    names
};

/// The live value called `name`, if there is one.
#[must_use]
pub fn lookup(name: &str) -> Option<&'static LiveValue> {
    LIVE.iter().find(|v| v.name == name)
}

/// Whether `name` is a live value the tutor can show.
#[must_use]
pub fn is_known(name: &str) -> bool {
    lookup(name).is_some()
}

fn trace(s: &Snapshot) -> Option<&UpdateTrace> {
    s.trace.as_ref()
}

fn last_epoch(s: &Snapshot) -> Option<&EpochTrace> {
    trace(s)?.epochs.last()
}

fn cont(s: &Snapshot) -> Option<&ContinuousUpdateTrace> {
    s.continuous.as_ref()
}

/// A float32 column of the latest update, from whichever trace the run keeps.
fn column(
    name: &'static str,
    s: &Snapshot,
    discrete: impl Fn(&UpdateTrace) -> &Vec<f32>,
    continuous: impl Fn(&ContinuousUpdateTrace) -> &Vec<f32>,
) -> Option<TensorView> {
    match cont(s) {
        Some(c) => Some(TensorView::column(name, continuous(c))),
        None => Some(TensorView::column(name, discrete(trace(s)?))),
    }
}

/// A float32 column of the latest update's last epoch, from whichever trace the run keeps.
fn epoch_column(
    name: &'static str,
    s: &Snapshot,
    discrete: impl Fn(&EpochTrace) -> &Vec<f32>,
    continuous: impl Fn(&ContinuousEpochTrace) -> &Vec<f32>,
) -> Option<TensorView> {
    match cont(s) {
        Some(c) => Some(TensorView::column(name, continuous(c.last_epoch()?))),
        None => Some(TensorView::column(name, discrete(last_epoch(s)?))),
    }
}

/// A per-epoch scalar of a Pendulum update as a vector over epochs.
fn continuous_series(
    name: &'static str,
    c: &ContinuousUpdateTrace,
    f: impl Fn(&ContinuousEpochTrace) -> f32,
) -> TensorView {
    let values: Vec<f64> = c.epochs.iter().map(|e| f64::from(f(e))).collect();
    TensorView::new(name, vec![values.len()], "float32", values).counting(Index::Epoch)
}

/// `μ` or `σ` over the policy map's grid, `(θ̇ rows, θ columns)`.
fn policy_map(
    name: &'static str,
    s: &Snapshot,
    pick: impl Fn(&super::PolicyMap) -> &Vec<f32>,
) -> Option<TensorView> {
    let map = s.policy_map.as_ref()?;
    let values = pick(map).iter().map(|&v| f64::from(v)).collect();
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
    Some(t)
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

fn probs(name: &'static str, s: &Snapshot) -> Option<TensorView> {
    if s.probs.is_empty() {
        return None;
    }
    let values = s.probs.iter().flatten().map(|&p| f64::from(p)).collect();
    Some(TensorView::new(
        name,
        vec![s.probs.len(), 2],
        "float32",
        values,
    ))
}

fn actions(name: &'static str, s: &Snapshot) -> Option<TensorView> {
    if let Some(c) = cont(s) {
        return Some(TensorView::column(name, &c.actions));
    }
    let actions = &trace(s)?.actions;
    Some(TensorView::new(
        name,
        vec![actions.len(), 1],
        "int64",
        actions.iter().map(|&a| a as f64).collect(),
    ))
}

/// The last epoch's ratio, clipped entries marked.
fn ratio(name: &'static str, s: &Snapshot) -> Option<TensorView> {
    if let Some(epoch) = cont(s).and_then(ContinuousUpdateTrace::last_epoch) {
        let mut t = TensorView::column(name, &epoch.ratio);
        let (lo, hi) = (1.0 - s.eps, 1.0 + s.eps);
        let outside: Vec<bool> = epoch.ratio.iter().map(|&r| r < lo || r > hi).collect();
        t.marks = clip_marks(&outside);
        return Some(t);
    }
    let epoch = last_epoch(s)?;
    let mut t = TensorView::column(name, &epoch.ratio);
    t.marks = clip_marks(&epoch.clipped);
    Some(t)
}

/// The last epoch's clip flags as a bool column, clipped entries marked.
fn clipped(name: &'static str, s: &Snapshot) -> Option<TensorView> {
    let epoch = last_epoch(s)?;
    let mut t = TensorView::flags(name, &epoch.clipped);
    t.dtype = "bool";
    t.marks = clip_marks(&epoch.clipped);
    Some(t)
}

fn clip_marks(clipped: &[bool]) -> Vec<Mark> {
    clipped
        .iter()
        .map(|&c| if c { Mark::Clipped } else { Mark::Plain })
        .collect()
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

/// One of the two policy gradients, a row per actor parameter in PyTorch's order
/// (`fc1.weight` rows 0–511, `fc1.bias`, `fc2.weight`, `fc2.bias` last, for width 128).
fn gradient(
    name: &'static str,
    s: &Snapshot,
    pick: impl Fn(&crate::ppo::SurrogateGradients) -> &Vec<f32>,
) -> Option<TensorView> {
    Some(signed(TensorView::column(
        name,
        pick(s.gradients.as_ref()?),
    )))
}

/// A float64 curve over episodes, `None` before the first episode.
fn curve(name: &'static str, values: &[f64]) -> Option<TensorView> {
    (!values.is_empty()).then(|| {
        TensorView::new(name, vec![values.len()], "float64", values.to_vec())
            .counting(Index::Episode)
    })
}

/// Marks each entry by its sign.
fn signed(mut t: TensorView) -> TensorView {
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

/// A per-epoch scalar of the latest update as a vector over epochs (`(epochs,)`).
fn epoch_series(
    name: &'static str,
    s: &Snapshot,
    f: impl Fn(&EpochTrace) -> f32,
) -> Option<TensorView> {
    let values: Vec<f64> = trace(s)?.epochs.iter().map(|e| f64::from(f(e))).collect();
    Some(TensorView::new(name, vec![values.len()], "float32", values).counting(Index::Epoch))
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::HashSet;

    /// PPO-Penalty's live values come from its trace: each epoch's exact mean KL (0 before
    /// the first step), β before, d and β after; a clip run has none of them and says why.
    #[test]
    fn penalty_values_view_the_penalty_trace() -> Result<(), crate::ppo::PpoError> {
        use crate::lesson::Session;
        use crate::ppo::{Objective, PpoConfig};
        let penalty = PpoConfig {
            objective: Objective::Penalty,
            num_episodes: 3,
            ..PpoConfig::default()
        };
        let s = Session::run(penalty, 0, 3)?;
        let t = s.trace.as_ref().ok_or(crate::ppo::PpoError::EmptyBatch)?;
        let p = t.penalty.ok_or(crate::ppo::PpoError::EmptyBatch)?;
        let beta = s.tensor("beta").ok_or(crate::ppo::PpoError::EmptyBatch)?;
        assert_eq!(
            beta.values,
            [p.beta_before, f64::from(p.kl_after), p.beta_after]
        );
        assert_eq!(beta.labels.len(), 3);
        let kl = s
            .tensor("kl_mean")
            .ok_or(crate::ppo::PpoError::EmptyBatch)?;
        assert_eq!(kl.values.len(), t.epochs.len());
        assert_eq!(kl.values[0], 0.0, "π_θ is π_old before the first step");
        assert!(kl.values.windows(2).all(|w| w[1] >= w[0]) && kl.values[9] > 0.0);
        let after = s
            .tensor("kl_after")
            .ok_or(crate::ppo::PpoError::EmptyBatch)?;
        // The same KL, computed by the penalty (candle) and for every objective (plain f32).
        let d = f64::from(p.kl_after);
        assert!(
            (after.values[0] - d).abs() < 1e-5 * d,
            "d is kl_after: {after:?} {d}"
        );

        let clip = Session::run(
            PpoConfig {
                num_episodes: 3,
                ..PpoConfig::default()
            },
            0,
            3,
        )?;
        for name in PENALTY_ONLY {
            assert!(clip.tensor(name).is_none(), "{name}");
            assert!(why_missing(name, &clip).contains("penalty"), "{name}");
        }
        assert!(
            clip.tensor("kl_after").is_some(),
            "every objective reports it"
        );
        let fresh = Snapshot::default();
        assert!(why_missing("beta", &fresh).contains("train an episode"));
        Ok(())
    }

    #[test]
    fn names_are_unique_and_known() {
        let unique: HashSet<&str> = NAMES.iter().copied().collect();
        assert_eq!(unique.len(), LIVE.len(), "a name is listed twice");
        assert!(NAMES.iter().all(|n| is_known(n)));
        assert!(!is_known("td_targets"));
        assert!(!is_known("plot"), "views are not live values");
    }

    #[test]
    fn the_return_to_go_discounts_and_restarts_at_done() {
        let g = return_to_go(&[1.0, 1.0, 1.0, 1.0], &[false, true, false, false], 0.5);
        assert_eq!(g, [1.5, 1.0, 1.5, 1.0]);
    }

    /// The policy maps carry their axes, θ̇ down the rows and θ across.
    #[test]
    fn the_policy_maps_name_both_axes() -> Result<(), &'static str> {
        let snapshot = Snapshot {
            policy_map: Some(super::super::PolicyMap::of(|_| (0.0, 1.0))),
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
        Ok(())
    }

    #[test]
    fn every_view_is_named_after_its_row() {
        let snapshot = Snapshot::default();
        for v in LIVE {
            if let Some(t) = v.view(&snapshot) {
                assert_eq!(t.name, v.name);
            }
        }
    }
}
