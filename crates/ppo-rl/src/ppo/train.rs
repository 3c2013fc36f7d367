//! The seed's `rl_utils.train_on_policy_agent`, one episode at a time.
//!
//! ```text
//! for each episode:
//!     play until done, storing (s, a, r, s', done) in a transition_dict
//!     agent.update(transition_dict)                 one update per episode
//! ```
//!
//! The seed splits `num_episodes` into 10 tqdm bars ("Iteration 0" .. "Iteration 9") of
//! `num_episodes / 10` episodes; [`EpisodeReport`] carries the same bookkeeping so a face
//! can draw those bars. (Where `num_episodes` is not a multiple of 10 the seed silently drops
//! the remainder; here the first iterations take one episode more instead.)
//!
//! [`Training`] is written once for every agent ([`OnPolicyAgent`]): [`Trainer`] is the
//! seed's PPO (or REINFORCE) on CartPole, [`ContinuousTrainer`] the book's
//! `PPOContinuous` on Pendulum. It is `Send`: a face runs it on a worker thread and forwards
//! each report.
//!
//! ```
//! use ppo_rl::ppo::{PpoConfig, Trainer};
//!
//! let config = PpoConfig { num_episodes: 3, ..PpoConfig::default() };
//! let mut trainer = Trainer::new(config, 0)?;
//! while let Some(report) = trainer.next_episode()? {
//!     assert_eq!(report.trace.len(), report.steps);
//! }
//! assert_eq!(trainer.returns().len(), 3);
//! # Ok::<(), ppo_rl::ppo::PpoError>(())
//! ```

use std::ops::ControlFlow;
use std::time::{Duration, Instant};

use serde::Serialize;

use super::PpoError;
use super::agent::{Agent, Losses};
use super::continuous::PpoContinuous;
use super::on_policy::{AgentConfig, Batch, Environment, OnPolicyAgent};
use super::trace::UpdateTrace;

/// The seed's number of progress bars.
pub const ITERATIONS: usize = 10;

/// What one training episode produced; `T` is the agent's update trace.
#[derive(Debug, Clone, Serialize)]
pub struct EpisodeReport<T = UpdateTrace> {
    /// The episode, from 0.
    pub episode: usize,
    /// Its progress bar, 0 to 9 ("Iteration i").
    pub iteration: usize,
    /// Its position within that bar, from 0.
    pub episode_in_iteration: usize,
    /// How many episodes that bar holds.
    pub iteration_len: usize,
    /// The undiscounted return, the seed's `episode_return` (the environment's rewards,
    /// before any rescaling inside the update).
    pub episode_return: f64,
    /// Environment steps in the episode.
    pub steps: usize,
    /// Environment steps since training began.
    pub total_steps: u64,
    /// Gymnasium's `terminated` for each step, as the environment reported it.
    pub terminated: Vec<bool>,
    /// Gymnasium's `truncated` for each step: the time limit, reached on the last step or never.
    pub truncated: Vec<bool>,
    /// The update on this episode, every intermediate.
    pub trace: T,
}

/// Training so far, and the final result.
#[derive(Debug, Clone, Serialize)]
pub struct TrainSummary {
    /// One return per episode.
    pub returns: Vec<f64>,
    /// Environment steps over all episodes.
    pub env_steps: u64,
    /// Wall-clock time spent in [`Training::next_episode`].
    pub wall_s: f64,
}

impl TrainSummary {
    /// The mean of the last `k` returns (all of them if fewer).
    #[must_use]
    pub fn mean_last(&self, k: usize) -> f64 {
        mean_last(&self.returns, k)
    }

    /// Environment steps per second of wall time.
    #[must_use]
    pub fn steps_per_s(&self) -> f64 {
        if self.wall_s > 0.0 {
            self.env_steps as f64 / self.wall_s
        } else {
            0.0
        }
    }
}

/// The mean of the last `k` values (all of them if fewer; 0 for none).
#[must_use]
pub fn mean_last(values: &[f64], k: usize) -> f64 {
    let tail = &values[values.len().saturating_sub(k)..];
    if tail.is_empty() {
        0.0
    } else {
        tail.iter().sum::<f64>() / tail.len() as f64
    }
}

/// Which bar episode `episode` of `num_episodes` belongs to: `(iteration, index within it,
/// bar length)`. The seed's ten bars; where `num_episodes` is not a multiple of 10 the
/// first bars take one episode more.
#[must_use]
pub fn iteration_of(num_episodes: usize, episode: usize) -> (usize, usize, usize) {
    let bars = ITERATIONS.min(num_episodes).max(1);
    let (base, extra) = (num_episodes / bars, num_episodes % bars);
    let mut start = 0;
    for i in 0..bars {
        let len = base + usize::from(i < extra);
        if episode < start + len {
            return (i, episode - start, len);
        }
        start += len;
    }
    (bars - 1, episode.saturating_sub(start), base)
}

