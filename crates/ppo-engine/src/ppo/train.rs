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
//! [`Trainer`] is `Send`: a face runs it on a worker thread and forwards each report.
//!
//! ```
//! use ppo_engine::ppo::{PpoConfig, Trainer};
//!
//! let config = PpoConfig { num_episodes: 3, ..PpoConfig::default() };
//! let mut trainer = Trainer::new(config, 0)?;
//! while let Some(report) = trainer.next_episode()? {
//!     assert_eq!(report.trace.len(), report.steps);
//! }
//! assert_eq!(trainer.returns().len(), 3);
//! # Ok::<(), ppo_engine::ppo::PpoError>(())
//! ```

use std::ops::ControlFlow;
use std::time::{Duration, Instant};

use serde::Serialize;

use super::agent::{Agent, Losses, Transitions};
use super::trace::UpdateTrace;
use super::{PpoConfig, PpoError};
use crate::env::CartPole;

/// The seed's number of progress bars.
pub const ITERATIONS: usize = 10;

/// What one training episode produced.
#[derive(Debug, Clone, Serialize)]
pub struct EpisodeReport {
    /// The episode, from 0.
    pub episode: usize,
    /// Its progress bar, 0 to 9 ("Iteration i").
    pub iteration: usize,
    /// Its position within that bar, from 0.
    pub episode_in_iteration: usize,
    /// How many episodes that bar holds.
    pub iteration_len: usize,
    /// The undiscounted return, the seed's `episode_return`.
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
    pub trace: UpdateTrace,
}

/// Training so far, and the final result.
#[derive(Debug, Clone, Serialize)]
pub struct TrainSummary {
    /// One return per episode.
    pub returns: Vec<f64>,
    /// Environment steps over all episodes.
    pub env_steps: u64,
    /// Wall-clock time spent in [`Trainer::next_episode`].
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

/// The training loop as a state machine: call [`Trainer::next_episode`] until it gives `None`.
#[derive(Debug, Clone)]
pub struct Trainer {
    config: PpoConfig,
    seed: u64,
    agent: Agent,
    env: CartPole,
    returns: Vec<f64>,
    env_steps: u64,
    elapsed: Duration,
}

impl Trainer {
    /// A fresh agent (initialised from `seed`) and environment (first reset with `seed`,
    /// as the seed's `env.reset(seed=0)`).
    ///
    /// # Errors
    /// [`PpoError::InvalidConfig`] for a hyper-parameter out of range.
    pub fn new(config: PpoConfig, seed: u64) -> Result<Self, PpoError> {
        let agent = Agent::new(&config, seed)?;
        let env = CartPole::new(config.env_id);
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
    pub fn config(&self) -> &PpoConfig {
        &self.config
    }

    /// The agent as trained so far.
    #[must_use]
    pub fn agent(&self) -> &Agent {
        &self.agent
    }

    /// The returns of the episodes played so far.
    #[must_use]
    pub fn returns(&self) -> &[f64] {
        &self.returns
    }

    /// Whether every episode has been played.
    #[must_use]
    pub fn is_done(&self) -> bool {
        self.returns.len() >= self.config.num_episodes
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
        let n = self.config.num_episodes;
        let bars = ITERATIONS.min(n).max(1);
        let (base, extra) = (n / bars, n % bars);
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

    /// Plays one episode and updates the agent on it; `None` once all episodes are done.
    ///
    /// # Errors
    /// [`PpoError::Diverged`] naming the episode when an action probability, target or
    /// loss turns NaN or infinite.
    pub fn next_episode(&mut self) -> Result<Option<EpisodeReport>, PpoError> {
        self.episode(None)
    }

    /// [`Trainer::next_episode`] with the update's losses computed by `losses` (see
    /// [`Agent::update_with`]).
    ///
    /// # Errors
    /// As [`Trainer::next_episode`], plus an error `losses` returned.
    pub fn next_episode_with(
        &mut self,
        losses: &Losses<'_>,
    ) -> Result<Option<EpisodeReport>, PpoError> {
        self.episode(Some(losses))
    }

    fn episode(&mut self, losses: Option<&Losses<'_>>) -> Result<Option<EpisodeReport>, PpoError> {
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
        let trace = match losses {
            None => self.agent.update(&transitions),
            Some(losses) => self.agent.update_with(&transitions, losses),
        }
        .map_err(diverged)?;
        let steps = transitions.len();
        self.returns.push(episode_return);
        self.env_steps += steps as u64;
        self.elapsed += started.elapsed();
        let (iteration, episode_in_iteration, iteration_len) = self.iteration_of(episode);
        let limit = self.config.env_id.max_episode_steps() as usize;
        Ok(Some(EpisodeReport {
            episode,
            iteration,
            episode_in_iteration,
            iteration_len,
            episode_return,
            steps,
            total_steps: self.env_steps,
            terminated: transitions.terminated,
            truncated: (1..=steps).map(|t| t >= limit).collect(),
            trace,
        }))
    }

    // ANCHOR: episode_loop
    /// One episode with the current policy: the seed's `while not done` loop.
    fn play_episode(&mut self, episode: usize) -> Result<(Transitions, f64), PpoError> {
        let seed = (episode == 0).then_some(self.seed); // env.reset(seed=seed) only once
        let mut state = self.env.reset(seed);
        let mut transition_dict = Transitions::default();
        let mut episode_return = 0.0;
        loop {
            let action = self.agent.take_action(&state)?;
            let step = self.env.step(action)?;
            let done = step.terminated || step.truncated;
            transition_dict.push(
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

impl Iterator for Trainer {
    type Item = Result<EpisodeReport, PpoError>;

    fn next(&mut self) -> Option<Self::Item> {
        self.next_episode().transpose()
    }
}

/// Trains for `config.num_episodes`, calling `on_episode` after each; it may stop early by
/// returning [`ControlFlow::Break`].
///
/// # Errors
/// [`PpoError::InvalidConfig`] before training; [`PpoError::Diverged`] during it.
pub fn train(
    config: PpoConfig,
    seed: u64,
    mut on_episode: impl FnMut(&EpisodeReport) -> ControlFlow<()>,
) -> Result<(TrainSummary, Agent), PpoError> {
    let mut trainer = Trainer::new(config, seed)?;
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
