//! The interfaces every environment shares, as Gymnasium names them: [`Environment`] (one
//! environment's `reset` and `step`, returning one [`EnvStep`]) and [`VectorEnv`] (several
//! environments stepped together with automatic reset, returning one [`VecStep`]).
//!
//! A vector environment resets an environment whose episode ended in one of two ways, the
//! two a learner meets ([`Autoreset`]):
//!
//! - **same-step** (Gymnasium 0.29, which CleanRL pins): the step that ends an episode
//!   returns the *next* episode's first observation in `obs`, and the real last observation
//!   in `final_obs`;
//! - **next-step** (Gymnasium 1.x's default): the step that ends an episode returns its real
//!   last observation in `obs`; the *following* step ignores that environment's action,
//!   resets it and returns its first observation with reward 0 and both flags false
//!   (`reset[i]` says so).
//!
//! [`SyncVectorEnv`] runs any [`Environment`] this way, one after the other, as Gymnasium's
//! `SyncVectorEnv`: `reset(Some(s))` seeds environment `i` with `s + i`, and each keeps its
//! own generator across autoresets. [`CartPoleVec`] and [`PendulumVec`] are the
//! struct-of-arrays fast forms (same-step only) with the same numbers.
//!
//! ```
//! use ppo_rl::env::{Autoreset, CartPole, EnvId, SyncVectorEnv, VectorEnv};
//! let envs = (0..4).map(|_| CartPole::new(EnvId::CartPoleV1)).collect();
//! let mut vec = SyncVectorEnv::new(envs, Autoreset::NextStep)?;
//! let first = vec.reset(Some(0)).to_vec();
//! let mut single = CartPole::new(EnvId::CartPoleV1);
//! assert_eq!(first[2], single.reset(Some(2)));
//! let out = vec.step(&[1, 0, 1, 0])?;
//! assert_eq!(out.rewards, vec![1.0; 4]);
//! # Ok::<(), ppo_rl::env::EnvError>(())
//! ```

use std::fmt::{self, Debug};
use std::str::FromStr;

use super::vector::{CartPoleVec, PendulumVec, VecStep};
use super::{CartPole, EnvError, Pendulum};

/// One step of an [`Environment`], as Gymnasium's `env.step` returns it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EnvStep<O> {
    /// The next observation.
    pub obs: O,
    /// The reward.
    pub reward: f64,
    /// The episode ended in a terminal state (the pole fell, the cart left the track).
    pub terminated: bool,
    /// The time limit cut the episode.
    pub truncated: bool,
}

/// An environment an agent trains on: Gymnasium's `reset` and `step`.
pub trait Environment: Clone + Debug + Send + 'static {
    /// One observation.
    type Obs: Copy + Debug + Send + 'static;
    /// One action.
    type Action: Copy + Debug + Send + 'static;

    /// Starts an episode; `seed` reseeds the environment's generator (Gymnasium's
    /// `reset(seed=...)`), `None` continues it.
    fn reset(&mut self, seed: Option<u64>) -> Self::Obs;

    /// Applies `action`.
    ///
    /// # Errors
    /// An [`EnvError`] for an invalid action or a step before `reset`.
    fn step(&mut self, action: Self::Action) -> Result<EnvStep<Self::Obs>, EnvError>;

    /// The time limit: steps after which an episode is truncated.
    fn time_limit(&self) -> usize;
}

impl Environment for CartPole {
    type Obs = [f32; 4];
    type Action = usize;

    fn reset(&mut self, seed: Option<u64>) -> [f32; 4] {
        CartPole::reset(self, seed)
    }

    fn step(&mut self, action: usize) -> Result<EnvStep<[f32; 4]>, EnvError> {
        let s = CartPole::step(self, action)?;
        Ok(EnvStep {
            obs: s.obs,
            reward: s.reward,
            terminated: s.terminated,
            truncated: s.truncated,
        })
    }

    fn time_limit(&self) -> usize {
        self.config().env_id.max_episode_steps() as usize
    }
}

impl Environment for Pendulum {
    type Obs = [f32; 3];
    /// The sampled torque, unclipped: the environment clips it to `[-2, 2]`, as the book's
    /// `env.step([action])` leaves it to Gymnasium.
    type Action = f32;

