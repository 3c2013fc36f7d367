//! The book's training loop for `PPOContinuous` on Pendulum-v1, one episode at a time.
//!
//! ```text
//! for each episode:
//!     state = env.reset(seed) on the first episode, env.reset() after
//!     until terminated or truncated (Pendulum: truncated after 200 steps):
//!         a ~ Normal(μ(s), σ(s))             sent unclipped: the environment clips it
//!         store (s, a, r, s', done)
//!     agent.update(transition_dict)          one update per episode
//! ```
//!
//! It is the discrete [`Trainer`](crate::ppo::Trainer)'s loop with a torque for an action:
//! [`ContinuousTrainer`] has the same methods, reports the same bookkeeping (the ten
//! "Iteration i" bars) with the continuous update's trace, and sums up a run as the same
//! [`TrainSummary`].
//!
//! ```
//! use ppo_engine::ppo::{ContinuousTrainer, PpoContinuousConfig};
//!
//! let config = PpoContinuousConfig { num_episodes: 2, ..PpoContinuousConfig::default() };
//! let mut trainer = ContinuousTrainer::new(config, 0)?;
//! while let Some(report) = trainer.next_episode()? {
//!     assert_eq!(report.steps, 200); // Pendulum-v1 never terminates: the time limit ends it
//!     assert!(report.episode_return <= 0.0);
//! }
//! assert_eq!(trainer.returns().len(), 2);
//! # Ok::<(), ppo_engine::ppo::PpoError>(())
//! ```

use std::ops::ControlFlow;
use std::time::{Duration, Instant};

use serde::Serialize;

use super::agent::{ContinuousTransitions, PpoContinuous};
use super::config::PpoContinuousConfig;
use super::trace::ContinuousUpdateTrace;
use crate::env::Pendulum;
use crate::ppo::PpoError;
use crate::ppo::train::{ITERATIONS, TrainSummary};

/// What one training episode on Pendulum produced.
#[derive(Debug, Clone, Serialize)]
pub struct ContinuousEpisodeReport {
    /// The episode, from 0.
    pub episode: usize,
    /// Its progress bar, 0 to 9 ("Iteration i").
    pub iteration: usize,
    /// Its position within that bar, from 0.
    pub episode_in_iteration: usize,
    /// How many episodes that bar holds.
    pub iteration_len: usize,
    /// The undiscounted return (the environment's rewards, before the update's rescaling).
    pub episode_return: f64,
    /// Environment steps in the episode (200 for Pendulum-v1).
    pub steps: usize,
    /// Environment steps since training began.
    pub total_steps: u64,
    /// The update on this episode, every intermediate.
    pub trace: ContinuousUpdateTrace,
}

/// Which bar episode `episode` of `num_episodes` belongs to: `(iteration, index within it,
/// bar length)`. The seed's ten bars; where `num_episodes` is not a multiple of 10 the
/// first bars take one episode more (the same split as [`Trainer`](crate::ppo::Trainer)).
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

/// The book's training loop as a state machine: call [`ContinuousTrainer::next_episode`]
/// until it gives `None`.
#[derive(Debug, Clone)]
pub struct ContinuousTrainer {
    config: PpoContinuousConfig,
    seed: u64,
    agent: PpoContinuous,
    env: Pendulum,
    returns: Vec<f64>,
    env_steps: u64,
    elapsed: Duration,
}

impl ContinuousTrainer {
    /// A fresh agent (initialised from `seed`) and Pendulum-v1 (first reset with `seed`, as
    /// the book's `env.reset(seed=seed)`).
    ///
    /// # Errors
    /// [`PpoError::InvalidConfig`] for a hyper-parameter out of range.
    pub fn new(config: PpoContinuousConfig, seed: u64) -> Result<Self, PpoError> {
        let agent = PpoContinuous::new(&config, seed)?;
        Ok(Self {
            config,
            seed,
            agent,
            env: Pendulum::new(),
            returns: Vec::new(),
            env_steps: 0,
            elapsed: Duration::ZERO,
        })
    }

    /// The hyper-parameters.
    #[must_use]
    pub fn config(&self) -> &PpoContinuousConfig {
        &self.config
    }

    /// The agent as trained so far.
    #[must_use]
    pub fn agent(&self) -> &PpoContinuous {
        &self.agent
    }

    /// The trained agent, giving the trainer up.
    #[must_use]
    pub fn into_agent(self) -> PpoContinuous {
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

    /// Plays one episode and updates the agent on it; `None` once all episodes are done.
    ///
    /// # Errors
    /// [`PpoError::Diverged`] naming the episode when μ, σ, a target or a loss turns NaN or
    /// infinite.
    pub fn next_episode(&mut self) -> Result<Option<ContinuousEpisodeReport>, PpoError> {
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
        let trace = self.agent.update(&transitions).map_err(diverged)?;
        let steps = transitions.len();
        self.returns.push(episode_return);
        self.env_steps += steps as u64;
        self.elapsed += started.elapsed();
        let (iteration, episode_in_iteration, iteration_len) =
            iteration_of(self.config.num_episodes, episode);
        Ok(Some(ContinuousEpisodeReport {
            episode,
            iteration,
            episode_in_iteration,
            iteration_len,
            episode_return,
            steps,
            total_steps: self.env_steps,
            trace,
        }))
    }

    // ANCHOR: episode_loop_continuous
    /// One episode with the current policy: the book's `while not done` loop.
    fn play_episode(&mut self, episode: usize) -> Result<(ContinuousTransitions, f64), PpoError> {
        let seed = (episode == 0).then_some(self.seed); // env.reset(seed=seed) only once
        let mut state = self.env.reset(seed);
        let mut transition_dict = ContinuousTransitions::default();
        let mut episode_return = 0.0;
        loop {
            let action = self.agent.take_action(&state)?;
            let step = self.env.step(f64::from(action))?; // unclipped: the env clips it
            let done = step.terminated || step.truncated;
            transition_dict.push(state, action, step.reward as f32, step.obs, done);
            state = step.obs;
            episode_return += step.reward;
            if done {
                return Ok((transition_dict, episode_return));
            }
        }
    }
    // ANCHOR_END: episode_loop_continuous
}

impl Iterator for ContinuousTrainer {
    type Item = Result<ContinuousEpisodeReport, PpoError>;

