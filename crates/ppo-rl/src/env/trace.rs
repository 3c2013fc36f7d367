//! Recorded trajectories in the schema of Gymnasium's fixture traces.
//!
//! A [`Trajectory`] is `reset(seed)` followed by actions until the episode ends:
//! f64 internal states, f32 observations (widened to f64 for JSON), rewards and
//! both end flags. It is what `ppo-tutor cartpole --json` prints and what the
//! parity tests compare with `tests/fixtures/cartpole_gymnasium.json`.

use serde::{Deserialize, Serialize};

use super::seeding::NumpyRng;
use super::{CartPole, CartPoleConfig, EnvError};

/// Who picks the actions of a recorded episode.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Policy {
    /// A fixed list, applied in order until it runs out or the episode ends.
    Actions(Vec<usize>),
    /// Uniformly random actions from a generator seeded with the episode's seed.
    Random,
    /// Push towards the side the pole leans to (`θ + 0.3·θ̇ > 0` → right), 10% random.
    Lean,
}

/// One episode, in the fixture's schema.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Trajectory {
    /// The seed given to `reset`.
    pub seed: u64,
    /// The f64 state after `reset(seed)`.
    pub reset_state: [f64; 4],
    /// The f32 observation after `reset(seed)`, widened to f64.
    pub reset_obs: [f64; 4],
    /// The actions applied.
    pub actions: Vec<usize>,
    /// The f64 state after each step.
    pub states: Vec<[f64; 4]>,
    /// The f32 observation after each step, widened to f64.
    pub obs: Vec<[f64; 4]>,
    /// The reward of each step.
    pub rewards: Vec<f64>,
    /// `terminated` of each step.
    pub terminated: Vec<bool>,
    /// `truncated` of each step.
    pub truncated: Vec<bool>,
    /// States of further unseeded resets, when asked for.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub next_resets: Vec<[f64; 4]>,
}

fn widen(obs: [f32; 4]) -> [f64; 4] {
    obs.map(f64::from)
}

impl Trajectory {
    /// Resets a CartPole with `seed`, then plays `policy` for at most `max_steps` steps,
    /// stopping when the episode terminates or is truncated. Then performs
    /// `extra_resets` unseeded resets and records their states.
    ///
    /// # Errors
    /// [`EnvError::InvalidAction`] if the policy lists an action other than 0 or 1.
    pub fn record(
        config: CartPoleConfig,
        seed: u64,
        policy: &Policy,
        max_steps: usize,
        extra_resets: usize,
    ) -> Result<Self, EnvError> {
        let mut env = CartPole::with_config(config);
        let reset_obs = env.reset(Some(seed));
        let reset_state = env.state().ok_or(EnvError::NotReset)?;
        let mut t = Trajectory {
            seed,
            reset_state,
            reset_obs: widen(reset_obs),
            actions: Vec::new(),
            states: Vec::new(),
            obs: Vec::new(),
            rewards: Vec::new(),
            terminated: Vec::new(),
            truncated: Vec::new(),
            next_resets: Vec::new(),
        };
        let mut rng = NumpyRng::from_seed(seed.wrapping_add(10_000));
        let mut obs = reset_obs;
        for i in 0..max_steps {
            let action = match policy {
                Policy::Actions(list) => match list.get(i) {
                    Some(&a) => a,
                    None => break,
                },
                Policy::Random => usize::from(rng.next_f64() < 0.5),
                Policy::Lean => {
                    if rng.next_f64() > 0.1 {
                        usize::from(obs[2] + 0.3 * obs[3] > 0.0)
                    } else {
                        usize::from(rng.next_f64() < 0.5)
                    }
                }
            };
            let step = env.step(action)?;
            obs = step.obs;
            t.actions.push(action);
            t.states.push(env.state().ok_or(EnvError::NotReset)?);
            t.obs.push(widen(step.obs));
            t.rewards.push(step.reward);
            t.terminated.push(step.terminated);
            t.truncated.push(step.truncated);
            if step.terminated || step.truncated {
                break;
            }
        }
        for _ in 0..extra_resets {
            env.reset(None);
            t.next_resets.push(env.state().ok_or(EnvError::NotReset)?);
        }
        Ok(t)
    }

    /// The episode's return (sum of rewards).
    #[must_use]
    pub fn episode_return(&self) -> f64 {
        self.rewards.iter().sum()
    }
}
