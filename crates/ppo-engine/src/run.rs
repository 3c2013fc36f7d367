//! The registry of agents, and the configuration of a run: which agent (and so which
//! environment), which settings. The `agents!` list below is the one list of agents: every
//! per-agent list elsewhere ([`AgentKind::ALL`], [`PerAgent`], the checkpoint kinds
//! [`AgentKind::checkpoint`], the command line's environments [`RunConfig::choices`]) is
//! derived from it, and everything else is generic over [`AgentConfig`] and reaches the right
//! agent through [`RunConfig::visit`], or reads what differs between agents from
//! [`AgentKind::spec`].
//!
//! ```
//! use ppo_engine::ppo::knobs::Tunable;
//! use ppo_engine::ppo::{OnPolicyAgent, Training};
//! use ppo_engine::run::{AgentKind, RunConfig, RunVisitor};
//!
//! /// The first return of a run, for any agent.
//! struct FirstReturn;
//! impl RunVisitor for FirstReturn {
//!     type Output = Result<f64, ppo_engine::ppo::PpoError>;
//!     fn visit<C: Tunable>(self, config: &C) -> Self::Output
//!     where
//!         C::Agent: ppo_engine::lesson::live::session::LiveAgent,
//!     {
//!         let mut run = Training::<C::Agent>::new(config.clone(), 0)?;
//!         Ok(run.next_episode()?.map_or(0.0, |r| r.episode_return))
//!     }
//! }
//! for env in AgentKind::ALL {
//!     let first = RunConfig::default_for(env).visit(FirstReturn)?;
//!     assert_eq!(first > 0.0, env == AgentKind::CartPole); // Pendulum's rewards are ≤ 0
//! }
//! # Ok::<(), ppo_engine::ppo::PpoError>(())
//! ```

use std::any::Any;
use std::ops::{Index, IndexMut};

use crate::i18n::t;
use crate::lesson::Snapshot;
use crate::lesson::live::LatestView;
use crate::lesson::live::session::LiveAgent;
use crate::ppo::knobs::Tunable;
use crate::ppo::knobs::{self, KnobValue};
use crate::ppo::on_policy::Replayed;
use crate::ppo::replay_file::first_weights;
use crate::ppo::{
    AgentConfig, CheckpointKind, OnPolicyAgent, PpoConfig, PpoContinuousConfig, PpoError,
};

