//! The seed's PPO (*Hands-on RL* chapter 12, `task_PPO.py` + `rl_utils.py`) on candle.
//!
//! Read it top to bottom in the seed's order:
//!
//! - [`config`]: [`PpoConfig`], whose `Default` is the seed's hyper-parameters.
//! - [`model`]: [`PolicyNet`] `π(a|s)` and [`ValueNet`] `V(s)`, initialised like PyTorch.
//! - [`ops`]: `relu` and the bias add as candle ops with a short backward pass.
//! - [`adam`]: [`Adam`], `torch.optim.Adam` step for step.
//! - [`advantage`]: GAE, `compute_advantage` in f32 as numpy runs it.
//! - [`agent`]: [`Agent`] with `take_action` and `update`, which returns an [`UpdateTrace`].
//! - [`trace`]: the recorded intermediates every face displays.
//! - [`gradient`]: the policy gradient and PPO's surrogate have one gradient at θ_old, computed.
//! - [`rollout`]: how experience is collected between updates, written once: the seed's
//!   one episode ([`OneEpisode`]) or `T` steps of a vector of environments ([`FixedSteps`]).
//! - [`train`](mod@train): `train_on_policy_agent` as a step-by-step [`Trainer`], driving the
//!   agent's rollout.
//! - [`moving_average`](mod@moving_average): `rl_utils.moving_average`, for the return curve.
//! - [`seeds`]: one configuration over several seeds in parallel, and the band of their curves.
//! - [`checkpoint`]: saving and loading an agent as safetensors with PyTorch's names.
//! - [`replay`]: re-running a recorded PyTorch update (`ppo_update_pytorch.json`).
//! - [`continuous`]: the book's `PPOContinuous` for Pendulum, a Gaussian policy on the same
//!   critic, GAE, clipped surrogate and Adam ([`PpoContinuous`]), trained by
//!   [`ContinuousTrainer`].
//! - [`update_path`]: which implementation ran an update ([`UpdatePath`]), the rule that
//!   picks it, and `PPO_TUTOR_UPDATE=candle`, which forces the reference.
//!
//! Both updates are written on candle tensors with autograd: that is the code the lessons
//! show, and what runs as [`UpdatePath::Candle`]. Where the configuration is the seed's
//! (the book's for Pendulum) and the CPU has AVX2 and FMA, the same IEEE operations in the
//! same order run on plain `f32` slices instead, [`UpdatePath::Plain`]: same numbers, bit for
//! bit, about ten to twenty times faster. The rule that picks one, and what the plain path
//! costs a maintainer, are stated once, in [`update_path`]; each trace says which ran
//! ([`UpdateTrace::path`], [`ContinuousUpdateTrace::path`]), and `ppo-tutor train` prints it.
//!
//! Acting (one observation at a time, 200k times per run) runs the same two matrix products
//! in plain Rust on a copy of the actor's weights, which is an order of magnitude faster
//! than a tensor round trip.

pub mod adam;
pub mod advantage;
pub mod checkpoint;
pub mod continuous;
pub mod discrete;
pub(crate) mod kernels;
pub mod model;
pub mod moving_average;
pub mod on_policy;
pub mod ops;
pub(crate) mod ranges;
pub mod replay_file;
pub mod rollout;
pub mod seeds;
pub mod train;
pub mod update_path;

// The discrete agent's modules keep their old paths (`ppo::agent`, `ppo::config`, ...).
pub use discrete::{
    ACTION_DIM, STATE_DIM, agent, config, gradient, penalty, replay, trace, trust_region,
};

pub use adam::Adam;
pub use advantage::{compute_advantage, normalize_advantage};
pub use agent::{Agent, Losses, Transitions};
pub use checkpoint::CheckpointKind;
pub use config::{Algorithm, Objective, PpoConfig, RuleClash, RuleSetting, UpdateRule};
pub use continuous::{
    ContinuousEpisodeReport, ContinuousEpochTrace, ContinuousTransitions, ContinuousUpdateTrace,
    PolicyNetContinuous, PpoContinuous, PpoContinuousConfig,
};
pub use gradient::{SurrogateGradients, surrogate_gradients};
pub use model::{Linear, NamedWeights, PolicyNet, ValueNet, WeightTensor};
pub use moving_average::moving_average;
pub use on_policy::{AgentConfig, Batch, Budget, EnvStep, Environment, OnPolicyAgent};
pub use rollout::{
    Collected, FinishedEpisode, FixedSteps, OneEpisode, Rollout, StepBuffer, VecActor,
};
pub use trace::{EarlyStop, EpochTrace, PenaltyTrace, UpdateTrace};
pub use train::{
    ContinuousTrainer, EpisodeReport, TrainSummary, Trainer, Training, UpdateReport, train,
};
pub use update_path::UpdatePath;