    fn reset(&mut self, seed: Option<u64>) -> [f32; 3] {
        Pendulum::reset(self, seed)
    }

    fn step(&mut self, torque: f32) -> Result<EnvStep<[f32; 3]>, EnvError> {
        let s = Pendulum::step(self, f64::from(torque))?;
        Ok(EnvStep {
            obs: s.obs,
            reward: s.reward,
            terminated: s.terminated,
            truncated: s.truncated,
        })
    }

    fn time_limit(&self) -> usize {
        super::pendulum::MAX_EPISODE_STEPS as usize
    }
}

/// When a vector environment resets an environment whose episode ended.
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, Hash, Default, serde::Serialize, serde::Deserialize,
)]
#[serde(rename_all = "kebab-case")]
pub enum Autoreset {
    /// In the step that ends the episode (Gymnasium 0.29, CleanRL): `obs` is the next
    /// episode's first observation, the real last one is in `final_obs`.
    #[default]
    SameStep,
    /// In the step after (Gymnasium 1.x): that step ignores the action and returns the first
    /// observation, reward 0, both flags false, and `reset` true.
    NextStep,
}

impl Autoreset {
    /// Both modes, in the order help text lists them.
    pub const ALL: [Autoreset; 2] = [Autoreset::SameStep, Autoreset::NextStep];

    /// The mode's name on the command line and in traces.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Autoreset::SameStep => "same-step",
            Autoreset::NextStep => "next-step",
        }
    }
}

impl fmt::Display for Autoreset {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Autoreset {
    type Err = EnvError;

    fn from_str(s: &str) -> Result<Self, EnvError> {
        Self::ALL
            .into_iter()
            .find(|mode| mode.name() == s)
            .ok_or_else(|| EnvError::UnknownAutoreset(s.to_owned()))
    }
}

/// Several environments stepped together with automatic reset: Gymnasium's `VectorEnv`.
pub trait VectorEnv {
    /// One observation.
    type Obs: Copy + Debug + Send + 'static;
    /// One action.
    type Action: Copy + Debug + Send + 'static;

    /// How many environments there are.
    fn num_envs(&self) -> usize;

    /// How an environment whose episode ended is reset.
    fn autoreset(&self) -> Autoreset;

    /// Resets every environment; `Some(s)` seeds environment `i` with `s + i` (wrapping),
    /// `None` continues each generator. Returns the first observations.
    fn reset(&mut self, seed: Option<u64>) -> &[Self::Obs];

    /// Steps every environment with its action.
    ///
    /// # Errors
    /// [`EnvError::ActionCount`] for a wrong number of actions, [`EnvError::NotReset`]
    /// before the first [`VectorEnv::reset`], or the environment's own error for an
    /// invalid action (nothing is stepped then where the environment checks first).
    fn step(&mut self, actions: &[Self::Action]) -> Result<&VecStep<Self::Obs>, EnvError>;
}

/// Any [`Environment`], `n` of them stepped one after the other: Gymnasium's `SyncVectorEnv`.
#[derive(Debug, Clone)]
pub struct SyncVectorEnv<E: Environment> {
    envs: Vec<E>,
    autoreset: Autoreset,
    /// Under next-step autoreset: environment `i` ended on the last step and resets on this one.
    pending: Vec<bool>,
    out: VecStep<E::Obs>,
}

impl<E: Environment> SyncVectorEnv<E> {
    /// The environments `envs`, reset under `autoreset`.
    ///
    /// # Errors
    /// [`EnvError::NoEnvironments`] when `envs` is empty.
    pub fn new(envs: Vec<E>, autoreset: Autoreset) -> Result<Self, EnvError> {
        if envs.is_empty() {
            return Err(EnvError::NoEnvironments);
        }
        let n = envs.len();
        Ok(Self {
            envs,
            autoreset,
            pending: vec![false; n],
            out: VecStep::before_reset(n),
        })
    }

    /// The environments, in order.
    #[must_use]
    pub fn envs(&self) -> &[E] {
        &self.envs
    }
}

impl<E: Environment> VectorEnv for SyncVectorEnv<E> {
    type Obs = E::Obs;
    type Action = E::Action;

    fn num_envs(&self) -> usize {
        self.envs.len()
    }

