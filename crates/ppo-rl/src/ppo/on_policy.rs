//! One abstraction for every agent the course trains: [`OnPolicyAgent`].
//!
//! The seed's PPO and REINFORCE on CartPole ([`Agent`](super::Agent), the algorithm chosen by
//! [`PpoConfig::algorithm`](super::PpoConfig)) and the book's `PPOContinuous` on Pendulum
//! ([`PpoContinuous`](super::PpoContinuous)) all do the same five things: act on one
//! observation, collect an episode into a batch, update on the batch (returning a trace of
//! every intermediate), validate their configuration, and save and load their weights.
//! Everything that drives an agent is written once, generic over this trait:
//!
//! - [`Training`](super::train::Training): `train_on_policy_agent`, one episode at a time;
//! - [`train_seeds`](super::seeds::train_seeds): one configuration over several seeds;
//! - in the course crate above this one (`ppo-engine`): the live session, `ppo-tutor
//!   train`, the lab and the sandbox, through its run registry, the one place that
//!   matches on the agent.
//!
//! Adding an agent: CONTRIBUTING.md, "Adding an agent".
//!
//! ```
//! use ppo_rl::ppo::{OnPolicyAgent, PpoConfig, PpoContinuousConfig, Training};
//!
//! fn mean_return<A: OnPolicyAgent>(config: A::Config) -> Result<f64, ppo_rl::ppo::PpoError> {
//!     let mut run = Training::<A>::new(config, 0)?;
//!     while run.next_episode()?.is_some() {}
//!     Ok(run.summary().mean_last(2))
//! }
//! let cartpole = PpoConfig { num_episodes: 2, ..PpoConfig::default() };
//! let pendulum = PpoContinuousConfig { num_episodes: 2, ..PpoContinuousConfig::default() };
//! assert!(mean_return::<ppo_rl::ppo::Agent>(cartpole)? > 0.0);
//! assert!(mean_return::<ppo_rl::ppo::PpoContinuous>(pendulum)? < 0.0);
//! # Ok::<(), ppo_rl::ppo::PpoError>(())
//! ```

use std::fmt::Debug;
use std::path::Path;

use serde::Serialize;

use super::PpoError;
use super::checkpoint::CheckpointKind;
use super::model::NamedWeights;
pub use crate::env::{EnvStep, Environment};

/// One episode's transitions, the seed's `transition_dict`.
pub trait Batch: Default + Clone + Debug + Send + 'static {
    /// One observation.
    type Obs;
    /// One action.
    type Action;

    /// Appends one step, as the seed's five `transition_dict[...].append(...)`:
    /// `done = terminated or truncated`; an agent that does not bootstrap on truncation
    /// ignores `terminated`.
    fn record(
        &mut self,
        state: Self::Obs,
        action: Self::Action,
        reward: f32,
        next_state: Self::Obs,
        done: bool,
        terminated: bool,
    );

    /// The number of transitions.
    fn steps(&self) -> usize;

    /// Gymnasium's `terminated` for each step.
    fn terminated(&self) -> Vec<bool>;
}

/// Checks one episode's columns: at least one step, and every column (name, length) as long
/// as `actions`, the `n` steps.
///
/// # Errors
/// [`PpoError::EmptyBatch`], or [`PpoError::InvalidBatch`] naming the first column of
/// another length.
pub(crate) fn check_columns(n: usize, columns: &[(&str, usize)]) -> Result<(), PpoError> {
    if n == 0 {
        return Err(PpoError::EmptyBatch);
    }
    match columns.iter().find(|(_, len)| *len != n) {
        Some((name, len)) => Err(PpoError::InvalidBatch(crate::tr!(
            "{name} has {len} entries but actions has {n}: every column needs one per step",
            "{name} 有 {len} 项，而 actions 有 {n} 项：每一列在每个时间步都要有一项"
        ))),
        None => Ok(()),
    }
}

/// How long a run trains.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum Budget {
    /// Until this many episodes have finished (the seed's `num_episodes`).
    Episodes(usize),
    /// Until this many environment steps have been taken (CleanRL's `total_timesteps`).
    Steps(u64),
}

/// The hyper-parameters of an agent's run.
pub trait AgentConfig: Clone + Debug + PartialEq + Send + Sync + Serialize + 'static {
    /// The agent these settings train.
    type Agent: OnPolicyAgent<Config = Self>;

    /// Every field in its range.
    ///
    /// # Errors
    /// [`PpoError::InvalidConfig`] naming the first field out of range and its range.
    fn validate(&self) -> Result<(), PpoError>;

    /// Episodes the run trains for (one update per episode).
    fn num_episodes(&self) -> usize;

    /// When the run stops: after [`AgentConfig::num_episodes`] episodes unless the agent
    /// says otherwise (a fixed-steps rollout counts environment steps).
    fn budget(&self) -> Budget {
        Budget::Episodes(self.num_episodes())
    }

    /// The Gymnasium id of the environment the run plays (`CartPole-v0` where the settings
    /// say so).
    fn env_id(&self) -> &'static str;

    /// The highest return an episode can have, for a plot's scale (CartPole's time limit,
    /// Pendulum's 0).
    fn max_return(&self) -> f64;

    /// The Gymnasium ids a run of this agent can play, in the sandbox's order
    /// (`CartPole-v1`, `CartPole-v0`).
    const ENV_IDS: &'static [&'static str];

    /// Plays `id`, one of [`AgentConfig::ENV_IDS`]; `false` (nothing changed) for another.
    fn set_env_id(&mut self, id: &str) -> bool;
}