use crate::env::EnvError;

/// What can go wrong in the PPO engine. Messages say what, where, and what to do.
#[derive(Debug, thiserror::Error)]
// Display below, in the current language (thiserror writes only `source` and `From`).
pub enum PpoError {
    /// A hyper-parameter outside its range.
    InvalidConfig {
        /// The field's name as in [`PpoConfig`] (and the `--flag` of `ppo-tutor train`).
        field: &'static str,
        /// The value given.
        value: String,
        /// The accepted range.
        expected: &'static str,
    },
    /// Training produced a NaN or infinite number.
    Diverged {
        /// The episode (0-based) whose acting or update hit the non-finite value.
        episode: usize,
        /// Which quantity went non-finite, and where.
        what: String,
    },
    /// A non-finite value inside one update or action (the trainer adds the episode).
    NonFinite(String),
    /// An update was asked for an empty batch.
    EmptyBatch,
    /// A batch whose columns have different lengths or hold invalid values.
    InvalidBatch(String),
    /// A key missing from a replay or checkpoint file.
    MissingKey {
        /// The file read.
        file: String,
        /// The key's path, like `cases[0].batch.states`.
        key: String,
        /// What the key should hold, with its shape.
        expected: String,
    },
    /// A value of the wrong shape or type in a replay or checkpoint file.
    WrongShape {
        /// The file read.
        file: String,
        /// The key's path, like `cases[0].weights_before.actor.fc1.weight`.
        key: String,
        /// What was expected, with its shape.
        expected: String,
        /// What the file holds.
        got: String,
    },
    /// A file that could not be read or parsed at all.
    File {
        /// The file.
        file: String,
        /// What went wrong.
        reason: String,
    },
    /// `moving_average` needs an odd window no longer than the series plus one.
    InvalidWindow {
        /// The window asked for.
        window: usize,
        /// The series length.
        len: usize,
    },
    /// The environment refused a step.
    Env(EnvError),
    /// A candle tensor operation failed (a bug: shapes are checked before).
    Candle(#[from] candle_core::Error),
}

impl From<EnvError> for PpoError {
    fn from(e: EnvError) -> Self {
        Self::Env(e)
    }
}

/// `text` after a Chinese word: with a space before it when it starts with a Latin letter, a
/// digit or a bracket (`应为 f32 张量`, `应为形状 [2]`).
fn spaced(text: &str) -> String {
    match text.chars().next() {
        Some(c) if c.is_ascii_alphanumeric() || "[(".contains(c) => format!(" {text}"),
        _ => text.to_string(),
    }
}

impl std::fmt::Display for PpoError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        use crate::tr;
        let text = match self {
            Self::InvalidConfig {
                field,
                value,
                expected,
            } => tr!(
                "invalid {field} = {value}: expected {expected}",
                "{field} = {value} 无效：应为 {expected}"
            ),
            Self::Diverged { episode, what } => tr!(
                "training diverged at episode {episode}: {what}; lower the learning rates or enable --max-grad-norm",
                "训练在第 {episode} 个回合发散：{what}；请调低学习率，或加上 --max-grad-norm"
            ),
            Self::NonFinite(what) => tr!(
                "{what} is not finite (NaN or infinite)",
                "{what} 不是有限数（NaN 或无穷大）"
            ),
            Self::EmptyBatch => tr!(
                "the batch is empty: an update needs at least one transition",
                "这一批数据是空的：一次更新至少需要一条转移"
            ),
            Self::InvalidBatch(why) => tr!("invalid batch: {why}", "这一批数据无效：{why}"),
            Self::MissingKey {
                file,
                key,
                expected,
            } => {
                let wanted = spaced(expected);
                tr!(
                    "{file}: missing key '{key}' (expected {expected})",
                    "{file}：缺少键 '{key}'（应为{wanted}）"
                )
            }
            Self::WrongShape {
                file,
                key,
                expected,
                got,
            } => {
                let (wanted, found) = (spaced(expected), spaced(got));
                tr!(
                    "{file}: '{key}' has {got}, expected {expected}",
                    "{file}：'{key}' 应为{wanted}，实际是{found}"
                )
            }
            Self::File { file, reason } => tr!("{file}: {reason}", "{file}：{reason}"),
            Self::InvalidWindow { window, len } => tr!(
                "moving_average: window {window} does not fit {len} values (needs an odd window <= len + 1)",
                "moving_average：窗口 {window} 不适合 {len} 个值（窗口须为奇数，且不超过 len + 1）"
            ),
            Self::Env(e) => return std::fmt::Display::fmt(e, f),
            Self::Candle(e) => {
                let said = crate::causes::message(e);
                tr!("tensor operation failed: {said}", "{said}")
            }
        };
        f.write_str(&text)
    }
}
