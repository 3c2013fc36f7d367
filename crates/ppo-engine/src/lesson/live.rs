//! Live values: the named tensors a lesson step shows, taken from the running agent.
//!
//! A [`Snapshot`] is what the tutor knows after the latest episode and update: the
//! hyper-parameters, the episode's batch and every intermediate of the update
//! ([`UpdateTrace`]), the action probabilities, the return curve. [`Snapshot::tensor`]
//! turns a name from a lesson's `show` list into a [`TensorView`] with its shape,
//! dtype, values and the entries that matter marked (clipped ratios, done flags, the
//! sign of the advantage).
//!
//! - [`session`]: [`Session`], the one training run that turns episodes into snapshots; the
//!   terminal app's worker, `ppo-tutor show`, the notebooks and the tests all go through it.
//! - [`values`]: [`LIVE`], the table of live value names and their views.

pub mod agents;
pub mod batch;
pub mod probe;
pub mod session;
pub mod values;

pub use agents::cartpole::{CartPoleLatest, PENALTY_ONLY};
pub use agents::pendulum::PendulumLatest;
pub use batch::Batch;
pub use session::Session;
pub use values::{COMMON, LiveValue, is_known, lookup, names, runs_on, why_missing};

use super::AgentKind;
use crate::ppo::NamedWeights;
pub use crate::run::Latest;
use crate::run::RunConfig;

/// An agent's view of what it shows of its latest episode and update (its
/// [`session::LiveAgent::Latest`]): the columns every run has, and its own live values.
pub trait LatestView {
    /// The batch's columns and the update's epochs, as every agent has them.
    fn batch(&self) -> Batch<'_>;

    /// The agent's own live value `name` ([`session::LiveAgent::LIVE_VALUES`]); `None` for
    /// another name, or one this run did not compute. `snapshot` holds the settings.
    fn tensor(&self, name: &'static str, snapshot: &Snapshot) -> Option<TensorView>;

    /// Why the agent's own live value `name` is empty in this run, where it can say
    /// (a value only one of its objectives computes); `None` otherwise.
    fn why_missing(&self, name: &str) -> Option<String> {
        let _ = name;
        None
    }
}

/// How an entry is highlighted.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Mark {
    /// Nothing special.
    #[default]
    Plain,
    /// A ratio outside `[1 − ε, 1 + ε]`: the clip is active.
    Clipped,
    /// A step whose `done` flag is set (the TD target drops `V(s')`).
    Done,
    /// A positive advantage (the action did better than expected).
    Positive,
    /// A negative advantage.
    Negative,
}

/// One tensor, ready to display.
#[derive(Debug, Clone, PartialEq)]
pub struct TensorView {
    /// The name, as in the seed's code.
    pub name: String,
    /// The shape, PyTorch-style (`(N, 1)` columns stay two-dimensional).
    pub shape: Vec<usize>,
    /// The element type, as PyTorch would print it.
    pub dtype: &'static str,
    /// Row labels for key/value tables (`hyper`), empty for numeric tensors.
    pub labels: Vec<String>,
    /// The values, row-major.
    pub values: Vec<f64>,
    /// One mark per value.
    pub marks: Vec<Mark>,
    /// What the rows and columns of a grid stand for (the policy maps' θ̇ rows and θ
    /// columns); `None` for tensors whose rows are steps of the batch.
    pub axes: Option<Axes>,
    /// What the entries of a vector count, when they are one per epoch or per episode (a
    /// face then labels each entry with its number, from 1).
    pub index: Index,
}

/// What the entries of a one-dimensional live value count.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Index {
    /// Nothing in particular (a scalar, a list of named rows).
    #[default]
    None,
    /// One entry per epoch of the latest update (`approx_kl`, `clip_frac`, the losses).
    Epoch,
    /// One entry per episode of the run (`returns`, `moving_average`).
    Episode,
}

impl Index {
    /// The name of what is counted, for a table's corner: `epoch`, `episode`.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::None => "",
            Self::Epoch => crate::i18n::t("epoch", "轮"),
            Self::Episode => crate::i18n::t("episode", "回合"),
        }
    }
}

/// The two axes of a grid tensor, so that a face can label its rows and columns.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Axes {
    /// The quantity down the rows.
    pub rows: Axis,
    /// The quantity across the columns.
    pub columns: Axis,
}

/// One axis of a grid: the quantity and its value at each row or column.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Axis {
    /// The quantity, as the lessons write it (`θ`, `θ̇`).
    pub name: &'static str,
    /// The value at each row or column, written for a label (`-π`, `-3π/4`, …, `8`, `6`, …).
    pub ticks: Vec<String>,
}

impl TensorView {
    fn new(name: &str, shape: Vec<usize>, dtype: &'static str, values: Vec<f64>) -> Self {
        let marks = vec![Mark::Plain; values.len()];
        Self {
            name: name.into(),
            shape,
            dtype,
            labels: Vec::new(),
            values,
            marks,
            axes: None,
            index: Index::None,
        }
    }

