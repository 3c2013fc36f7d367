//! Rollouts: how an agent's experience is collected between two updates, written once.
//!
//! [`Training`](super::train::Training) drives an agent's [`Rollout`]: it collects a batch,
//! the agent learns from it, and the report counts the environment steps and the episodes
//! that finished in it. Two kinds:
//!
//! - [`OneEpisode`]: the seed's and the book's `while not done` loop, one episode per
//!   update (`rl_utils.train_on_policy_agent`);
//! - [`FixedSteps`]: `T` steps of a [`VectorEnv`] of `N` environments per update, stored
//!   as CleanRL's `ppo.py` stores them ([`StepBuffer`]), episodes running on across
//!   rollouts and bootstrapped at the cut.
//!
//! ```
//! use ppo_rl::env::{Autoreset, CartPole, EnvId, SyncVectorEnv};
//! use ppo_rl::ppo::rollout::{FixedSteps, VecActor};
//!
//! /// Always pushes right, storing nothing.
//! struct Right;
//! impl VecActor<[f32; 4], usize> for Right {
//!     type Extra = ();
//!     fn act_all(&mut self, obs: &[[f32; 4]]) -> Result<Vec<(usize, ())>, ppo_rl::ppo::PpoError> {
//!         Ok(obs.iter().map(|_| (1, ())).collect())
//!     }
//! }
//! let envs = (0..2).map(|_| CartPole::new(EnvId::CartPoleV1)).collect();
//! let mut rollout = FixedSteps::new(SyncVectorEnv::new(envs, Autoreset::SameStep)?, 64, 0)?;
//! let got = rollout.collect(&mut Right)?;
//! assert_eq!(got.steps, 128);
//! assert!(got.episodes.len() >= 2, "pushing right ends an episode in a few dozen steps");
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use std::fmt::Debug;

use serde::Serialize;

use super::PpoError;
use super::on_policy::{Batch, OnPolicyAgent};
use crate::env::{Autoreset, EnvStep, Environment, VectorEnv};

/// An episode that finished inside a rollout.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct FinishedEpisode {
    /// The environment it ran in (0 for a single environment).
    pub env: usize,
    /// Its undiscounted return (the environment's rewards).
    pub episode_return: f64,
    /// Its environment steps.
    pub steps: usize,
    /// It ended in a terminal state.
    pub terminated: bool,
    /// The time limit cut it.
    pub truncated: bool,
    /// Environment steps since training began, this episode's last included: the x-axis
    /// that compares runs with different rollouts.
    pub end_step: u64,
}

/// What one rollout collected.
#[derive(Debug, Clone)]
pub struct Collected<B> {
    /// The batch the agent learns from.
    pub batch: B,
    /// Environment steps in it (next-step reset steps, which are no transitions, excluded).
    pub steps: usize,
    /// The episodes that finished in it, in the order they finished; `end_step` counts from
    /// the start of this rollout (the trainer adds the steps before it).
    pub episodes: Vec<FinishedEpisode>,
}

/// How an agent collects the batch of one update.
pub trait Rollout<A: OnPolicyAgent>: Clone + Debug + Send + 'static {
    /// The rollout of a run of `config`, its environments first reset with `seed`.
    fn start(config: &A::Config, seed: u64) -> Self;

    /// Plays the current policy of `agent` until the batch is full.
    ///
    /// # Errors
    /// [`PpoError::NonFinite`] when the policy's output is not finite, or the environment's
    /// error for an invalid action.
    fn collect(&mut self, agent: &mut A) -> Result<Collected<A::Batch>, PpoError>;
}

/// One episode per update: the seed's `train_on_policy_agent`; the first episode's reset is
/// seeded, the others continue the environment's generator.
#[derive(Debug, Clone)]
pub struct OneEpisode<E> {
    env: E,
    seed: Option<u64>,
}

impl<E: Environment> OneEpisode<E> {
    /// Episodes of `env`, the first reset with `seed`.
    #[must_use]
    pub fn new(env: E, seed: u64) -> Self {
        Self {
            env,
            seed: Some(seed),
        }
    }

    /// The environment.
    #[must_use]
    pub fn env(&self) -> &E {
        &self.env
    }
}