    fn autoreset(&self) -> Autoreset {
        self.autoreset
    }

    fn reset(&mut self, seed: Option<u64>) -> &[E::Obs] {
        self.out.obs = self
            .envs
            .iter_mut()
            .enumerate()
            .map(|(i, env)| env.reset(seed.map(|s| s.wrapping_add(i as u64))))
            .collect();
        self.pending.fill(false);
        self.out.clear_step();
        &self.out.obs
    }

    fn step(&mut self, actions: &[E::Action]) -> Result<&VecStep<E::Obs>, EnvError> {
        if actions.len() != self.envs.len() {
            return Err(EnvError::ActionCount {
                expected: self.envs.len(),
                got: actions.len(),
            });
        }
        if self.out.obs.len() != self.envs.len() {
            return Err(EnvError::NotReset);
        }
        for (i, (env, &action)) in self.envs.iter_mut().zip(actions).enumerate() {
            self.out.final_obs[i] = None;
            if self.pending[i] {
                self.pending[i] = false;
                self.out.obs[i] = env.reset(None);
                self.out.rewards[i] = 0.0;
                self.out.terminated[i] = false;
                self.out.truncated[i] = false;
                self.out.reset[i] = true;
                continue;
            }
            let s = env.step(action)?;
            self.out.rewards[i] = s.reward;
            self.out.terminated[i] = s.terminated;
            self.out.truncated[i] = s.truncated;
            self.out.reset[i] = false;
            let ended = s.terminated || s.truncated;
            match (ended, self.autoreset) {
                (true, Autoreset::SameStep) => {
                    self.out.final_obs[i] = Some(s.obs);
                    self.out.obs[i] = env.reset(None);
                }
                (true, Autoreset::NextStep) => {
                    self.pending[i] = true;
                    self.out.obs[i] = s.obs;
                }
                (false, _) => self.out.obs[i] = s.obs,
            }
        }
        Ok(&self.out)
    }
}

impl VectorEnv for CartPoleVec {
    type Obs = [f32; 4];
    type Action = usize;

    fn num_envs(&self) -> usize {
        self.len()
    }

    fn autoreset(&self) -> Autoreset {
        Autoreset::SameStep
    }

    fn reset(&mut self, seed: Option<u64>) -> &[[f32; 4]] {
        self.reset_all(seed);
        self.obs()
    }

    fn step(&mut self, actions: &[usize]) -> Result<&VecStep, EnvError> {
        CartPoleVec::step(self, actions)
    }
}

impl VectorEnv for PendulumVec {
    type Obs = [f32; 3];
    /// The sampled torque, unclipped, as [`Pendulum`]'s [`Environment`] impl takes it.
    type Action = f32;

    fn num_envs(&self) -> usize {
        self.len()
    }

    fn autoreset(&self) -> Autoreset {
        Autoreset::SameStep
    }

    fn reset(&mut self, seed: Option<u64>) -> &[[f32; 3]] {
        self.reset_all(seed);
        self.obs()
    }

