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
use crate::ppo::knobs::Tunable;
use crate::ppo::model::ActorSnapshot;
use crate::ppo::{
    Agent, EpisodeReport, OnPolicyAgent, PpoContinuous, PpoError, Training, moving_average,
    surrogate_gradients,
};
use crate::run::{RunConfig, RunVisitor};

/// The window of the return curve's moving average, as in the seed's plot.
pub const MOVING_AVERAGE_WINDOW: usize = 9;

/// An agent the live session can show: what it keeps of the policy before an episode,
/// and how the episode's report fills the snapshot. Its settings carry the sandbox's
/// knobs ([`crate::ppo::knobs::Tunable`]).
pub trait LiveAgent: OnPolicyAgent<Config: crate::ppo::knobs::Tunable> {
    /// What is kept of the policy that plays the episode, before its update changes it.
    type Before: Send;

    /// What the tutor shows before the run's first episode: the settings, no numbers yet.
    fn first_snapshot(config: &Self::Config, seed: u64) -> Snapshot;

    /// Keeps what [`LiveAgent::show`] needs of the policy before the episode.
    ///
    /// # Errors
    /// [`PpoError::Candle`] if the weights cannot be copied (a bug).
    fn before_episode(&self) -> Result<Self::Before, PpoError>;

    /// Fills the agent's own parts of `snapshot` from the episode's report (the return
    /// curve, the episode count and the weights are filled for every agent).
    ///
    /// # Errors
    /// [`PpoError::Candle`] if a gradient or a map cannot be computed (a bug).
    fn show(
        &self,
        before: Self::Before,
        report: EpisodeReport<Self::Trace>,
        snapshot: &mut Snapshot,
    ) -> Result<(), PpoError>;
}

impl LiveAgent for Agent {
    /// The policy the episode is played with, before the episode's update changes it: its
    /// probabilities are the ones the actions were sampled from (`old_log_probs`); and
    /// θ_old as candle variables, for the two policy gradients of the batch it played.
    type Before = (ActorSnapshot, crate::ppo::PolicyNet);

    fn first_snapshot(config: &crate::ppo::PpoConfig, seed: u64) -> Snapshot {
        Snapshot::new(config, seed)
    }

    fn before_episode(&self) -> Result<Self::Before, PpoError> {
        Ok((
            ActorSnapshot::of(self.actor())?,
            self.actor().frozen_copy()?,
        ))
    }

    fn show(
        &self,
        (played_with, theta_old): Self::Before,
        report: EpisodeReport,
        s: &mut Snapshot,
    ) -> Result<(), PpoError> {
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
        s.played_with = Some(played_with);
        Ok(())
    }
}

impl LiveAgent for PpoContinuous {
    type Before = ();

    fn first_snapshot(config: &crate::ppo::PpoContinuousConfig, seed: u64) -> Snapshot {
        Snapshot::new_pendulum(config, seed)
    }

    fn before_episode(&self) -> Result<(), PpoError> {
        Ok(())
    }

    /// The update's trace and the policy's `(μ, σ)` map after the update.
    fn show(
        &self,
        (): (),
        report: EpisodeReport<crate::ppo::ContinuousUpdateTrace>,
        s: &mut Snapshot,
    ) -> Result<(), PpoError> {
        s.continuous = Some(report.trace);
        s.policy_map = Some(PolicyMap::of(|state| self.mu_std(state)));
        Ok(())
    }
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
        s.returns.push(report.episode_return);
        s.moving_average = moving_average(&s.returns, MOVING_AVERAGE_WINDOW).unwrap_or_default();
        self.agent().show(before, report, s)?;
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
    use crate::lesson::AgentKind;
    use crate::lesson::live::{LIVE, PENALTY_ONLY};
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
        let cartpole = Session::run(PpoConfig::default(), 0, 10)?;
        let pendulum = Session::run(PpoContinuousConfig::default(), 0, 10)?;
        for (env, snapshot) in [
            (AgentKind::CartPole, cartpole),
            (AgentKind::Pendulum, pendulum),
        ] {
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
        for v in LIVE.iter().filter(|v| v.runs_on(env) && checked(v.name)) {
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
        // The same seed's fresh agent: the policy the first episode is played with.
        let trainer = Trainer::new(PpoConfig::default(), 0)?;
        let before = ActorSnapshot::of(trainer.agent().actor())?;
        let s = session.next_episode()?.ok_or("no episode")?;
        let trace = s.trace.as_ref().ok_or("no trace")?;
        // log π_old(a_t|s_t), recorded by the update, is the log of the played probability.
        for ((p, &a), old) in s.probs.iter().zip(&trace.actions).zip(&trace.old_log_probs) {
            assert!((p[a].ln() - old).abs() < 1e-5, "{p:?} {a} {old}");
        }
        assert_eq!(s.probs, probs_over(&before, &trace.states));
        assert_eq!(s.played_with.as_ref(), Some(&before), "θ_old is kept");
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
            assert_eq!(s.agent, AgentKind::Pendulum);
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
