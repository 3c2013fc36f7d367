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

use super::{LatestView, Snapshot};
use crate::ppo::knobs::Tunable;
use crate::ppo::{EpisodeReport, OnPolicyAgent, PpoError, Training, moving_average};
use crate::run::{IntoLatest, RunConfig, RunVisitor};

/// The window of the return curve's moving average, as in the seed's plot.
pub const MOVING_AVERAGE_WINDOW: usize = 9;

/// An agent the live session can show: what it keeps of the policy before an episode,
/// what it shows of the episode and its update ([`LiveAgent::Latest`], with the live
/// values only it has), and its settings as the hyper-parameter table. Its settings carry
/// the sandbox's knobs ([`crate::ppo::knobs::Tunable`]). Each agent's impl sits in its own
/// file under `lesson/live/agents/`.
pub trait LiveAgent: OnPolicyAgent<Config: crate::ppo::knobs::Tunable> {
    /// What is kept of the policy that plays the episode, before its update changes it.
    type Before: Send;

    /// What the tutor shows of the latest episode and update: the agent's slot of
    /// [`crate::run::Latest`].
    type Latest: LatestView + IntoLatest + Clone + std::fmt::Debug + PartialEq + Send + Sync;

    /// The live values only this agent's runs have, each viewed by
    /// [`LatestView::tensor`] (the values every run has are [`super::values::COMMON`]).
    const LIVE_VALUES: &'static [&'static str];

    /// The hyper-parameters of a run with `config` and `seed`, as `(name, value)` in the
    /// order the agent's Python source lists them.
    fn hyper(config: &Self::Config, seed: u64) -> Vec<(String, String)>;

    /// The clip range ε and the discount γ of `config` (for marking clipped ratios and for
    /// the return-to-go).
    fn eps_gamma(config: &Self::Config) -> (f64, f64);

    /// Keeps what [`LiveAgent::show`] needs of the policy before the episode.
    ///
    /// # Errors
    /// [`PpoError::Candle`] if the weights cannot be copied (a bug).
    fn before_episode(&self) -> Result<Self::Before, PpoError>;

    /// What the tutor shows of the episode's report (the return curve, the episode count
    /// and the weights are filled for every agent).
    ///
    /// # Errors
    /// [`PpoError::Candle`] if a gradient or a map cannot be computed (a bug).
    fn show(
        &self,
        before: Self::Before,
        report: EpisodeReport<Self::Trace>,
    ) -> Result<Self::Latest, PpoError>;
}

/// A run the session drives, whatever its agent.
trait LiveRun: std::fmt::Debug + Send {
    /// Plays one episode and fills `snapshot`; false once the run is done.
    fn next(&mut self, snapshot: &mut Snapshot) -> Result<bool, PpoError>;
    /// Whether every episode has been played.
    fn is_done(&self) -> bool;
    /// A copy of the run.
    fn clone_box(&self) -> Box<dyn LiveRun>;
}

impl<A: LiveAgent> LiveRun for Training<A> {
    fn next(&mut self, s: &mut Snapshot) -> Result<bool, PpoError> {
        let before = self.agent().before_episode()?;
        let Some(report) = self.next_episode()? else {
            return Ok(false);
        };
        s.episodes = report.episode + 1;
        s.env_steps += report.steps;
        s.returns.push(report.episode_return);
        s.moving_average = moving_average(&s.returns, MOVING_AVERAGE_WINDOW).unwrap_or_default();
        s.latest = self.agent().show(before, report)?.into_latest();
        s.weights = self.agent().named_weights()?;
        Ok(true)
    }

    fn is_done(&self) -> bool {
        Training::is_done(self)
    }

    fn clone_box(&self) -> Box<dyn LiveRun> {
        Box::new(self.clone())
    }
}

/// Starts the run of a configuration, for [`RunConfig::visit`].
struct Start(u64);

impl RunVisitor for Start {
    type Output = Result<Box<dyn LiveRun>, PpoError>;

    fn visit<C: Tunable>(self, config: &C) -> Self::Output
    where
        C::Agent: LiveAgent,
    {
        Ok(Box::new(Training::<C::Agent>::new(config.clone(), self.0)?))
    }
}

/// A training run and what the tutor shows of it after its latest episode.
#[derive(Debug)]
pub struct Session {
    run: Box<dyn LiveRun>,
    snapshot: Snapshot,
}

impl Clone for Session {
    fn clone(&self) -> Self {
        Self {
            run: self.run.clone_box(),
            snapshot: self.snapshot.clone(),
        }
    }
}