/// The training loop of any agent as a state machine: call [`Training::next_episode`]
/// until it gives `None`.
#[derive(Debug, Clone)]
pub struct Training<A: OnPolicyAgent> {
    config: A::Config,
    seed: u64,
    agent: A,
    env: A::Env,
    returns: Vec<f64>,
    env_steps: u64,
    elapsed: Duration,
}

/// The seed's PPO (or REINFORCE) on CartPole, one episode at a time.
pub type Trainer = Training<Agent>;
/// The book's `PPOContinuous` on Pendulum-v1, one episode at a time.
pub type ContinuousTrainer = Training<PpoContinuous>;

impl<A: OnPolicyAgent> Training<A> {
    /// A fresh agent (initialised from `seed`) and environment (first reset with `seed`,
    /// as the seed's `env.reset(seed=0)`).
    ///
    /// # Errors
    /// [`PpoError::InvalidConfig`] for a hyper-parameter out of range.
    pub fn new(config: A::Config, seed: u64) -> Result<Self, PpoError> {
        let agent = A::create(&config, seed)?;
        let env = A::environment(&config);
        Ok(Self {
            config,
            seed,
            agent,
            env,
            returns: Vec::new(),
            env_steps: 0,
            elapsed: Duration::ZERO,
        })
    }

    /// The hyper-parameters.
    #[must_use]
    pub fn config(&self) -> &A::Config {
        &self.config
    }

    /// The agent as trained so far.
    #[must_use]
    pub fn agent(&self) -> &A {
        &self.agent
    }

    /// The agent, ending the run.
    #[must_use]
    pub fn into_agent(self) -> A {
        self.agent
    }

    /// The returns of the episodes played so far.
    #[must_use]
    pub fn returns(&self) -> &[f64] {
        &self.returns
    }

    /// Whether every episode has been played.
    #[must_use]
    pub fn is_done(&self) -> bool {
        self.returns.len() >= self.config.num_episodes()
    }

    /// The result so far.
    #[must_use]
    pub fn summary(&self) -> TrainSummary {
        TrainSummary {
            returns: self.returns.clone(),
            env_steps: self.env_steps,
            wall_s: self.elapsed.as_secs_f64(),
        }
    }

    /// Which bar episode `episode` belongs to: `(iteration, index within it, bar length)`.
    #[must_use]
    pub fn iteration_of(&self, episode: usize) -> (usize, usize, usize) {
        iteration_of(self.config.num_episodes(), episode)
    }

    /// Plays one episode and updates the agent on it; `None` once all episodes are done.
    ///
    /// # Errors
    /// [`PpoError::Diverged`] naming the episode when an action, target or loss turns NaN
    /// or infinite.
    pub fn next_episode(&mut self) -> Result<Option<EpisodeReport<A::Trace>>, PpoError> {
        self.episode(A::learn)
    }

    /// [`Training::next_episode`] with the update done by `update` (the agent's own
    /// [`OnPolicyAgent::learn`], or one with a learner's losses).
    ///
    /// # Errors
    /// As [`Training::next_episode`], plus an error `update` returned.
    pub fn episode(
        &mut self,
        update: impl FnOnce(&mut A, &A::Batch) -> Result<A::Trace, PpoError>,
    ) -> Result<Option<EpisodeReport<A::Trace>>, PpoError> {
        if self.is_done() {
            return Ok(None);
        }
        let started = Instant::now();
        let episode = self.returns.len();
        let diverged = |e: PpoError| match e {
            PpoError::NonFinite(what) => PpoError::Diverged { episode, what },
            other => other,
        };
        let (transitions, episode_return) = self.play_episode(episode).map_err(diverged)?;
        let trace = update(&mut self.agent, &transitions).map_err(diverged)?;
        let steps = transitions.steps();
        self.returns.push(episode_return);
        self.env_steps += steps as u64;
        self.elapsed += started.elapsed();
        let (iteration, episode_in_iteration, iteration_len) = self.iteration_of(episode);
        let limit = self.env.time_limit();
        Ok(Some(EpisodeReport {
            episode,
            iteration,
            episode_in_iteration,
            iteration_len,
            episode_return,
            steps,
            total_steps: self.env_steps,
            terminated: transitions.terminated(),
            truncated: (1..=steps).map(|t| t >= limit).collect(),
            trace,
        }))
    }