/// An on-policy agent: the seed's `take_action` and `update`, with the environment it
/// plays, the batch it learns from and the trace each update records.
pub trait OnPolicyAgent: Sized + Clone + Debug + Send + 'static {
    /// Its hyper-parameters.
    type Config: AgentConfig<Agent = Self>;
    /// The environment it plays.
    type Env: Environment;
    /// What one update learns from (one episode of that environment, for the seed's agents).
    type Batch: Batch<Obs = Obs<Self>, Action = Action<Self>>;
    /// How that batch is collected ([`OneEpisode`](super::rollout::OneEpisode) for the
    /// seed's agents).
    type Rollout: super::rollout::Rollout<Self>;
    /// What one update records: every intermediate the faces show.
    type Trace: Clone + Debug + PartialEq + Send + Serialize + 'static;

    /// How its checkpoints are marked (environment and algorithm).
    const CHECKPOINT: CheckpointKind;

    /// A fresh agent: networks initialised from `seed` (as `torch.manual_seed(seed)`).
    ///
    /// # Errors
    /// [`PpoError::InvalidConfig`] for a hyper-parameter out of range.
    fn create(config: &Self::Config, seed: u64) -> Result<Self, PpoError>;

    /// The environment a run of `config` plays.
    fn environment(config: &Self::Config) -> Self::Env;

    /// Samples an action for one observation (the seed's `take_action`).
    ///
    /// # Errors
    /// [`PpoError::NonFinite`] when the policy's output is not finite.
    fn act(&mut self, obs: &Obs<Self>) -> Result<Action<Self>, PpoError>;

    /// One update on an episode (the seed's `update`), recording every intermediate.
    ///
    /// # Errors
    /// [`PpoError::EmptyBatch`], [`PpoError::InvalidBatch`] or [`PpoError::NonFinite`].
    fn learn(&mut self, batch: &Self::Batch) -> Result<Self::Trace, PpoError>;

    /// Which implementation ran the update `trace` records (plain `f32` kernels or candle).
    fn path_of(trace: &Self::Trace) -> super::UpdatePath;

    /// The weights, with PyTorch's names.
    ///
    /// # Errors
    /// [`PpoError::Candle`] if a tensor cannot be read back (a bug).
    fn named_weights(&self) -> Result<NamedWeights, PpoError>;

    /// Writes the weights to a safetensors checkpoint marked [`Self::CHECKPOINT`].
    ///
    /// # Errors
    /// [`PpoError::File`] when the file cannot be written.
    fn save_to(&self, path: &Path) -> Result<(), PpoError> {
        super::checkpoint::write_checkpoint(path, self.named_weights()?, Self::CHECKPOINT)
    }

    /// Reads a checkpoint written by [`OnPolicyAgent::save_to`] (hidden width from the
    /// file); actions are sampled with `seed`.
    ///
    /// # Errors
    /// [`PpoError::File`], [`PpoError::MissingKey`] or [`PpoError::WrongShape`], naming the
    /// file and the tensor.
    fn load_from(path: &Path, config: &Self::Config, seed: u64) -> Result<Self, PpoError>;

    /// Whether a recorded update whose first case starts from `weights_before` (the
    /// fixture's JSON object of named tensors) is this agent's.
    fn replays(weights_before: &serde_json::Value) -> bool;

    /// Replays every case of a recorded PyTorch update of this agent
    /// (`tests/fixtures/*_update_pytorch.json`): one result per case; `file` names the file
    /// in errors.
    ///
    /// # Errors
    /// [`PpoError::File`], [`PpoError::MissingKey`] or [`PpoError::WrongShape`] naming the
    /// key, when the file cannot be read as this agent's cases.
    #[allow(clippy::type_complexity)]
    fn replay(text: &str, file: &str) -> Result<Vec<Result<Replayed, PpoError>>, PpoError>;
}

/// One case of a recorded PyTorch update, replayed: what `ppo-tutor replay` prints.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Replayed {
    /// The case's transitions.
    pub transitions: usize,
    /// `(actor_loss, critic_loss)` of each epoch.
    pub losses: Vec<(f32, f32)>,
    /// Every tensor the update computed, as JSON text in the fixture's key names, shapes
    /// and order (f32 values printed as f32, shortest form).
    pub output: String,
}

impl Replayed {
    /// Replays `cases` with `replay`; `summary` gives a case's transitions and each epoch's
    /// `(actor_loss, critic_loss)` from the case and its output.
    pub(crate) fn all<C, O: Serialize>(
        cases: &[C],
        replay: impl Fn(&C) -> Result<O, PpoError>,
        summary: impl Fn(&C, &O) -> (usize, Vec<(f32, f32)>),
    ) -> Vec<Result<Self, PpoError>> {
        cases
            .iter()
            .map(|case| {
                let out = replay(case)?;
                let (transitions, losses) = summary(case, &out);
                let output = serde_json::to_string(&out).map_err(|e| {
                    PpoError::NonFinite(crate::tr!("the replay's output: {e}", "回放的输出：{e}"))
                })?;
                Ok(Self {
                    transitions,
                    losses,
                    output,
                })
            })
            .collect()
    }
}

/// The observation type of agent `A`.
pub type Obs<A> = <<A as OnPolicyAgent>::Env as Environment>::Obs;
/// The action type of agent `A`.
pub type Action<A> = <<A as OnPolicyAgent>::Env as Environment>::Action;
