//! The seed's PPO on CartPole (*Hands-on RL*, `task_PPO.py`), and REINFORCE on the same
//! networks: a softmax policy over CartPole's two actions.
//!
//! - [`config`]: [`PpoConfig`], whose `Default` is the seed's hyper-parameters, and the
//!   [`Algorithm`] (PPO or REINFORCE).
//! - [`agent`]: [`Agent`] with `take_action` and `update`, which returns an [`UpdateTrace`].
//! - [`trace`]: the recorded intermediates every face displays.
//! - [`gradient`]: the policy gradient and PPO's surrogate have one gradient at θ_old.
//! - [`penalty`]: PPO-Penalty's exact KL and adaptive β ([`Objective::Penalty`]).
//! - [`line_search`]: the KL-constrained line search on the surrogate's gradient
//!   ([`Objective::LineSearch`]).
//! - [`replay`]: re-running a recorded PyTorch update (`ppo_update_pytorch.json`).
//! - [`trust_region`]: how far the surrogate's prediction holds, measured along its gradient.

pub mod agent;
pub mod checkpoint;
pub mod config;
pub mod gradient;
pub mod line_search;
pub mod penalty;
pub mod replay;
pub mod trace;
pub mod trust_region;

use std::path::Path;

use crate::env::CartPole;
use crate::ppo::PpoError;
use crate::ppo::checkpoint::CheckpointKind;
use crate::ppo::model::NamedWeights;
use crate::ppo::on_policy::{AgentConfig, Batch, OnPolicyAgent, Replayed};

pub use agent::{Agent, Losses, Transitions};
pub use config::{Algorithm, Objective, PpoConfig, RuleClash, RuleSetting, UpdateRule};
pub use trace::{EarlyStop, EpochTrace, LineSearchTrace, PenaltyTrace, UpdateTrace};

/// Observations per state: CartPole's `(x, x_dot, theta, theta_dot)`.
pub const STATE_DIM: usize = 4;
/// Actions: 0 pushes left, 1 pushes right.
pub const ACTION_DIM: usize = 2;

impl Batch for Transitions {
    type Obs = [f32; 4];
    type Action = usize;

    fn record(
        &mut self,
        state: [f32; 4],
        action: usize,
        reward: f32,
        next_state: [f32; 4],
        done: bool,
        terminated: bool,
    ) {
        self.push(state, action, reward, next_state, done, terminated);
    }

    fn steps(&self) -> usize {
        self.len()
    }

    fn terminated(&self) -> Vec<bool> {
        self.terminated.clone()
    }
}

impl AgentConfig for PpoConfig {
    type Agent = Agent;

    fn validate(&self) -> Result<(), PpoError> {
        PpoConfig::validate(self)
    }

    fn num_episodes(&self) -> usize {
        self.num_episodes
    }

    fn env_id(&self) -> &'static str {
        self.env_id.as_str()
    }

    fn max_return(&self) -> f64 {
        f64::from(self.env_id.max_episode_steps())
    }

    const ENV_IDS: &'static [&'static str] = &["CartPole-v1", "CartPole-v0"];

    fn set_env_id(&mut self, id: &str) -> bool {
        id.parse().map(|id| self.env_id = id).is_ok()
    }
}

/// The seed's PPO, or REINFORCE when `config.algorithm` says so: one agent, two update
/// rules on the same networks.
impl OnPolicyAgent for Agent {
    type Config = PpoConfig;
    type Env = CartPole;
    type Rollout = super::rollout::OneEpisode<CartPole>;
    type Batch = Transitions;
    type Trace = UpdateTrace;

    const CHECKPOINT: CheckpointKind = CheckpointKind {
        env: "CartPole-v1",
        algorithm: "ppo",
        telltale: "actor.fc2.weight",
        train_flags: "",
    };

    fn create(config: &PpoConfig, seed: u64) -> Result<Self, PpoError> {
        Agent::new(config, seed)
    }

    fn environment(config: &PpoConfig) -> CartPole {
        CartPole::new(config.env_id)
    }

    fn act(&mut self, obs: &[f32; 4]) -> Result<usize, PpoError> {
        self.take_action(obs)
    }

    fn learn(&mut self, batch: &Transitions) -> Result<UpdateTrace, PpoError> {
        self.update(batch)
    }

    fn path_of(trace: &UpdateTrace) -> crate::ppo::UpdatePath {
        trace.path
    }

    fn named_weights(&self) -> Result<NamedWeights, PpoError> {
        self.weights()
    }

    fn load_from(path: &Path, config: &PpoConfig, seed: u64) -> Result<Self, PpoError> {
        Agent::load(path, config, seed)
    }

    /// A softmax policy: `actor.fc2`, no Gaussian head.
    fn replays(weights_before: &serde_json::Value) -> bool {
        weights_before.get("actor.fc2.weight").is_some()
    }

    fn replay(text: &str, file: &str) -> Result<Vec<Result<Replayed, PpoError>>, PpoError> {
        let cases = replay::parse_replay(text, file)?;
        Ok(Replayed::all(&cases, replay::replay_case, |case, out| {
            let losses = out.epochs.iter().map(|e| (e.actor_loss, e.critic_loss));
            (case.batch.len(), losses.collect())
        }))
    }
}
