//! The live session: one training run, turned into a [`Snapshot`] after every episode.
//!
//! This is the only code that fills a snapshot in. The terminal app's worker thread owns a
//! session and sends its snapshot to the screen after each episode; `ppo-tutor show`, the
//! notebooks ([`crate::notebook::snapshot`]) and the tests call [`Session::run`].
//!
//! ```
//! use ppo_tutor::lesson::Session;
//! use ppo_tutor::ppo::PpoConfig;
//!
//! let mut session = Session::new(PpoConfig::default(), 0)?;
//! let snapshot = session.next_episode()?.ok_or("the run has episodes left")?;
//! assert_eq!(snapshot.episodes, 1);
//! assert!(snapshot.tensor("td_target").is_some());
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use super::Snapshot;
use crate::ppo::model::ActorSnapshot;
use crate::ppo::{PpoConfig, PpoError, Trainer, moving_average, surrogate_gradients};

/// The window of the return curve's moving average, as in the seed's plot.
pub const MOVING_AVERAGE_WINDOW: usize = 9;

/// A training run and what the tutor shows of it after its latest episode.
#[derive(Debug, Clone)]
pub struct Session {
    trainer: Trainer,
    snapshot: Snapshot,
}

impl Session {
    /// A fresh agent and environment from `config` and `seed` (see [`Trainer::new`]), with
    /// nothing trained yet: the snapshot holds only the hyper-parameters.
    ///
    /// # Errors
    /// [`PpoError::InvalidConfig`] for a hyper-parameter out of range.
    pub fn new(config: PpoConfig, seed: u64) -> Result<Self, PpoError> {
        let snapshot = Snapshot::new(&config, seed);
        Ok(Self {
            trainer: Trainer::new(config, seed)?,
            snapshot,
        })
    }

    /// Trains up to `episodes` episodes (fewer if the config's `num_episodes` ends the run
    /// first) and returns what the tutor shows after them.
    ///
    /// # Errors
    /// Invalid settings, or a diverged run.
    pub fn run(config: PpoConfig, seed: u64, episodes: usize) -> Result<Snapshot, PpoError> {
        let mut session = Self::new(config, seed)?;
        for _ in 0..episodes {
            if session.next_episode()?.is_none() {
                break;
            }
        }
        Ok(session.into_snapshot())
    }

    /// Plays one episode, updates the agent on it and brings the snapshot up to date: the
    /// return curve and its moving average, the batch and every intermediate of the update,
    /// the probabilities the episode was played with, the flags and the updated weights.
    /// `None` once the run has played all its episodes.
    ///
    /// # Errors
    /// [`PpoError::Diverged`] naming the episode, or [`PpoError::Candle`] if the weights
    /// cannot be read back (a bug).
    pub fn next_episode(&mut self) -> Result<Option<&Snapshot>, PpoError> {
        // The policy the episode is played with, before the episode's update changes it:
        // its probabilities are the ones the actions were sampled from (`old_log_probs`).
        let played_with = ActorSnapshot::of(self.trainer.agent().actor())?;
        // θ_old as candle variables, for the two policy gradients of the batch it played.
        let theta_old = self.trainer.agent().actor().frozen_copy()?;
        let Some(report) = self.trainer.next_episode()? else {
            return Ok(None);
        };
        let s = &mut self.snapshot;
        s.episodes = report.episode + 1;
        s.returns.push(report.episode_return);
        s.moving_average = moving_average(&s.returns, MOVING_AVERAGE_WINDOW).unwrap_or_default();
        s.probs = probs_over(&played_with, &report.trace.states);
        s.terminated = report.terminated;
        s.truncated = report.truncated;
        s.gradients = Some(surrogate_gradients(
            &theta_old,
            &report.trace.states,
            &report.trace.actions,
            &report.trace.advantage,
        )?);
        s.trace = Some(report.trace);
        s.weights = self.trainer.agent().weights()?;
        Ok(Some(&self.snapshot))
    }

    /// What the tutor shows now.
    #[must_use]
    pub fn snapshot(&self) -> &Snapshot {
        &self.snapshot
    }