/// Declares the agents a run can train: the [`AgentKind`] enum, the [`RunConfig`] enum
/// and the dispatch between them. One line per agent: `Variant(ConfigType) = SPEC`; the
/// first is the default.
macro_rules! agents {
    ($( $(#[doc = $doc:expr])* $env:ident($config:ty) = $spec:expr ),+ $(,)?) => {
        /// The agent a run (and a lesson's live view) trains, each on its environment: one
        /// variant per line of `agents!`.
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
        pub enum AgentKind {
            $( $(#[doc = $doc])* $env, )+
        }

        const COUNT: usize = [$(stringify!($env)),+].len();

        /// The first agent's: CartPole-v1 with the seed's PPO.
        impl Default for AgentKind {
            fn default() -> Self {
                Self::ALL[0]
            }
        }

        impl AgentKind {
            /// Every agent, in course order.
            pub const ALL: [AgentKind; COUNT] = [$(AgentKind::$env),+];

            /// The number of agents.
            pub const COUNT: usize = COUNT;

            /// The position in [`AgentKind::ALL`].
            #[must_use]
            pub const fn index(self) -> usize {
                self as usize
            }

            /// What differs between the agents' runs outside the agents themselves.
            #[must_use]
            pub const fn spec(self) -> &'static EnvSpec {
                match self {
                    $( AgentKind::$env => &$spec, )+
                }
            }

            /// The live values only this agent's runs have
            /// ([`LiveAgent::LIVE_VALUES`]).
            #[must_use]
            pub const fn live_values(self) -> &'static [&'static str] {
                match self {
                    $( AgentKind::$env => <<$config as AgentConfig>::Agent as LiveAgent>::LIVE_VALUES, )+
                }
            }

            /// How this agent's checkpoint file is marked (its own declaration,
            /// [`OnPolicyAgent::CHECKPOINT`]).
            #[must_use]
            pub const fn checkpoint(self) -> CheckpointKind {
                match self {
                    $( AgentKind::$env => <<$config as AgentConfig>::Agent as OnPolicyAgent>::CHECKPOINT, )+
                }
            }
        }

        /// What the tutor shows of a run's latest episode and update, in the run's agent's
        /// own type ([`LiveAgent::Latest`]); `None` before the first episode.
        #[derive(Debug, Clone, PartialEq)]
        pub enum Latest {
            $( $(#[doc = $doc])* $env(Option<Box<<<$config as AgentConfig>::Agent as LiveAgent>::Latest>>), )+
        }

        /// Nothing shown yet, of the first agent.
        impl Default for Latest {
            fn default() -> Self {
                Self::empty(AgentKind::default())
            }
        }


        impl Latest {
            /// Nothing shown yet of a run of `agent`.
            #[must_use]
            pub fn empty(agent: AgentKind) -> Self {
                match agent {
                    $( AgentKind::$env => Self::$env(None), )+
                }
            }

            /// The agent whose run this is.
            #[must_use]
            pub fn agent(&self) -> AgentKind {
                match self {
                    $( Self::$env(_) => AgentKind::$env, )+
                }
            }

            /// The agent's view of what it shows, `None` before the first episode.
            #[must_use]
            pub fn view(&self) -> Option<&dyn LatestView> {
                match self {
                    $( Self::$env(latest) => latest.as_deref().map(|l| l as &dyn LatestView), )+
                }
            }
        }

        /// The settings of a run: which agent on which environment, and its
        /// hyper-parameters. `Session::new` takes any agent's config directly (`From`).
        #[derive(Debug, Clone, PartialEq, serde::Serialize)]
        #[serde(untagged)]
        pub enum RunConfig {
            $( $(#[doc = $doc])* $env($config), )+
        }

        /// The first agent's defaults: CartPole-v1 with the seed's PPO.
        impl Default for RunConfig {
            fn default() -> Self {
                Self::default_for(AgentKind::default())
            }
        }

        $(
            impl From<$config> for RunConfig {
                fn from(c: $config) -> Self {
                    Self::$env(c)
                }
            }
        )+

        impl RunConfig {
            /// Calls `visitor` with the agent configuration inside: the one dispatch from
            /// a run's environment to code generic over the agents (training, the live
            /// session, `ppo-tutor train`, its `--seeds`).
            pub fn visit<V: RunVisitor>(&self, visitor: V) -> V::Output {
                match self {
                    $( Self::$env(c) => visitor.visit(c), )+
                }
            }

            /// Calls `visitor` with the agent configuration inside, to change it: see
            /// [`RunConfig::visit`].
            pub fn visit_mut<V: RunVisitorMut>(&mut self, visitor: V) -> V::Output {
                match self {
                    $( Self::$env(c) => visitor.visit_mut(c), )+
                }
            }

            /// The agent configuration inside, if it is a `C`.
            #[must_use]
            pub fn get<C: AgentConfig>(&self) -> Option<&C> {
                match self {
                    $( Self::$env(c) => (c as &dyn Any).downcast_ref::<C>(), )+
                }
            }

            /// The defaults of `env`'s run: the reference hyper-parameters of its agent
            /// (the seed's, or the book's for Pendulum).
            #[must_use]
            pub fn default_for(env: AgentKind) -> Self {
                match env {
                    $( AgentKind::$env => Self::$env(<$config>::default()), )+
                }
            }

            /// The agent the run trains.
            #[must_use]
            pub fn agent(&self) -> AgentKind {
                match self {
                    $( Self::$env(_) => AgentKind::$env, )+
                }
            }
        }
    };
}

agents! {
    /// `CartPole-v1` (or v0), the seed's PPO or REINFORCE (two actions).
    CartPole(PpoConfig) = CARTPOLE,
    /// `Pendulum-v1`, the book's Gaussian-policy `PPOContinuous` (one torque).
    Pendulum(PpoContinuousConfig) = PENDULUM,
}

const CARTPOLE: EnvSpec = EnvSpec {
    id: "CartPole-v1",
    name: "CartPole",
    python_source: "seed",
    source_name: ("the seed", "原教程代码"),
    engine_name: ("the real PPO and CartPole", "真实的 PPO 和 CartPole"),
    summary_window: 50,
    whole_returns: true,
    plot_floor: 0.0,
};

const PENDULUM: EnvSpec = EnvSpec {
    id: "Pendulum-v1",
    name: "Pendulum",
    python_source: "book",
    source_name: ("the book", "书中代码"),
    engine_name: (
        "the real PPOContinuous and Pendulum",
        "真实的 PPOContinuous 和 Pendulum",
    ),
    summary_window: 100,
    whole_returns: false,
    plot_floor: -1800.0,
};

/// What differs between the environments outside the agents themselves: names, the
/// source the lessons quote, and how results are summed up and drawn.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EnvSpec {
    /// The id as Gymnasium spells it (and a lesson's front matter writes it).
    pub id: &'static str,
    /// The environment without its version (`CartPole`), as the sandbox names it.
    pub name: &'static str,
    /// Whose PyTorch program a step's `python` lines quote: `seed` (`seed_ppo.py`) or `book`.
    pub python_source: &'static str,
    /// That program in prose, English and Chinese ("the seed", "原教程代码").
    pub source_name: (&'static str, &'static str),
    /// What every number of a notebook comes from, English and Chinese.
    pub engine_name: (&'static str, &'static str),
    /// How many last episodes a summary averages (50 as the seed prints, 100 as the book's
    /// Pendulum script).
    pub summary_window: usize,
    /// Whether returns are whole numbers (CartPole's +1 per step).
    pub whole_returns: bool,
    /// The return plot's lowest value (CartPole's 0; Pendulum's returns are negative, a
    /// random policy scoring around −1200).
    pub plot_floor: f64,
}

impl AgentKind {
    /// Whose PyTorch program a step's `python` lines quote: the seed's (`seed_ppo.py`) on
    /// CartPole, the book's `PPOContinuous` on Pendulum.
    #[must_use]
    pub fn python_source(self) -> &'static str {
        self.spec().python_source
    }

    /// That program in prose, in the current language ("the seed", "书中代码").
    #[must_use]
    pub fn source_name(self) -> &'static str {
        let (en, zh) = self.spec().source_name;
        t(en, zh)
    }

    /// The id as Gymnasium spells it (and a lesson's front matter writes it).
    #[must_use]
    pub fn as_str(self) -> &'static str {
        self.spec().id
    }

    /// The environment called `name` (`CartPole-v1` or `Pendulum-v1`).
    #[must_use]
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|e| e.as_str() == name)
    }

    /// A return formatted as the environment's returns are (whole numbers on CartPole, one
    /// decimal on Pendulum).
    #[must_use]
    pub fn format_return(self, value: f64) -> String {
        if self.spec().whole_returns {
            format!("{value}")
        } else {
            format!("{value:.1}")
        }
    }
}

