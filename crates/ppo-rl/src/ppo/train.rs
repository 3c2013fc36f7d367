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
use super::on_policy::{AgentConfig, Batch, Budget, OnPolicyAgent};
use super::rollout::{FinishedEpisode, Rollout};
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

/// What one update produced, for any rollout; `T` is the agent's update trace.
#[derive(Debug, Clone, Serialize)]
pub struct UpdateReport<T = UpdateTrace> {
    /// The update, from 0.
    pub update: usize,
    /// Environment steps in its rollout.
    pub steps: usize,
    /// Environment steps since training began.
    pub total_steps: u64,
    /// The episodes that finished in its rollout (`end_step` counted since training began).
    pub episodes: Vec<FinishedEpisode>,
    /// Gymnasium's `terminated` for each transition of the batch.
    pub terminated: Vec<bool>,
    /// The update, every intermediate.
    pub trace: T,
}

/// Training so far, and the final result.
#[derive(Debug, Clone, Serialize)]
pub struct TrainSummary {
    /// One return per episode.
    pub returns: Vec<f64>,
    /// Environment steps over all episodes.
    pub env_steps: u64,
    /// Environment steps since training began at the end of each episode: the x-axis on
    /// which runs with different rollouts compare.
    pub episode_end_steps: Vec<u64>,
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

/// The training loop of any agent as a state machine: call [`Training::next_update`] (or,
/// for a one-episode rollout, [`Training::next_episode`]) until it gives `None`.
#[derive(Debug, Clone)]
pub struct Training<A: OnPolicyAgent> {
    config: A::Config,
    agent: A,
    rollout: A::Rollout,
    updates: usize,
    returns: Vec<f64>,
    episode_end_steps: Vec<u64>,
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
        let rollout = A::Rollout::start(&config, seed);
        Ok(Self {
            config,
            agent,
            rollout,
            updates: 0,
            returns: Vec::new(),
            episode_end_steps: Vec::new(),
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

    /// The rollout, as far as it has run.
    #[must_use]
    pub fn rollout(&self) -> &A::Rollout {
        &self.rollout
    }

    /// Whether the run's budget (episodes or environment steps) is spent.
    #[must_use]
    pub fn is_done(&self) -> bool {
        match self.config.budget() {
            Budget::Episodes(n) => self.returns.len() >= n,
            Budget::Steps(n) => self.env_steps >= n,
        }
    }

    /// The result so far.
    #[must_use]
    pub fn summary(&self) -> TrainSummary {
        TrainSummary {
            returns: self.returns.clone(),
            env_steps: self.env_steps,
            episode_end_steps: self.episode_end_steps.clone(),
            wall_s: self.elapsed.as_secs_f64(),
        }
    }

    /// Which bar episode `episode` belongs to: `(iteration, index within it, bar length)`.
    #[must_use]
    pub fn iteration_of(&self, episode: usize) -> (usize, usize, usize) {
        iteration_of(self.config.num_episodes(), episode)
    }

    /// Collects one rollout and updates the agent on it; `None` once the budget is spent.
    ///
    /// # Errors
    /// [`PpoError::Diverged`] naming the update when an action, target or loss turns NaN or
    /// infinite.
    pub fn next_update(&mut self) -> Result<Option<UpdateReport<A::Trace>>, PpoError> {
        self.update_with(A::learn)
    }

    /// [`Training::next_update`] with the update done by `update` (the agent's own
    /// [`OnPolicyAgent::learn`], or one with a learner's losses).
    ///
    /// # Errors
    /// As [`Training::next_update`], plus an error `update` returned.
    pub fn update_with(
        &mut self,
        update: impl FnOnce(&mut A, &A::Batch) -> Result<A::Trace, PpoError>,
    ) -> Result<Option<UpdateReport<A::Trace>>, PpoError> {
        if self.is_done() {
            return Ok(None);
        }
        let started = Instant::now();
        // A one-episode run names the episode that diverged, as the seed counts them.
        let episode = self.returns.len();
        let diverged = |e: PpoError| match e {
            PpoError::NonFinite(what) => PpoError::Diverged { episode, what },
            other => other,
        };
        let collected = self.rollout.collect(&mut self.agent).map_err(diverged)?;
        let trace = update(&mut self.agent, &collected.batch).map_err(diverged)?;
        let before = self.env_steps;
        self.env_steps += collected.steps as u64;
        let episodes: Vec<FinishedEpisode> = collected
            .episodes
            .into_iter()
            .map(|e| FinishedEpisode {
                end_step: before + e.end_step,
                ..e
            })
            .collect();
        for e in &episodes {
            self.returns.push(e.episode_return);
            self.episode_end_steps.push(e.end_step);
        }
        let update = self.updates;
        self.updates += 1;
        self.elapsed += started.elapsed();
        Ok(Some(UpdateReport {
            update,
            steps: collected.steps,
            total_steps: self.env_steps,
            episodes,
            terminated: collected.batch.terminated(),
            trace,
        }))
    }

    /// Plays one episode and updates the agent on it; `None` once all episodes are done.
    ///
    /// # Errors
    /// [`PpoError::Diverged`] naming the episode when an action, target or loss turns NaN
    /// or infinite; [`PpoError::InvalidBatch`] when the agent's rollout is not one episode
    /// (use [`Training::next_update`] for those).
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
        let episode = self.returns.len();
        let Some(report) = self.update_with(update)? else {
            return Ok(None);
        };
        let [finished] = report.episodes[..] else {
            let (update, finished) = (report.update, report.episodes.len());
            return Err(PpoError::InvalidBatch(crate::tr!(
                "update {update} finished {finished} episodes: next_episode needs a one-episode \
                 rollout; call next_update for this agent",
                "第 {update} 次更新结束了 {finished} 个回合：next_episode 要求每次更新只采集一个回合；\
                 这个智能体请调用 next_update"
            )));
        };
        let (iteration, episode_in_iteration, iteration_len) = self.iteration_of(episode);
        let steps = report.steps;
        Ok(Some(EpisodeReport {
            episode,
            iteration,
            episode_in_iteration,
            iteration_len,
            episode_return: finished.episode_return,
            steps,
            total_steps: report.total_steps,
            terminated: report.terminated,
            truncated: (1..=steps)
                .map(|t| t == steps && finished.truncated)
                .collect(),
            trace: report.trace,
        }))
    }
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
    fn updates_and_episodes_agree_and_count_steps() -> Result<(), PpoError> {
        let config = PpoConfig {
            num_episodes: 4,
            ..PpoConfig::default()
        };
        let mut by_episode = Trainer::new(config.clone(), 3)?;
        let mut by_update = Trainer::new(config, 3)?;
        let mut total = 0;
        while let Some(e) = by_episode.next_episode()? {
            let Some(u) = by_update.next_update()? else {
                panic!("the same budget gives the same number of updates");
            };
            total += e.steps as u64;
            assert_eq!(
                (u.update, u.steps, u.total_steps),
                (e.episode, e.steps, total)
            );
            assert_eq!(u.episodes.len(), 1, "one episode per update");
            assert_eq!(u.episodes[0].episode_return, e.episode_return);
            assert_eq!(u.episodes[0].end_step, total);
            assert_eq!(u.episodes[0].truncated, e.truncated.last() == Some(&true));
            assert_eq!(u.trace, e.trace);
        }
        assert!(by_update.next_update()?.is_none());
        let (a, b) = (by_episode.summary(), by_update.summary());
        assert_eq!(a.returns, b.returns);
        assert_eq!(a.episode_end_steps, b.episode_end_steps);
        assert_eq!(a.episode_end_steps.last(), Some(&a.env_steps));
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