    fn next(&mut self) -> Option<Self::Item> {
        self.next_episode().transpose()
    }
}

/// Trains `PPOContinuous` on Pendulum-v1 for `config.num_episodes`, calling `on_episode`
/// after each; it may stop early by returning [`ControlFlow::Break`].
///
/// # Errors
/// [`PpoError::InvalidConfig`] before training; [`PpoError::Diverged`] during it.
pub fn train_continuous(
    config: PpoContinuousConfig,
    seed: u64,
    mut on_episode: impl FnMut(&ContinuousEpisodeReport) -> ControlFlow<()>,
) -> Result<(TrainSummary, PpoContinuous), PpoError> {
    let mut trainer = ContinuousTrainer::new(config, seed)?;
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
    use crate::ppo::Trainer;
    use crate::ppo::config::PpoConfig;

    fn short(num_episodes: usize) -> PpoContinuousConfig {
        PpoContinuousConfig {
            num_episodes,
            ..PpoContinuousConfig::default()
        }
    }

    #[test]
    fn trainer_is_send() {
        fn assert_send<T: Send + 'static>() {}
        assert_send::<ContinuousTrainer>();
        assert_send::<ContinuousEpisodeReport>();
    }

    /// The same split as the discrete trainer's, for a few lengths.
    #[test]
    fn iterations_split_like_the_discrete_trainer() -> Result<(), PpoError> {
        for n in [1, 3, 12, 500, 2000] {
            let discrete = Trainer::new(
                PpoConfig {
                    num_episodes: n,
                    ..PpoConfig::default()
                },
                0,
            )?;
            for episode in 0..n {
                assert_eq!(
                    iteration_of(n, episode),
                    discrete.iteration_of(episode),
                    "{episode} of {n}"
                );
            }
        }
        assert_eq!(iteration_of(2000, 1999), (9, 199, 200));
        Ok(())
    }

    /// The first episode starts from `reset(seed)`, later ones from unseeded resets; every
    /// episode is 200 steps whose last one alone is `done`; the return is the sum of the
    /// environment's rewards, each in Pendulum's range.
    #[test]
    fn episodes_follow_the_books_loop() -> Result<(), PpoError> {
        let mut trainer = ContinuousTrainer::new(short(3), 4)?;
        let mut env = Pendulum::new();
        let first = env.reset(Some(4));
        let reports: Vec<_> = trainer.by_ref().collect::<Result<_, _>>()?;
        assert_eq!(reports.len(), 3);
        assert_eq!(reports[0].trace.states[0], first);
        let second = env.reset(None);
        assert_eq!(
            reports[1].trace.states[0], second,
            "unseeded: the same generator"
        );
        for (i, r) in reports.iter().enumerate() {
            assert_eq!(
                (r.episode, r.steps, r.total_steps),
                (i, 200, 200 * (i as u64 + 1))
            );
            let dones = &r.trace.dones;
            assert!(dones[199] && dones[..199].iter().all(|d| !d));
            let sum: f64 = r.trace.rewards.iter().map(|&x| f64::from(x)).sum();
            assert!(
                (sum - r.episode_return).abs() < 1e-3,
                "{sum} {}",
                r.episode_return
            );
            assert!(r.trace.rewards.iter().all(|&x| (-16.3..=0.0).contains(&x)));
        }
        assert_eq!(trainer.summary().env_steps, 600);
        assert!(trainer.next_episode()?.is_none());
        Ok(())
    }

    #[test]
    fn same_seed_same_run() -> Result<(), PpoError> {
        let (a, agent_a) = train_continuous(short(3), 7, |_| ControlFlow::Continue(()))?;
        let (b, agent_b) = train_continuous(short(3), 7, |_| ControlFlow::Continue(()))?;
        assert_eq!(a.returns, b.returns);
        assert_eq!(agent_a.weights()?, agent_b.weights()?);
        let (c, _) = train_continuous(short(3), 8, |_| ControlFlow::Continue(()))?;
        assert_ne!(a.returns, c.returns);
        Ok(())
    }

    #[test]
    fn a_break_stops_training() -> Result<(), PpoError> {
        let (summary, _) = train_continuous(short(5), 0, |r| {
            if r.episode == 1 {
                ControlFlow::Break(())
            } else {
                ControlFlow::Continue(())
            }
        })?;
        assert_eq!(summary.returns.len(), 2);
        Ok(())
    }

    #[test]
    fn divergence_names_the_episode() {
        let config = PpoContinuousConfig {
            actor_lr: 1e30,
            critic_lr: 1e30,
            ..short(20)
        };
        match train_continuous(config, 0, |_| ControlFlow::Continue(())).err() {
            Some(PpoError::Diverged { episode, what }) => {
                assert!(episode < 20, "{episode} {what}");
            }
            other => panic!("expected divergence, got {other:?}"),
        }
    }
}