/// An agent's [`LiveAgent::Latest`] in its slot of [`Latest`] (each agent's live file
/// writes its one line).
pub trait IntoLatest {
    /// `self` in its agent's variant.
    fn into_latest(self) -> Latest;
}

/// Code generic over the agents, called with the run's configuration, typed: see
/// [`RunConfig::visit`].
pub trait RunVisitor {
    /// What the visit returns.
    type Output;

    /// Called with the run's configuration.
    fn visit<C: Tunable>(self, config: &C) -> Self::Output
    where
        C::Agent: LiveAgent;
}

/// Code generic over the agents that changes the run's configuration: see
/// [`RunConfig::visit_mut`].
pub trait RunVisitorMut {
    /// What the visit returns.
    type Output;

    /// Called with the run's configuration.
    fn visit_mut<C: Tunable>(self, config: &mut C) -> Self::Output;
}

/// One value per [`AgentKind`] (the settings of each agent's run, say), indexed by the
/// agent: adding an agent adds its slot, so no per-agent state is kept for "the other one".
#[derive(Debug, Clone, PartialEq)]
pub struct PerAgent<T>([T; AgentKind::COUNT]);

impl<T> PerAgent<T> {
    /// `f(agent)` for every agent.
    #[must_use]
    pub fn from_fn(f: impl FnMut(AgentKind) -> T) -> Self {
        Self(AgentKind::ALL.map(f))
    }
}