impl<A> Rollout<A> for OneEpisode<A::Env>
where
    A: OnPolicyAgent<Rollout = OneEpisode<<A as OnPolicyAgent>::Env>>,
{
    fn start(config: &A::Config, seed: u64) -> Self {
        Self::new(A::environment(config), seed)
    }

    // ANCHOR: episode_loop
    /// One episode with the current policy: the `while not done` loop of the seed and the book.
    fn collect(&mut self, agent: &mut A) -> Result<Collected<A::Batch>, PpoError> {
        let mut state = self.env.reset(self.seed.take()); // env.reset(seed=seed) once
        let mut transition_dict = A::Batch::default();
        let mut episode_return = 0.0;
        loop {
            let action = agent.act(&state)?; // the seed's agent.take_action(state)
            let step = self.env.step(action)?;
            let done = step.terminated || step.truncated;
            transition_dict.record(
                state,
                action,
                step.reward as f32,
                step.obs,
                done,
                step.terminated,
            );
            state = step.obs;
            episode_return += step.reward;
            if done {
                return Ok(one_episode(transition_dict, episode_return, &step));
            }
        }
    }
    // ANCHOR_END: episode_loop
}

/// The [`Collected`] of one whole episode ending with `last`.
fn one_episode<B: Batch, O>(batch: B, episode_return: f64, last: &EnvStep<O>) -> Collected<B> {
    let steps = batch.steps();
    Collected {
        batch,
        steps,
        episodes: vec![FinishedEpisode {
            env: 0,
            episode_return,
            steps,
            terminated: last.terminated,
            truncated: last.truncated,
            end_step: steps as u64,
        }],
    }
}

/// An actor over a vector of environments: one action per observation, and what it keeps
/// of each step for the update (its log-probability and value, for a PPO).
pub trait VecActor<O, Act> {
    /// What is kept per step besides the action.
    type Extra: Clone + Debug + Send + 'static;

    /// One action (and its extra) per observation, in order.
    ///
    /// # Errors
    /// [`PpoError::NonFinite`] when the policy's output is not finite.
    fn act_all(&mut self, obs: &[O]) -> Result<Vec<(Act, Self::Extra)>, PpoError>;
}

/// `T` steps of `N` environments, step-major as CleanRL's `ppo.py` keeps them: entry
/// `t * N + i` is step `t` of environment `i`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StepBuffer<O, Act, X> {
    /// `N`.
    pub num_envs: usize,
    /// The observation acted on.
    pub obs: Vec<O>,
    /// The action taken.
    pub actions: Vec<Act>,
    /// What the actor kept (log-probability, value).
    pub extra: Vec<X>,
    /// The reward of the step (0 on a reset step).
    pub rewards: Vec<f32>,
    /// CleanRL's `dones[t]`: `obs` is the first observation of an episode because the step
    /// before it ended one (or, under next-step autoreset, was the reset step). False for the
    /// very first observation of a run, as CleanRL's `next_done = zeros`.
    pub starts: Vec<bool>,
    /// The step ended its episode in a terminal state.
    pub terminated: Vec<bool>,
    /// The time limit cut the episode on this step.
    pub truncated: Vec<bool>,
    /// Under next-step autoreset: this step only reset the environment (its action was
    /// ignored, its reward is 0); it is no transition and an update must mask it.
    pub reset: Vec<bool>,
    /// Under same-step autoreset: the real last observation of an episode that ended on this
    /// step (`obs` of the next step is already the next episode's); what a truncated
    /// episode's bootstrap needs.
    pub final_obs: Vec<Option<O>>,
    /// The `N` observations after the last step: `V(next_obs)` bootstraps the cut.
    pub next_obs: Vec<O>,
    /// Whether each of `next_obs` starts an episode (CleanRL's `next_done`).
    pub next_starts: Vec<bool>,
}

impl<O, Act, X> StepBuffer<O, Act, X> {
    /// Entries (`T * N`).
    #[must_use]
    pub fn len(&self) -> usize {
        self.actions.len()
    }

    /// True when no step is stored.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.actions.is_empty()
    }

    /// Steps per environment (`T`).
    #[must_use]
    pub fn steps_per_env(&self) -> usize {
        self.len().checked_div(self.num_envs).unwrap_or(0)
    }
}

/// `T` steps of a vector environment per update; episodes run on across rollouts.
#[derive(Debug, Clone)]
pub struct FixedSteps<V: VectorEnv> {
    envs: V,
    steps: usize,
    seed: Option<u64>,
    obs: Vec<V::Obs>,
    starts: Vec<bool>,
    /// The running return and length of each environment's current episode.
    returns: Vec<f64>,
    lengths: Vec<usize>,
}