    /// The same values, labelled as one entry per `index` (epoch or episode).
    #[must_use]
    pub fn counting(mut self, index: Index) -> Self {
        self.index = index;
        self
    }

    /// A float32 column `(N, 1)` named `name`, unmarked: how a notebook shows a vector it
    /// computed itself.
    #[must_use]
    pub fn column(name: &str, values: &[f32]) -> Self {
        Self::new(
            name,
            vec![values.len(), 1],
            "float32",
            values.iter().map(|&v| f64::from(v)).collect(),
        )
    }

    pub(crate) fn rows<const N: usize>(name: &str, rows: &[[f32; N]]) -> Self {
        let values = rows.iter().flatten().map(|&v| f64::from(v)).collect();
        Self::new(name, vec![rows.len(), N], "float32", values)
    }

    fn flags(name: &str, flags: &[bool]) -> Self {
        let mut t = Self::new(
            name,
            vec![flags.len(), 1],
            "float32",
            flags.iter().map(|&d| if d { 1.0 } else { 0.0 }).collect(),
        );
        t.marks = flags
            .iter()
            .map(|&d| if d { Mark::Done } else { Mark::Plain })
            .collect();
        t
    }

    /// Columns per displayed row (the last dimension, 1 for vectors and scalars).
    #[must_use]
    pub fn cols(&self) -> usize {
        if self.shape.len() >= 2 {
            self.shape[self.shape.len() - 1].max(1)
        } else {
            1
        }
    }

    /// `(min, max, mean)` of the finite values, `None` when there are none.
    #[must_use]
    pub fn stats(&self) -> Option<(f64, f64, f64)> {
        let finite: Vec<f64> = self
            .values
            .iter()
            .copied()
            .filter(|v| v.is_finite())
            .collect();
        if finite.is_empty() {
            return None;
        }
        let min = finite.iter().copied().fold(f64::INFINITY, f64::min);
        let max = finite.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        Some((min, max, finite.iter().sum::<f64>() / finite.len() as f64))
    }

    /// How many entries carry `mark`.
    #[must_use]
    pub fn count(&self, mark: Mark) -> usize {
        self.marks.iter().filter(|&&m| m == mark).count()
    }

    /// A one-line shape description, like `(149, 1) float32`.
    #[must_use]
    pub fn shape_text(&self) -> String {
        let dims: Vec<String> = self.shape.iter().map(ToString::to_string).collect();
        let shape = match dims.len() {
            0 => "()".to_string(),
            1 => format!("({},)", dims[0]),
            _ => format!("({})", dims.join(", ")),
        };
        format!("{shape} {}", self.dtype)
    }
}

/// What the tutor knows after the latest episode and update.
///
/// A [`Session`] fills it in, once per episode; [`Snapshot::new`] is the view before any.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Snapshot {
    /// The hyper-parameters in force, as `(name, value)` in the seed's order.
    pub hyper: Vec<(String, String)>,
    /// Episodes finished so far.
    pub episodes: usize,
    /// Environment steps taken so far, over every episode.
    pub env_steps: usize,
    /// Every episode's return, in order.
    pub returns: Vec<f64>,
    /// The seed's `moving_average(returns, 9)`, same length as `returns` (empty while there
    /// are too few returns for the window).
    pub moving_average: Vec<f64>,
    /// The actor's and critic's parameters after the latest update, by PyTorch name.
    pub weights: NamedWeights,
    /// The clip range ε in force (for marking clipped ratios).
    pub eps: f32,
    /// The discount γ in force (for the return-to-go).
    pub gamma: f64,
    /// The agent's own part: what it shows of the latest episode and update. Its variant
    /// names the run's agent ([`Snapshot::agent`]).
    pub latest: Latest,
}

/// The Gaussian policy's `μ(θ, θ̇)` and `σ(θ, θ̇)` over a grid of Pendulum states.
///
/// Rows run over the angular velocity θ̇ from +8 (row 0) down to −8, columns over the angle
/// θ from −π to π (0 is upright); the state fed to the actor is `(cos θ, sin θ, θ̇)`.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct PolicyMap {
    /// The angles of the columns, in radians.
    pub thetas: Vec<f32>,
    /// The angular velocities of the rows, in rad/s.
    pub theta_dots: Vec<f32>,
    /// `μ` row by row (`theta_dots.len() × thetas.len()`).
    pub mu: Vec<f32>,
    /// `σ` row by row.
    pub std: Vec<f32>,
}

impl PolicyMap {
    /// Rows and columns of the grid the sessions compute.
    pub const SIZE: (usize, usize) = (9, 9);