impl<T> Index<AgentKind> for PerAgent<T> {
    type Output = T;

    fn index(&self, env: AgentKind) -> &T {
        &self.0[env.index()]
    }
}

impl<T> IndexMut<AgentKind> for PerAgent<T> {
    fn index_mut(&mut self, env: AgentKind) -> &mut T {
        &mut self.0[env.index()]
    }
}

/// The settings of every environment's run.
pub type RunConfigs = PerAgent<RunConfig>;

impl RunConfigs {
    /// Every environment's defaults ([`RunConfig::default_for`]).
    #[must_use]
    pub fn defaults() -> Self {
        Self::from_fn(RunConfig::default_for)
    }

    /// Keeps `config` as its environment's settings.
    pub fn set(&mut self, config: RunConfig) {
        let env = config.agent();
        self[env] = config;
    }

    /// The first settings that are a `C`.
    #[must_use]
    pub fn get<C: AgentConfig>(&self) -> Option<&C> {
        self.0.iter().find_map(RunConfig::get)
    }
}

/// One environment the sandbox can choose: an agent's environment and one of its
/// Gymnasium ids.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Choice {
    /// The agent that plays it.
    pub agent: AgentKind,
    /// The Gymnasium id (`CartPole-v0`).
    pub id: &'static str,
}

/// The Gymnasium id, as a command line writes it.
impl std::fmt::Display for Choice {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.id)
    }
}

impl RunConfig {
    /// The Gymnasium id of the run's environment (`CartPole-v0` where the config says so).
    #[must_use]
    pub fn env_id(&self) -> &'static str {
        self.visit(EnvId)
    }

    /// Episodes the run trains for.
    #[must_use]
    pub fn num_episodes(&self) -> usize {
        self.visit(NumEpisodes)
    }

    /// Every setting in its range.
    ///
    /// # Errors
    /// [`PpoError::InvalidConfig`] naming the first field out of range.
    pub fn validate(&self) -> Result<(), PpoError> {
        self.visit(Validate)
    }

    /// The highest return an episode can have (CartPole's time limit; 0 on Pendulum), for
    /// a plot's scale.
    #[must_use]
    pub fn max_return(&self) -> f64 {
        self.visit(MaxReturn)
    }

    /// What the tutor shows before the run's first episode.
    #[must_use]
    pub fn first_snapshot(&self, seed: u64) -> Snapshot {
        self.visit(FirstSnapshot {
            seed,
            agent: self.agent(),
        })
    }

    /// The ids of this run's knobs ([`Tunable::KNOBS`]), in display order.
    #[must_use]
    pub fn knob_ids(&self) -> Vec<&'static str> {
        self.visit(KnobIds)
    }

    /// The ids of every agent's knobs, in display order: the first agent's, then each
    /// other's not yet listed (the sandbox's rows).
    #[must_use]
    pub fn all_knob_ids() -> Vec<&'static str> {
        let mut ids: Vec<&'static str> = Vec::new();
        for env in AgentKind::ALL {
            for id in Self::default_for(env).knob_ids() {
                if !ids.contains(&id) {
                    ids.push(id);
                }
            }
        }
        ids
    }

    /// The environments whose agents have the knob `id`.
    #[must_use]
    pub fn environments_with(id: &str) -> Vec<AgentKind> {
        AgentKind::ALL
            .into_iter()
            .filter(|&env| Self::default_for(env).knob(id).is_some())
            .collect()
    }

    /// The knob `id` of this run, read; `None` when its agent has no such knob.
    #[must_use]
    pub fn knob(&self, id: &str) -> Option<KnobValue> {
        self.visit(ReadKnob(id))
    }

    /// Changes the setting `id` one notch up or down, within its range; `false` (nothing
    /// changed) when the agent has no such setting, or it is the seed or the environment.
    pub fn nudge(&mut self, id: &str, up: bool) -> bool {
        self.visit_mut(Nudge(id, up))
    }

    /// Every environment a run can play, in the sandbox's cycle order: each agent's
    /// Gymnasium ids ([`AgentConfig::ENV_IDS`]), agent after agent (CartPole-v1,
    /// CartPole-v0, Pendulum-v1).
    #[must_use]
    pub fn choices() -> Vec<Choice> {
        AgentKind::ALL
            .into_iter()
            .flat_map(|agent| {
                Self::default_for(agent)
                    .visit(EnvIds)
                    .iter()
                    .map(move |&id| Choice { agent, id })
            })
            .collect()
    }

    /// This run's place among [`RunConfig::choices`].
    #[must_use]
    pub fn choice(&self) -> Choice {
        Choice {
            agent: self.agent(),
            id: self.env_id(),
        }
    }

    /// Plays `id`, one of the agent's Gymnasium ids; `false` (nothing changed) for another.
    pub fn set_env_id(&mut self, id: &str) -> bool {
        self.visit_mut(SetEnvId(id))
    }
}

