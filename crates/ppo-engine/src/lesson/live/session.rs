//! The live session: one training run, turned into a [`Snapshot`] after every episode.
//!
//! This is the only code that fills a snapshot in. The terminal app's worker thread owns a
//! session and sends its snapshot to the screen after each episode; `ppo-tutor show`, the
//! notebooks ([`crate::notebook::snapshot`]) and the tests call [`Session::run`].
//!
//! ```
//! use ppo_engine::lesson::Session;
//! use ppo_engine::ppo::PpoConfig;
//!
//! let mut session = Session::new(PpoConfig::default(), 0)?;
//! let snapshot = session.next_episode()?.ok_or("the run has episodes left")?;
//! assert_eq!(snapshot.episodes, 1);
//! assert!(snapshot.tensor("td_target").is_some());
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use super::{PolicyMap, Snapshot};
use crate::lesson::Environment;
use crate::ppo::model::ActorSnapshot;
use crate::ppo::{
    ContinuousTrainer, PpoConfig, PpoContinuousConfig, PpoError, Trainer, moving_average,
    surrogate_gradients,
};

/// The window of the return curve's moving average, as in the seed's plot.
pub const MOVING_AVERAGE_WINDOW: usize = 9;

/// The settings of a run: the seed's PPO on CartPole, or the book's `PPOContinuous` on
/// Pendulum. `Session::new` takes either config directly (`From`).
#[derive(Debug, Clone, PartialEq)]
pub enum RunConfig {
    /// CartPole-v1 (or v0) with the discrete PPO.
    CartPole(PpoConfig),
    /// Pendulum-v1 with the Gaussian-policy PPO.
    Pendulum(PpoContinuousConfig),
}

impl From<PpoConfig> for RunConfig {
    fn from(c: PpoConfig) -> Self {
        Self::CartPole(c)
    }
}

impl From<PpoContinuousConfig> for RunConfig {
    fn from(c: PpoContinuousConfig) -> Self {
        Self::Pendulum(c)
    }
}

impl RunConfig {
    /// The defaults of `env`'s run: the seed's hyper-parameters, or the book's for Pendulum.
    #[must_use]
    pub fn default_for(env: Environment) -> Self {
        match env {
            Environment::CartPole => Self::CartPole(PpoConfig::default()),
            Environment::Pendulum => Self::Pendulum(PpoContinuousConfig::default()),
        }
    }

    /// The environment the run trains on.
    #[must_use]
    pub fn env(&self) -> Environment {
        match self {
            Self::CartPole(_) => Environment::CartPole,
            Self::Pendulum(_) => Environment::Pendulum,
        }
    }

    /// Episodes the run trains for.
    #[must_use]
    pub fn num_episodes(&self) -> usize {
        match self {
            Self::CartPole(c) => c.num_episodes,
            Self::Pendulum(c) => c.num_episodes,
        }
    }

    /// What the tutor shows before the run's first episode.
    #[must_use]
    pub fn first_snapshot(&self, seed: u64) -> Snapshot {
        match self {
            Self::CartPole(c) => Snapshot::new(c, seed),
            Self::Pendulum(c) => Snapshot::new_pendulum(c, seed),
        }
    }
}

/// The trainer behind a session.
#[derive(Debug, Clone)]
enum Run {
    CartPole(Box<Trainer>),
    Pendulum(Box<ContinuousTrainer>),
}

/// A training run and what the tutor shows of it after its latest episode.
#[derive(Debug, Clone)]
pub struct Session {
    run: Run,
    snapshot: Snapshot,
}

impl Session {
    /// A fresh agent and environment from `config` and `seed` (see [`Trainer::new`] and
    /// [`ContinuousTrainer::new`]), with nothing trained yet: the snapshot holds only the
    /// hyper-parameters.
    ///
    /// # Errors
    /// [`PpoError::InvalidConfig`] for a hyper-parameter out of range.
    pub fn new(config: impl Into<RunConfig>, seed: u64) -> Result<Self, PpoError> {
        let config = config.into();
        let snapshot = config.first_snapshot(seed);
        let run = match config {
            RunConfig::CartPole(c) => Run::CartPole(Box::new(Trainer::new(c, seed)?)),
            RunConfig::Pendulum(c) => Run::Pendulum(Box::new(ContinuousTrainer::new(c, seed)?)),
        };
        Ok(Self { run, snapshot })
    }