    // ANCHOR: episode_loop
    /// One episode with the current policy: the `while not done` loop of the seed and the book.
    fn play_episode(&mut self, episode: usize) -> Result<(A::Batch, f64), PpoError> {
        let seed = (episode == 0).then_some(self.seed); // env.reset(seed=seed) only once
        let mut state = self.env.reset(seed);
        let mut transition_dict = A::Batch::default();
        let mut episode_return = 0.0;
        loop {
            let action = self.agent.act(&state)?; // the seed's agent.take_action(state)
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
                return Ok((transition_dict, episode_return));
            }
        }
    }
    // ANCHOR_END: episode_loop
}

impl Training<Agent> {
    /// [`Training::next_episode`] with the update's losses computed by `losses` (see
    /// [`Agent::update_with`]).
    ///
    /// # Errors
    /// As [`Training::next_episode`], plus an error `losses` returned.
    pub fn next_episode_with(
        &mut self,
        losses: &Losses<'_>,
    ) -> Result<Option<EpisodeReport>, PpoError> {
        self.episode(|agent, batch| agent.update_with(batch, losses))
    }
}

impl<A: OnPolicyAgent> Iterator for Training<A> {
    type Item = Result<EpisodeReport<A::Trace>, PpoError>;

    fn next(&mut self) -> Option<Self::Item> {
        self.next_episode().transpose()
    }
}

/// Trains the agent `config` configures for `config.num_episodes`, calling `on_episode`
/// after each; it may stop early by returning [`ControlFlow::Break`].
///
/// # Errors
/// [`PpoError::InvalidConfig`] before training; [`PpoError::Diverged`] during it.
#[allow(clippy::type_complexity)]
pub fn train<C: AgentConfig>(
    config: C,
    seed: u64,
    mut on_episode: impl FnMut(&EpisodeReport<<C::Agent as OnPolicyAgent>::Trace>) -> ControlFlow<()>,
) -> Result<(TrainSummary, C::Agent), PpoError> {
    let mut trainer = Training::<C::Agent>::new(config, seed)?;
    while let Some(report) = trainer.next_episode()? {
        if on_episode(&report).is_break() {
            break;
        }
    }
    Ok((trainer.summary(), trainer.agent))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ppo::PpoConfig;

    #[test]
    fn trainer_is_send() {
        fn assert_send<T: Send + 'static>() {}
        assert_send::<Trainer>();
        assert_send::<EpisodeReport>();
    }

    #[test]
    fn iterations_split_like_the_seed() -> Result<(), PpoError> {
        let t = Trainer::new(PpoConfig::default(), 0)?;
        assert_eq!(t.iteration_of(0), (0, 0, 50));
        assert_eq!(t.iteration_of(49), (0, 49, 50));
        assert_eq!(t.iteration_of(50), (1, 0, 50));
        assert_eq!(t.iteration_of(499), (9, 49, 50));
        let t = Trainer::new(
            PpoConfig {
                num_episodes: 3,
                ..PpoConfig::default()
            },
            0,
        )?;
        assert_eq!(t.iteration_of(2), (2, 0, 1));
        let t = Trainer::new(
            PpoConfig {
                num_episodes: 12,
                ..PpoConfig::default()
            },
            0,
        )?;
        assert_eq!(t.iteration_of(1), (0, 1, 2));
        assert_eq!(t.iteration_of(2), (1, 0, 2));
        assert_eq!(t.iteration_of(11), (9, 0, 1));
        Ok(())
    }

    #[test]
    fn same_seed_same_run() -> Result<(), PpoError> {
        let config = PpoConfig {
            num_episodes: 5,
            ..PpoConfig::default()
        };
        let (a, _) = train(config.clone(), 7, |_| ControlFlow::Continue(()))?;
        let (b, _) = train(config, 7, |_| ControlFlow::Continue(()))?;
        assert_eq!(a.returns, b.returns);
        Ok(())
    }

    #[test]
    fn divergence_names_the_episode() -> Result<(), PpoError> {
        let config = PpoConfig {
            actor_lr: 1e30,
            critic_lr: 1e30,
            num_episodes: 50,
            ..PpoConfig::default()
        };
        let err = train(config, 0, |_| ControlFlow::Continue(())).err();
        match err {
            Some(PpoError::Diverged { episode, what }) => {
                assert!(episode < 50, "{episode} {what}");
            }
            other => panic!("expected divergence, got {other:?}"),
        }
        Ok(())
    }
}