struct KnobIds;

impl RunVisitor for KnobIds {
    type Output = Vec<&'static str>;

    fn visit<C: Tunable>(self, _: &C) -> Vec<&'static str> {
        C::KNOBS.iter().map(|k| k.id).collect()
    }
}

struct ReadKnob<'a>(&'a str);

impl RunVisitor for ReadKnob<'_> {
    type Output = Option<KnobValue>;

    fn visit<C: Tunable>(self, config: &C) -> Option<KnobValue> {
        knobs::find::<C>(self.0).map(|k| k.kind.read(config))
    }
}

struct Nudge<'a>(&'a str, bool);

impl RunVisitorMut for Nudge<'_> {
    type Output = bool;

    fn visit_mut<C: Tunable>(self, config: &mut C) -> bool {
        match knobs::find::<C>(self.0).map(|k| &k.kind) {
            Some(knobs::KnobKind::Value { nudge, .. }) => {
                nudge(config, self.1);
                true
            }
            _ => false,
        }
    }
}

struct EnvIds;

impl RunVisitor for EnvIds {
    type Output = &'static [&'static str];

    fn visit<C: Tunable>(self, _: &C) -> &'static [&'static str] {
        C::ENV_IDS
    }
}

struct SetEnvId<'a>(&'a str);

impl RunVisitorMut for SetEnvId<'_> {
    type Output = bool;

    fn visit_mut<C: Tunable>(self, config: &mut C) -> bool {
        config.set_env_id(self.0)
    }
}

struct NumEpisodes;

impl RunVisitor for NumEpisodes {
    type Output = usize;

    fn visit<C: Tunable>(self, config: &C) -> usize {
        config.num_episodes()
    }
}

struct Validate;

impl RunVisitor for Validate {
    type Output = Result<(), PpoError>;

    fn visit<C: Tunable>(self, config: &C) -> Result<(), PpoError> {
        config.validate()
    }
}

struct EnvId;

impl RunVisitor for EnvId {
    type Output = &'static str;

    fn visit<C: Tunable>(self, config: &C) -> &'static str {
        config.env_id()
    }
}

struct MaxReturn;

impl RunVisitor for MaxReturn {
    type Output = f64;

    fn visit<C: Tunable>(self, config: &C) -> f64 {
        config.max_return()
    }
}

struct FirstSnapshot {
    seed: u64,
    agent: AgentKind,
}

impl RunVisitor for FirstSnapshot {
    type Output = Snapshot;

    fn visit<C: Tunable>(self, config: &C) -> Snapshot
    where
        C::Agent: LiveAgent,
    {
        let (eps, gamma) = C::Agent::eps_gamma(config);
        Snapshot {
            hyper: C::Agent::hyper(config, self.seed),
            eps: eps as f32,
            gamma,
            latest: Latest::empty(self.agent),
            ..Snapshot::default()
        }
    }
}