impl Session {
    /// A fresh agent and environment from `config` and `seed` (see [`Training::new`]), with
    /// nothing trained yet: the snapshot holds only the hyper-parameters.
    ///
    /// # Errors
    /// [`PpoError::InvalidConfig`] for a hyper-parameter out of range.
    pub fn new(config: impl Into<RunConfig>, seed: u64) -> Result<Self, PpoError> {
        let config = config.into();
        let snapshot = config.first_snapshot(seed);
        let run = config.visit(Start(seed))?;
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
    /// what the agent shows of its policy ([`LiveAgent::show`]) and the updated weights.
    /// `None` once the run has played all its episodes.
    ///
    /// # Errors
    /// [`PpoError::Diverged`] naming the episode, or [`PpoError::Candle`] if the weights
    /// cannot be read back (a bug).
    pub fn next_episode(&mut self) -> Result<Option<&Snapshot>, PpoError> {
        Ok(self.run.next(&mut self.snapshot)?.then_some(&self.snapshot))
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
        self.run.is_done()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lesson::AgentKind;
    use crate::lesson::live::agents::cartpole::probs_over;
    use crate::lesson::live::{PENALTY_ONLY, names, runs_on};
    use crate::ppo::model::ActorSnapshot;
    use crate::ppo::{ContinuousTrainer, PpoConfig, PpoContinuousConfig, Trainer};

    type TestResult = Result<(), Box<dyn std::error::Error>>;

    fn short(num_episodes: usize) -> PpoConfig {
        PpoConfig {
            num_episodes,
            ..PpoConfig::default()
        }
    }

    #[test]
    fn every_live_value_resolves_after_a_short_run() -> TestResult {
        for env in AgentKind::ALL {
            let snapshot = Session::run(RunConfig::default_for(env), 0, 10)?;
            assert_eq!(snapshot.agent(), env);
            check_every_value(env, &snapshot, |name| !PENALTY_ONLY.contains(&name))?;
        }
        // PPO-Penalty's own values, in a run of that objective.
        let penalty = PpoConfig {
            objective: crate::ppo::Objective::Penalty,
            ..PpoConfig::default()
        };
        let penalty = Session::run(penalty, 0, 10)?;
        check_every_value(AgentKind::CartPole, &penalty, |name| {
            PENALTY_ONLY.contains(&name)
        })?;
        Ok(())
    }

    fn check_every_value(
        env: AgentKind,
        snapshot: &Snapshot,
        checked: impl Fn(&str) -> bool,
    ) -> TestResult {
        for name in names()
            .into_iter()
            .filter(|&n| runs_on(n, env) && checked(n))
        {
            let t = snapshot
                .tensor(name)
                .ok_or_else(|| format!("{name} has no view in a {env:?} run"))?;
            assert_eq!(t.name, name);
            let rows = t.values.len().max(t.labels.len());
            assert!(rows > 0, "{name} is empty");
        }
        for name in names().into_iter().filter(|&n| !runs_on(n, env)) {
            assert!(snapshot.tensor(name).is_none(), "{name} in a {env:?} run");
        }
        Ok(())
    }

    #[test]
    fn the_snapshot_follows_the_trainer_episode_by_episode() -> TestResult {
        let mut session = Session::new(short(12), 3)?;
        let mut trainer = Trainer::new(short(12), 3)?;
        let (mut returns, mut steps) = (Vec::new(), 0);
        while let Some(report) = trainer.next_episode()? {
            let s = session.next_episode()?.ok_or("the session ended early")?;
            returns.push(report.episode_return);
            assert_eq!(s.episodes, report.episode + 1);
            assert_eq!(s.returns, returns);
            let latest = s.cartpole_update().ok_or("a CartPole update")?;
            assert_eq!(latest.trace, report.trace);
            assert_eq!(latest.terminated, report.terminated);
            assert_eq!(latest.truncated, report.truncated);
            assert_eq!(latest.probs.len(), report.steps);
            steps += report.steps;
            assert_eq!(s.env_steps, steps);
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
        // The same seed's fresh agent: the policy the first episode is played with.
        let trainer = Trainer::new(PpoConfig::default(), 0)?;
        let before = ActorSnapshot::of(trainer.agent().actor())?;
        let s = session.next_episode()?.ok_or("no episode")?;
        let latest = s.cartpole_update().ok_or("no update")?;
        let trace = &latest.trace;
        // log π_old(a_t|s_t), recorded by the update, is the log of the played probability.
        for ((p, &a), old) in latest
            .probs
            .iter()
            .zip(&trace.actions)
            .zip(&trace.old_log_probs)
        {
            assert!((p[a].ln() - old).abs() < 1e-5, "{p:?} {a} {old}");
        }
        assert_eq!(latest.probs, probs_over(&before, &trace.states));
        assert_eq!(latest.played_with, before, "θ_old is kept");
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
        assert_eq!(s, Snapshot::new(short(3), 0));
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
            assert_eq!(s.agent(), AgentKind::Pendulum);
            let latest = s.pendulum_update().ok_or("a Pendulum update")?;
            assert_eq!(latest.trace, report.trace);
            assert_eq!(s.returns.last(), Some(&report.episode_return));
            assert_eq!(s.observation_count(), 201);
            let map = &latest.policy_map;
            let agent = trainer.agent();
            assert_eq!(map.mu.len(), 81);
            let upright = agent.mu_std(&[1.0, 0.0, 0.0]);
            assert_eq!(
                (map.mu[40], map.std[40]),
                upright,
                "the centre is upright at rest"
            );
            assert!(s.cartpole_update().is_none() && s.tensor("mu").is_some());
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