    fn step(&mut self, torques: &[f32]) -> Result<&VecStep<[f32; 3]>, EnvError> {
        let torques: Vec<f64> = torques.iter().map(|&t| f64::from(t)).collect();
        PendulumVec::step(self, &torques)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::env::{CartPoleConfig, EnvId, PendulumConfig};

    fn cartpoles(n: usize) -> Vec<CartPole> {
        (0..n).map(|_| CartPole::new(EnvId::CartPoleV1)).collect()
    }

    /// A fixed action pattern that makes episodes end at different steps.
    fn action(t: usize, i: usize) -> usize {
        ((t * 7 + i * 3) / 5) % 2
    }

    #[test]
    fn names_round_trip_and_unknown_is_an_error() {
        for mode in Autoreset::ALL {
            assert_eq!(mode.name().parse::<Autoreset>(), Ok(mode));
            assert_eq!(mode.to_string(), mode.name());
            let json = serde_json::to_string(&mode).unwrap_or_default();
            assert_eq!(json, format!("\"{}\"", mode.name()));
        }
        let err = "same".parse::<Autoreset>().err().map(|e| e.to_string());
        assert!(err.is_some_and(|e| e.contains("same-step or next-step")));
    }

    #[test]
    fn empty_is_an_error_and_step_needs_reset_and_one_action_each() {
        assert_eq!(
            SyncVectorEnv::<CartPole>::new(Vec::new(), Autoreset::SameStep).err(),
            Some(EnvError::NoEnvironments)
        );
        let Ok(mut v) = SyncVectorEnv::new(cartpoles(3), Autoreset::SameStep) else {
            panic!("three environments are a vector");
        };
        assert_eq!(v.step(&[0, 0, 0]).err(), Some(EnvError::NotReset));
        v.reset(Some(0));
        assert_eq!(
            v.step(&[0, 0]).err(),
            Some(EnvError::ActionCount {
                expected: 3,
                got: 2
            })
        );
        assert_eq!(v.step(&[0, 2, 0]).err(), Some(EnvError::InvalidAction(2)));
    }

    #[test]
    fn struct_of_arrays_equals_sync_same_step() {
        let Ok(mut sync) = SyncVectorEnv::new(cartpoles(5), Autoreset::SameStep) else {
            panic!("five environments are a vector");
        };
        let mut fast = CartPoleVec::new(CartPoleConfig::new(EnvId::CartPoleV1), 5, 0);
        assert_eq!(sync.reset(Some(9)), VectorEnv::reset(&mut fast, Some(9)));
        let mut ends = 0;
        for t in 0..700 {
            let actions: Vec<usize> = (0..5).map(|i| action(t, i)).collect();
            let (Ok(a), Ok(b)) = (
                sync.step(&actions).cloned(),
                VectorEnv::step(&mut fast, &actions).cloned(),
            ) else {
                panic!("valid actions step");
            };
            assert_eq!(a, b, "step {t}");
            ends += a.final_obs.iter().flatten().count();
        }
        assert!(ends > 10, "the comparison crossed {ends} autoresets");

        let pendulums = (0..3).map(|_| Pendulum::new()).collect();
        let Ok(mut sync) = SyncVectorEnv::new(pendulums, Autoreset::SameStep) else {
            panic!("three environments are a vector");
        };
        let mut fast = PendulumVec::new(PendulumConfig::default(), 3, 0);
        assert_eq!(sync.reset(Some(4)), VectorEnv::reset(&mut fast, Some(4)));
        for t in 0..450 {
            let torques: Vec<f32> = (0..3)
                .map(|i| (t as f32 * 0.1 + i as f32).sin() * 3.0)
                .collect();
            let (Ok(a), Ok(b)) = (
                sync.step(&torques).cloned(),
                VectorEnv::step(&mut fast, &torques).cloned(),
            ) else {
                panic!("torques step");
            };
            assert_eq!(a, b, "step {t}");
        }
    }

    #[test]
    fn next_step_resets_on_the_step_after_the_end() {
        let Ok(mut same) = SyncVectorEnv::new(cartpoles(2), Autoreset::SameStep) else {
            panic!("two environments are a vector");
        };
        let Ok(mut next) = SyncVectorEnv::new(cartpoles(2), Autoreset::NextStep) else {
            panic!("two environments are a vector");
        };
        same.reset(Some(3));
        next.reset(Some(3));
        // Push right until environment 0 falls.
        let mut end = None;
        for t in 0..500 {
            let (Ok(a), Ok(b)) = (same.step(&[1, 1]).cloned(), next.step(&[1, 1]).cloned()) else {
                panic!("valid actions step");
            };
            if let Some(last) = a.final_obs[0] {
                assert_eq!(
                    b.obs[0], last,
                    "next-step returns the real last observation"
                );
                assert!(b.terminated[0] && b.final_obs[0].is_none());
                end = Some((t, a.obs[0], a.final_obs[1].is_some()));
                break;
            }
        }
        let Some((t, first, both)) = end else {
            panic!("pushing right ends an episode");
        };
        let Ok(b) = next.step(&[0, 1]) else {
            panic!("valid actions step");
        };
        assert!(b.reset[0], "step {} resets env 0", t + 1);
        assert_eq!(
            b.reset[1], both,
            "and env 1 only if it ended on the same step"
        );
        assert_eq!(b.obs[0], first, "the same first observation as same-step's");
        assert_eq!(
            (b.rewards[0], b.terminated[0], b.truncated[0]),
            (0.0, false, false)
        );
    }
}