/// Replays every case of a recorded PyTorch update of any agent: the agent whose weights
/// the first case's `weights_before` holds (the first agent, the seed's PPO, when none
/// claims them); `file` names it in errors. One result per case.
///
/// # Errors
/// [`PpoError::File`] for a file that is not JSON; as [`OnPolicyAgent::replay`] for one
/// that is not that agent's cases.
#[allow(clippy::type_complexity)]
pub fn replay_any(text: &str, file: &str) -> Result<Vec<Result<Replayed, PpoError>>, PpoError> {
    let weights = first_weights(text, file)?;
    let env = AgentKind::ALL
        .into_iter()
        .find(|env| RunConfig::default_for(*env).visit(Claims(&weights)))
        .unwrap_or_default();
    RunConfig::default_for(env).visit(Replay { text, file })
}

/// Whether an agent claims a replay file's weights.
struct Claims<'a>(&'a serde_json::Value);

impl RunVisitor for Claims<'_> {
    type Output = bool;

    fn visit<C: Tunable>(self, _config: &C) -> bool
    where
        C::Agent: LiveAgent,
    {
        C::Agent::replays(self.0)
    }
}

/// Replays a file as an agent's.
struct Replay<'a> {
    text: &'a str,
    file: &'a str,
}

impl RunVisitor for Replay<'_> {
    type Output = Result<Vec<Result<Replayed, PpoError>>, PpoError>;

    fn visit<C: Tunable>(self, _config: &C) -> Self::Output
    where
        C::Agent: LiveAgent,
    {
        C::Agent::replay(self.text, self.file)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip_and_specs_differ() {
        for env in AgentKind::ALL {
            assert_eq!(AgentKind::from_name(env.as_str()), Some(env));
            assert_eq!(RunConfig::default_for(env).agent(), env);
        }
        assert_eq!(AgentKind::from_name("Acrobot-v1"), None);
        assert_eq!(AgentKind::CartPole.format_return(500.0), "500");
        assert_eq!(AgentKind::Pendulum.format_return(-123.456), "-123.5");
    }

    #[test]
    fn the_config_serialises_as_its_agent_s() -> Result<(), serde_json::Error> {
        let config = RunConfig::default_for(AgentKind::Pendulum);
        assert_eq!(
            serde_json::to_value(&config)?,
            serde_json::to_value(PpoContinuousConfig::default())?
        );
        let bad = RunConfig::from(PpoConfig {
            gamma: 2.0,
            ..PpoConfig::default()
        });
        assert!(matches!(
            bad.validate(),
            Err(PpoError::InvalidConfig { field: "gamma", .. })
        ));
        assert_eq!(bad.num_episodes(), 500);
        Ok(())
    }

    #[test]
    fn knobs_and_choices_come_from_the_agents() {
        let ids: Vec<&str> = RunConfig::choices().iter().map(|c| c.id).collect();
        assert_eq!(ids, ["CartPole-v1", "CartPole-v0", "Pendulum-v1"]);
        for choice in RunConfig::choices() {
            let mut config = RunConfig::default_for(choice.agent);
            assert!(config.set_env_id(choice.id));
            assert_eq!(config.choice(), choice);
        }
        assert_eq!(RunConfig::all_knob_ids().len(), 16);
        for env in AgentKind::ALL {
            assert_eq!(
                env.index(),
                AgentKind::ALL.iter().position(|&e| e == env).unwrap_or(99)
            );
            let config = RunConfig::default_for(env);
            let ids = config.knob_ids();
            for (i, id) in ids.iter().enumerate() {
                assert!(!ids[..i].contains(id), "{id} twice");
            }
            assert_eq!(config.knob("seed"), Some(KnobValue::Seed));
            assert_eq!(config.knob("env"), Some(KnobValue::Environment));
        }
        assert_eq!(
            RunConfig::environments_with("no_clip"),
            [AgentKind::CartPole]
        );
        let mut pendulum = RunConfig::default_for(AgentKind::Pendulum);
        assert!(!pendulum.nudge("no_clip", true) && !pendulum.nudge("seed", true));
        assert!(pendulum.nudge("gamma", true));
        assert_eq!(
            pendulum.knob("gamma"),
            Some(KnobValue::Value("0.91".into()))
        );
        let mut configs = RunConfigs::defaults();
        configs.set(pendulum.clone());
        assert_eq!(configs[AgentKind::Pendulum], pendulum);
        assert_eq!(configs.get::<PpoConfig>(), Some(&PpoConfig::default()));
    }
}