    /// Trains up to `episodes` episodes (fewer if the config's `num_episodes` ends the run
    /// first) and returns what the tutor shows after them.
    ///
    /// # Errors
    /// Invalid settings, or a diverged run.
    pub fn run(
        config: impl Into<RunConfig>,
        seed: u64,
        episodes: usize,
    ) -> Result<Snapshot, PpoError> {
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
        let trainer = match &mut self.run {
            Run::CartPole(trainer) => trainer,
            Run::Pendulum(trainer) => return next_pendulum(trainer, &mut self.snapshot),
        };
        // The policy the episode is played with, before the episode's update changes it:
        // its probabilities are the ones the actions were sampled from (`old_log_probs`).
        let played_with = ActorSnapshot::of(trainer.agent().actor())?;
        // θ_old as candle variables, for the two policy gradients of the batch it played.
        let theta_old = trainer.agent().actor().frozen_copy()?;
        let Some(report) = trainer.next_episode()? else {
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
        s.weights = trainer.agent().weights()?;
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
        match &self.run {
            Run::CartPole(t) => t.is_done(),
            Run::Pendulum(t) => t.is_done(),
        }
    }
}

/// [`Session::next_episode`] for a Pendulum run: the return curve, the update's trace, the
/// weights and the policy's `(μ, σ)` map after the update.
fn next_pendulum<'a>(
    trainer: &mut ContinuousTrainer,
    s: &'a mut Snapshot,
) -> Result<Option<&'a Snapshot>, PpoError> {
    let Some(report) = trainer.next_episode()? else {
        return Ok(None);
    };
    s.episodes = report.episode + 1;
    s.returns.push(report.episode_return);
    s.moving_average = moving_average(&s.returns, MOVING_AVERAGE_WINDOW).unwrap_or_default();
    s.continuous = Some(report.trace);
    s.weights = trainer.agent().weights()?;
    let agent = trainer.agent();
    s.policy_map = Some(PolicyMap::of(|state| agent.mu_std(state)));
    Ok(Some(s))
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
        let cartpole = Session::run(PpoConfig::default(), 0, 10)?;
        let pendulum = Session::run(PpoContinuousConfig::default(), 0, 10)?;
        for (env, snapshot) in [
            (Environment::CartPole, cartpole),
            (Environment::Pendulum, pendulum),
        ] {
            check_every_value(env, &snapshot)?;
        }
        Ok(())
    }

    fn check_every_value(env: Environment, snapshot: &Snapshot) -> TestResult {
        for v in LIVE.iter().filter(|v| v.runs_on(env)) {
            let t = snapshot
                .tensor(v.name)
                .ok_or_else(|| format!("{} has no view in a {env:?} run", v.name))?;
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
        let Run::CartPole(trainer) = &session.run else {
            return Err("a CartPole session".into());
        };
        let before = ActorSnapshot::of(trainer.agent().actor())?;
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
    fn a_pendulum_session_follows_the_continuous_trainer() -> TestResult {
        let config = PpoContinuousConfig {
            num_episodes: 3,
            ..PpoContinuousConfig::default()
        };
        let mut session = Session::new(config.clone(), 5)?;
        let mut trainer = ContinuousTrainer::new(config, 5)?;
        while let Some(report) = trainer.next_episode()? {
            let s = session.next_episode()?.ok_or("the session ended early")?;
            assert_eq!(s.env, Environment::Pendulum);
            assert_eq!(s.continuous.as_ref(), Some(&report.trace));
            assert_eq!(s.returns.last(), Some(&report.episode_return));
            assert_eq!(s.observation_count(), 201);
            let map = s.policy_map.as_ref().ok_or("no policy map")?;
            let agent = trainer.agent();
            assert_eq!(map.mu.len(), 81);
            let upright = agent.mu_std(&[1.0, 0.0, 0.0]);
            assert_eq!(
                (map.mu[40], map.std[40]),
                upright,
                "the centre is upright at rest"
            );
            assert!(s.trace.is_none() && s.tensor("mu").is_some());
        }
        assert!(session.next_episode()?.is_none() && session.is_done());
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