    /// The grid of [`Self::SIZE`] under `policy`, a function of the state `(cos θ, sin θ, θ̇)`
    /// giving `(μ, σ)`.
    #[must_use]
    pub fn of(policy: impl Fn(&[f32; 3]) -> (f32, f32)) -> Self {
        let (rows, cols) = Self::SIZE;
        let pi = std::f32::consts::PI;
        let thetas: Vec<f32> = (0..cols)
            .map(|j| -pi + 2.0 * pi * j as f32 / (cols - 1) as f32)
            .collect();
        let theta_dots: Vec<f32> = (0..rows)
            .map(|i| 8.0 - 16.0 * i as f32 / (rows - 1) as f32)
            .collect();
        let mut map = Self {
            thetas,
            theta_dots,
            ..Self::default()
        };
        for &dot in &map.theta_dots {
            for &theta in &map.thetas {
                let (mu, std) = policy(&[theta.cos(), theta.sin(), dot]);
                map.mu.push(mu);
                map.std.push(std);
            }
        }
        map
    }
}

impl Snapshot {
    /// What the tutor shows before the first episode of a run with `config` and `seed`:
    /// the hyper-parameters and nothing else.
    #[must_use]
    pub fn new(config: impl Into<RunConfig>, seed: u64) -> Self {
        config.into().first_snapshot(seed)
    }

    /// The agent whose run this is.
    #[must_use]
    pub fn agent(&self) -> AgentKind {
        self.latest.agent()
    }

    /// The latest batch and update as every agent has them, `None` before the first episode.
    #[must_use]
    pub fn batch(&self) -> Option<Batch<'_>> {
        Some(self.latest.view()?.batch())
    }

    /// The view of live value `name`, `None` if it is not a live value of this run's agent
    /// (see [`values`]) or nothing has been computed for it yet.
    #[must_use]
    pub fn tensor(&self, name: &str) -> Option<TensorView> {
        if let Some(common) = lookup(name) {
            return common.view(self);
        }
        let own = self.agent().live_values().iter().find(|&&n| n == name)?;
        self.latest.view()?.tensor(own, self)
    }

    /// How many observations the latest episode went through: each state it acted in, then
    /// the one it ended in (0 before the first episode). The frames of an animation.
    #[must_use]
    pub fn observation_count(&self) -> usize {
        self.batch().map_or(0, |b| b.observation_count())
    }

    /// The latest episode's observation `i` (0 is the reset, [`Self::observation_count`]
    /// − 1 where it ended), `None` past the end.
    #[must_use]
    pub fn observation(&self, i: usize) -> Option<Vec<f32>> {
        self.batch()?.observation(i).map(<[f32]>::to_vec)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ppo::{EpochTrace, PpoConfig, UpdateTrace};
    use crate::run::IntoLatest;

    fn cartpole(trace: UpdateTrace) -> Latest {
        CartPoleLatest {
            trace,
            ..CartPoleLatest::default()
        }
        .into_latest()
    }

    fn snapshot() -> Snapshot {
        let trace = UpdateTrace {
            dones: vec![false, true],
            advantage: vec![0.5, -0.25],
            epochs: vec![EpochTrace {
                ratio: vec![1.3, 0.95],
                clipped: vec![true, false],
                ..EpochTrace::default()
            }],
            ..UpdateTrace::default()
        };
        Snapshot {
            latest: cartpole(trace),
            eps: 0.2,
            ..Snapshot::default()
        }
    }

    #[test]
    fn marks_follow_the_data() -> Result<(), &'static str> {
        let s = snapshot();
        let ratio = s.tensor("ratio").ok_or("no ratio")?;
        assert_eq!(ratio.marks, vec![Mark::Clipped, Mark::Plain]);
        let adv = s.tensor("advantage").ok_or("no advantage")?;
        assert_eq!(adv.marks, vec![Mark::Positive, Mark::Negative]);
        let dones = s.tensor("dones").ok_or("no dones")?;
        assert_eq!(dones.count(Mark::Done), 1);
        assert_eq!(adv.shape_text(), "(2, 1) float32");
        Ok(())
    }

    #[test]
    fn observations_are_the_states_then_where_the_episode_ended() {
        let mut s = Snapshot::new(PpoConfig::default(), 0);
        assert_eq!((s.observation_count(), s.observation(0)), (0, None));
        s.latest = cartpole(UpdateTrace {
            states: vec![[0.0; 4], [1.0; 4]],
            next_states: vec![[1.0; 4], [2.0; 4]],
            ..UpdateTrace::default()
        });
        assert_eq!(s.observation_count(), 3);
        assert_eq!(s.observation(1), Some(vec![1.0; 4]));
        assert_eq!(s.observation(2), Some(vec![2.0; 4]));
        assert_eq!(s.observation(3), None);
    }

    #[test]
    fn a_new_snapshot_shows_only_the_hyper_parameters() -> Result<(), &'static str> {
        let config = PpoConfig {
            eps: 0.3,
            ..PpoConfig::default()
        };
        let s = Snapshot::new(config, 7);
        let hyper = s.tensor("hyper").ok_or("no hyper")?;
        assert!(hyper.labels.contains(&"seed = 7".to_string()));
        assert!(hyper.labels.contains(&"eps = 0.3".to_string()));
        assert!((s.eps - 0.3).abs() < 1e-6);
        assert!(s.tensor("returns").is_none() && s.tensor("td_target").is_none());
        assert!(s.tensor("no_such_value").is_none());
        Ok(())
    }
}