    /// The snapshot, ending the session.
    #[must_use]
    pub fn into_snapshot(self) -> Snapshot {
        self.snapshot
    }

    /// Whether every episode of the run has been played.
    #[must_use]
    pub fn is_done(&self) -> bool {
        self.trainer.is_done()
    }
}

/// `π(·|s)` under `policy` for each of `states` (NaN where a probability is missing).
fn probs_over(policy: &ActorSnapshot, states: &[[f32; 4]]) -> Vec<[f32; 2]> {
    states
        .iter()
        .map(|s| {
            let p = policy.probs(s);
            [
                p.first().copied().unwrap_or(f32::NAN),
                p.get(1).copied().unwrap_or(f32::NAN),
            ]
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lesson::live::LIVE;

    type TestResult = Result<(), Box<dyn std::error::Error>>;

    fn short(num_episodes: usize) -> PpoConfig {
        PpoConfig {
            num_episodes,
            ..PpoConfig::default()
        }
    }

    #[test]
    fn every_live_value_resolves_after_a_short_run() -> TestResult {
        let snapshot = Session::run(PpoConfig::default(), 0, 10)?;
        for v in LIVE {
            let t = snapshot
                .tensor(v.name)
                .ok_or_else(|| format!("{} has no view after 10 episodes", v.name))?;
            assert_eq!(t.name, v.name);
            let rows = t.values.len().max(t.labels.len());
            assert!(rows > 0, "{} is empty", v.name);
        }
        Ok(())
    }

    #[test]
    fn the_snapshot_follows_the_trainer_episode_by_episode() -> TestResult {
        let mut session = Session::new(short(12), 3)?;
        let mut trainer = Trainer::new(short(12), 3)?;
        let mut returns = Vec::new();
        while let Some(report) = trainer.next_episode()? {
            let s = session.next_episode()?.ok_or("the session ended early")?;
            returns.push(report.episode_return);
            assert_eq!(s.episodes, report.episode + 1);
            assert_eq!(s.returns, returns);
            assert_eq!(s.trace.as_ref(), Some(&report.trace));
            assert_eq!(s.terminated, report.terminated);
            assert_eq!(s.truncated, report.truncated);
            assert_eq!(s.probs.len(), report.steps);
            assert_eq!(s.weights, trainer.agent().weights()?);
            let expected = moving_average(&returns, 9).unwrap_or_default();
            assert_eq!(s.moving_average, expected);
        }
        assert!(session.next_episode()?.is_none() && session.is_done());
        assert_eq!(session.snapshot().episodes, 12);
        Ok(())
    }

    #[test]
    fn probs_are_those_of_the_policy_that_played() -> TestResult {
        let mut session = Session::new(PpoConfig::default(), 0)?;
        let before = ActorSnapshot::of(session.trainer.agent().actor())?;
        let s = session.next_episode()?.ok_or("no episode")?;
        let trace = s.trace.as_ref().ok_or("no trace")?;
        // log π_old(a_t|s_t), recorded by the update, is the log of the played probability.
        for ((p, &a), old) in s.probs.iter().zip(&trace.actions).zip(&trace.old_log_probs) {
            assert!((p[a].ln() - old).abs() < 1e-5, "{p:?} {a} {old}");
        }
        assert_eq!(s.probs, probs_over(&before, &trace.states));
        Ok(())
    }

    #[test]
    fn run_stops_at_the_configured_episodes() -> TestResult {
        let s = Session::run(short(3), 0, 10)?;
        assert_eq!((s.episodes, s.returns.len()), (3, 3));
        assert!(
            s.moving_average.is_empty(),
            "3 returns are too few for window 9"
        );
        let s = Session::run(short(3), 0, 0)?;
        assert_eq!(s, Snapshot::new(&short(3), 0));
        Ok(())
    }

    #[test]
    fn invalid_settings_are_refused_before_training() {
        let bad = PpoConfig {
            gamma: 2.0,
            ..PpoConfig::default()
        };
        assert!(matches!(
            Session::new(bad, 0),
            Err(PpoError::InvalidConfig { .. })
        ));
    }
}