impl<V: VectorEnv> FixedSteps<V> {
    /// `steps` steps of each of `envs` per rollout; the first rollout resets them with `seed`.
    ///
    /// # Errors
    /// [`PpoError::InvalidConfig`] naming `steps` when it is 0, or `num_envs` when there
    /// are no environments.
    pub fn new(envs: V, steps: usize, seed: u64) -> Result<Self, PpoError> {
        let refuse = |field, value: usize| PpoError::InvalidConfig {
            field,
            value: value.to_string(),
            expected: "1 or more",
        };
        if steps == 0 {
            return Err(refuse("steps", steps));
        }
        if envs.num_envs() == 0 {
            return Err(refuse("num_envs", 0));
        }
        let n = envs.num_envs();
        Ok(Self {
            envs,
            steps,
            seed: Some(seed),
            obs: Vec::new(),
            starts: vec![false; n],
            returns: vec![0.0; n],
            lengths: vec![0; n],
        })
    }

    /// The vector environment.
    #[must_use]
    pub fn envs(&self) -> &V {
        &self.envs
    }

    /// Plays `T` steps of every environment with `actor`.
    ///
    /// # Errors
    /// An error of `actor`, or the environments' for an invalid action.
    #[allow(clippy::type_complexity)]
    pub fn collect<P: VecActor<V::Obs, V::Action>>(
        &mut self,
        actor: &mut P,
    ) -> Result<Collected<StepBuffer<V::Obs, V::Action, P::Extra>>, PpoError> {
        if let Some(seed) = self.seed.take() {
            self.obs = self.envs.reset(Some(seed)).to_vec();
        }
        let n = self.envs.num_envs();
        let capacity = n * self.steps;
        let mut buf = StepBuffer {
            num_envs: n,
            obs: Vec::with_capacity(capacity),
            actions: Vec::with_capacity(capacity),
            extra: Vec::with_capacity(capacity),
            rewards: Vec::with_capacity(capacity),
            starts: Vec::with_capacity(capacity),
            terminated: Vec::with_capacity(capacity),
            truncated: Vec::with_capacity(capacity),
            reset: Vec::with_capacity(capacity),
            final_obs: Vec::with_capacity(capacity),
            next_obs: Vec::new(),
            next_starts: Vec::new(),
        };
        let mut episodes = Vec::new();
        let mut steps = 0usize;
        for _ in 0..self.steps {
            let acted = actor.act_all(&self.obs)?;
            if acted.len() != n {
                let got = acted.len();
                return Err(PpoError::InvalidBatch(crate::tr!(
                    "the actor gave {got} actions for {n} environments: one per observation",
                    "策略网络给出了 {got} 个动作，而环境有 {n} 个：每个观测对应一个动作"
                )));
            }
            let actions: Vec<V::Action> = acted.iter().map(|(a, _)| *a).collect();
            let autoreset = self.envs.autoreset();
            let out = self.envs.step(&actions)?;
            for (i, (action, extra)) in acted.into_iter().enumerate() {
                let reset = out.reset.get(i).copied().unwrap_or(false);
                let (terminated, truncated) = (out.terminated[i], out.truncated[i]);
                buf.obs.push(self.obs[i]);
                buf.actions.push(action);
                buf.extra.push(extra);
                buf.rewards.push(out.rewards[i] as f32);
                buf.starts.push(self.starts[i]);
                buf.terminated.push(terminated);
                buf.truncated.push(truncated);
                buf.reset.push(reset);
                buf.final_obs.push(out.final_obs[i]);
                let ended = terminated || truncated;
                if !reset {
                    steps += 1;
                    self.returns[i] += out.rewards[i];
                    self.lengths[i] += 1;
                }
                if ended {
                    episodes.push(FinishedEpisode {
                        env: i,
                        episode_return: std::mem::take(&mut self.returns[i]),
                        steps: std::mem::take(&mut self.lengths[i]),
                        terminated,
                        truncated,
                        end_step: steps as u64,
                    });
                }
                self.starts[i] = match autoreset {
                    Autoreset::SameStep => ended,
                    Autoreset::NextStep => reset,
                };
            }
            self.obs.clone_from(&out.obs);
        }
        buf.next_obs.clone_from(&self.obs);
        buf.next_starts.clone_from(&self.starts);
        Ok(Collected {
            batch: buf,
            steps,
            episodes,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::env::{CartPole, EnvId, SyncVectorEnv};

    /// A fixed action pattern, counting its calls.
    struct Pattern(usize);

    impl VecActor<[f32; 4], usize> for Pattern {
        type Extra = usize;

        fn act_all(&mut self, obs: &[[f32; 4]]) -> Result<Vec<(usize, usize)>, PpoError> {
            self.0 += 1;
            Ok((0..obs.len())
                .map(|i| ((self.0 + i) / 3 % 2, self.0))
                .collect())
        }
    }

    fn cartpoles(n: usize, autoreset: Autoreset) -> SyncVectorEnv<CartPole> {
        let envs = (0..n).map(|_| CartPole::new(EnvId::CartPoleV1)).collect();
        match SyncVectorEnv::new(envs, autoreset) {
            Ok(v) => v,
            Err(e) => panic!("{e}"),
        }
    }

    #[test]
    fn empty_rollouts_are_refused() {
        let envs = cartpoles(2, Autoreset::SameStep);
        assert!(matches!(
            FixedSteps::new(envs, 0, 0),
            Err(PpoError::InvalidConfig { field: "steps", .. })
        ));
    }

    #[test]
    fn layout_is_step_major_and_episodes_run_across_rollouts() -> Result<(), PpoError> {
        let mut rollout = FixedSteps::new(cartpoles(3, Autoreset::SameStep), 40, 5)?;
        let mut actor = Pattern(0);
        let mut total = Vec::new();
        let mut lengths = [0usize; 3];
        let mut previous_next_obs: Option<Vec<[f32; 4]>> = None;
        for _ in 0..10 {
            let got = rollout.collect(&mut actor)?;
            let b = &got.batch;
            assert_eq!((b.len(), b.steps_per_env(), got.steps), (120, 40, 120));
            // Entry t * N + i was acted on in call t of this rollout.
            assert!(b.extra.chunks(3).all(|c| c.iter().all(|&x| x == c[0])));
            // The first observations of a rollout are the last rollout's next_obs.
            if let Some(prev) = previous_next_obs {
                assert_eq!(&b.obs[..3], &prev[..]);
            }
            previous_next_obs = Some(b.next_obs.clone());
            // starts[t] says the step before ended an episode.
            for t in 1..40 {
                for i in 0..3 {
                    let before = (t - 1) * 3 + i;
                    let ended = b.terminated[before] || b.truncated[before];
                    assert_eq!(b.starts[t * 3 + i], ended);
                    assert_eq!(b.final_obs[before].is_some(), ended);
                }
            }
            for t in 0..40 {
                for (i, length) in lengths.iter_mut().enumerate() {
                    *length += 1;
                    if b.terminated[t * 3 + i] || b.truncated[t * 3 + i] {
                        total.push((i, std::mem::take(length)));
                    }
                }
            }
            for e in &got.episodes {
                assert!(e.end_step <= 120);
            }
            let counted: Vec<(usize, usize)> =
                got.episodes.iter().map(|e| (e.env, e.steps)).collect();
            assert!(counted.iter().all(|c| total.contains(c)));
        }
        assert!(total.len() > 10, "{} episodes ended", total.len());
        assert!(
            total.iter().any(|&(_, len)| len > 40),
            "some episode ran across a rollout's end"
        );
        Ok(())
    }

    #[test]
    fn next_step_reset_steps_are_marked_and_not_counted() -> Result<(), PpoError> {
        let mut same = FixedSteps::new(cartpoles(2, Autoreset::SameStep), 300, 1)?;
        let mut next = FixedSteps::new(cartpoles(2, Autoreset::NextStep), 300, 1)?;
        // Always right: episodes end early, then the two modes' step counts part.
        struct Right;
        impl VecActor<[f32; 4], usize> for Right {
            type Extra = ();
            fn act_all(&mut self, obs: &[[f32; 4]]) -> Result<Vec<(usize, ())>, PpoError> {
                Ok(obs.iter().map(|_| (1, ())).collect())
            }
        }
        let a = same.collect(&mut Right)?;
        let b = next.collect(&mut Right)?;
        let resets = b.batch.reset.iter().filter(|&&r| r).count();
        assert!(resets > 0);
        assert!(a.batch.reset.iter().all(|&r| !r));
        assert_eq!(b.steps, 600 - resets);
        assert!(b.batch.final_obs.iter().all(Option::is_none));
        for (k, &r) in b.batch.reset.iter().enumerate() {
            if r {
                assert_eq!(b.batch.rewards[k], 0.0);
                // The step before, in the same environment, ended an episode.
                let before = k - 2;
                assert!(b.batch.terminated[before] || b.batch.truncated[before]);
                if k + 2 < b.batch.len() {
                    assert!(
                        b.batch.starts[k + 2],
                        "the observation after a reset starts"
                    );
                }
            }
        }
        // The same episodes finish in both modes, with the same returns: the first ones,
        // before next-step's reset steps shift the two apart in time.
        let first = |c: &Collected<StepBuffer<[f32; 4], usize, ()>>, env| {
            c.episodes
                .iter()
                .find(|e| e.env == env)
                .map(|e| (e.steps, e.episode_return))
        };
        assert_eq!(first(&a, 0), first(&b, 0));
        assert_eq!(first(&a, 1), first(&b, 1));
        Ok(())
    }
}
