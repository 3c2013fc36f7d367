//! The live runs the app shows: the current environment's session (its latest snapshot,
//! its settings, training or paused) and the other environment's, set aside while its
//! lessons are not open. The worker thread owns the sessions themselves; this is what the
//! app knows of them, and the commands it sends ([`Run::outbox`]).

use crate::i18n::t;
use crate::lesson::{AgentKind, RunConfig, Snapshot};
use crate::ppo::PpoConfig;
use crate::run::{PerAgent, RunConfigs};
use crate::tr;

use super::worker::{Command, WorkerEvent};

/// A previous run's return curve, overlaid on the plot after a sandbox retrain.
#[derive(Debug, Clone, PartialEq)]
pub struct PreviousCurve {
    /// Whether the curve is the run's moving average (otherwise its raw returns).
    pub smoothed: bool,
    /// The curve: the run's moving average, or its returns when it had too few for one.
    pub values: Vec<f64>,
}

impl PreviousCurve {
    /// The legend in the current language, like `before (moving average)`.
    #[must_use]
    pub fn label(&self) -> String {
        if self.smoothed {
            t("before (moving average)", "之前（移动平均）").to_string()
        } else {
            t("before (returns)", "之前（回报）").to_string()
        }
    }
}

/// Whether the worker is training.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum TrainState {
    /// Waiting for `t` or `e`.
    #[default]
    Paused,
    /// Training episode after episode.
    Running,
    /// The configured number of episodes is done.
    Finished,
}

/// A run set aside when a lesson on the other environment opened: what the app showed of
/// it, to show again when the learner comes back.
#[derive(Debug, Clone)]
pub struct ParkedRun {
    /// Its latest snapshot.
    pub snapshot: Snapshot,
    /// Its seed.
    pub seed: u64,
    /// Paused or finished (a running one is paused when set aside).
    pub train: TrainState,
    /// The curve overlaid on its plot, if any.
    pub previous: Option<PreviousCurve>,
}

/// A return as the app prints it: CartPole's whole numbers as they are, Pendulum's to one
/// decimal.
#[must_use]
pub fn return_text(r: f64) -> String {
    if r.fract() == 0.0 {
        format!("{r}")
    } else {
        format!("{r:.1}")
    }
}

/// What the app knows of the live runs, and the commands for the worker.
#[derive(Debug)]
pub struct Run {
    /// Training state.
    pub train: TrainState,
    /// The live values after the latest episode, as the worker's session sent them.
    pub snapshot: Snapshot,
    /// The cart-pole animation's frame: an index into the latest episode's observations
    /// ([`Snapshot::observation`]).
    pub frame: usize,
    /// The previous run's curve, overlaid on the plot after a sandbox retrain.
    pub previous: Option<PreviousCurve>,
    /// Each other agent's run while its lessons are not open (the worker keeps its
    /// session), one slot per agent: browsing back continues it.
    pub parked: PerAgent<Option<ParkedRun>>,
    /// Hyper-parameters of each environment's run: the current one's, and the next one's
    /// on every other environment.
    pub configs: RunConfigs,
    /// The environment of the current run: the open lesson's.
    pub agent: AgentKind,
    /// Seed of the current run.
    pub seed: u64,
    /// Commands for the worker, taken and sent by the event loop.
    pub outbox: Vec<Command>,
    /// The number of the run shown: each reset or environment switch starts a new one, and
    /// the worker's events of an earlier one are dropped.
    pub id: u64,
}

impl Run {
    /// A fresh, paused run on `env` with the defaults (seed 0).
    #[must_use]
    pub fn new(env: AgentKind) -> Self {
        let configs = RunConfigs::defaults();
        let snapshot = configs[env].first_snapshot(0);
        Self {
            train: TrainState::Paused,
            snapshot,
            frame: 0,
            previous: None,
            parked: PerAgent::from_fn(|_| None),
            configs,
            agent: env,
            seed: 0,
            outbox: Vec::new(),
            id: 0,
        }
    }

    /// The current run's environment and settings, as the worker's session was started.
    #[must_use]
    pub fn config(&self) -> RunConfig {
        self.config_for(self.agent)
    }

    /// A run on `env` with that environment's settings in force.
    #[must_use]
    pub fn config_for(&self, env: AgentKind) -> RunConfig {
        self.configs[env].clone()
    }

    /// Hyper-parameters of the current CartPole run (or of the next one, in a Pendulum
    /// lesson): what the clip lab starts from and the clip chart's ε.
    #[must_use]
    pub fn cartpole(&self) -> PpoConfig {
        self.configs.get::<PpoConfig>().cloned().unwrap_or_default()
    }

    /// What the current run changes of its agent's defaults (the seed's settings, or the
    /// book's for Pendulum), each as `name value (default)`, and the seed when it is not 0:
    /// empty when the live agent runs the lessons' settings.
    #[must_use]
    pub fn changed_settings(&self) -> Vec<String> {
        use crate::ppo::knobs::KnobValue;
        let run = self.config();
        let defaults = RunConfig::default_for(run.agent());
        let mut changed = Vec::new();
        if run.env_id() != defaults.env_id() {
            changed.push(format!("env {} ({})", run.env_id(), defaults.env_id()));
        }
        for id in run.knob_ids() {
            if let (Some(KnobValue::Value(now)), Some(KnobValue::Value(was))) =
                (run.knob(id), defaults.knob(id))
                && now != was
            {
                changed.push(format!("{id} {now} ({was})"));
            }
        }
        if self.seed != 0 {
            changed.push(format!("seed {} (0)", self.seed));
        }
        changed
    }

    /// `t`: trains, pauses, or says that every episode is done.
    pub fn toggle(&mut self) -> String {
        match self.train {
            TrainState::Paused => {
                self.train = TrainState::Running;
                self.outbox.push(Command::Run);
                t("training…", "训练中……").into()
            }
            TrainState::Running => {
                self.train = TrainState::Paused;
                self.outbox.push(Command::Pause);
                t("paused", "已暂停").into()
            }
            TrainState::Finished => tr!(
                "all {} episodes done: r resets the agent, s opens the sandbox",
                "全部 {} 个回合已训练完：按 r 重置智能体，按 s 打开沙盒",
                self.config().num_episodes()
            ),
        }
    }

    /// `e`: one more episode, unless every episode is done.
    pub fn one_episode(&mut self) -> Option<String> {
        (self.train != TrainState::Finished).then(|| {
            self.train = TrainState::Paused;
            self.outbox.push(Command::OneEpisode);
            t("training one episode", "正在训练一个回合").into()
        })
    }

    /// A fresh agent with `config` and `seed`, training at once if `run`.
    pub fn reset(&mut self, config: RunConfig, seed: u64, run: bool) -> String {
        self.id += 1;
        self.outbox.push(Command::Reset {
            config: Box::new(config.clone()),
            seed,
            run: self.id,
        });
        self.show(config.first_snapshot(seed));
        self.agent = config.agent();
        self.configs.set(config);
        self.seed = seed;
        self.train = TrainState::Paused;
        if run {
            self.outbox.push(Command::Run);
            self.train = TrainState::Running;
        }
        tr!("fresh agent, seed {seed}", "新的智能体，随机种子 {seed}")
    }

    /// Retrains with `config` and `seed`, keeping the current run's curve on the plot for
    /// comparison.
    pub fn retrain(&mut self, config: RunConfig, seed: u64) -> String {
        let s = &self.snapshot;
        if !s.returns.is_empty() {
            let smoothed = !s.moving_average.is_empty();
            let values = if smoothed {
                s.moving_average.clone()
            } else {
                s.returns.clone()
            };
            self.previous = Some(PreviousCurve { smoothed, values });
        }
        self.reset(config, seed, true)
    }

    /// Applies one event from the training worker, and what to say of it: `Some((text,
    /// quiet))`, where a `quiet` message (an episode's return while paused) must not
    /// replace a warning.
    pub fn on_worker(&mut self, event: WorkerEvent) -> Option<(String, bool)> {
        match event {
            // What an earlier run sent before the worker read the reset or switch: the app
            // already shows the new run.
            WorkerEvent::Episode { run, .. }
            | WorkerEvent::Finished { run }
            | WorkerEvent::Error { run, .. }
                if run != self.id =>
            {
                None
            }
            WorkerEvent::Episode { snapshot, .. } => {
                self.show(*snapshot);
                let r = self.snapshot.returns.last()?;
                (self.train == TrainState::Paused).then(|| {
                    let said = tr!(
                        "episode {}: return {}",
                        "第 {} 回合：回报 {}",
                        self.snapshot.episodes,
                        return_text(*r)
                    );
                    (said, true)
                })
            }
            WorkerEvent::Finished { .. } => {
                self.train = TrainState::Finished;
                Some((
                    tr!(
                        "finished {} episodes",
                        "已训练完 {} 个回合",
                        self.snapshot.returns.len()
                    ),
                    false,
                ))
            }
            // The app said so when it asked (`reset`, `follow`); saying it again here would
            // overwrite what it said since ("a Pendulum-v1 lesson: …", "training…"). A
            // resumed run was shown when it was asked for.
            WorkerEvent::Reset { .. } | WorkerEvent::Resumed { .. } => None,
            WorkerEvent::Error { message, .. } => {
                self.train = TrainState::Paused;
                Some((
                    tr!("training stopped: {message}", "训练已停止：{message}"),
                    false,
                ))
            }
        }
    }

    /// Shows `snapshot` (from the worker's session) and restarts the cart-pole animation on
    /// its episode.
    pub fn show(&mut self, snapshot: Snapshot) {
        self.snapshot = snapshot;
        self.frame = 0;
    }

    /// Advances the cart-pole animation by one frame (called on each tick).
    pub fn tick(&mut self) {
        let frames = self.snapshot.observation_count();
        if frames > 0 {
            self.frame = (self.frame + 1) % frames;
        }
    }

    /// A lesson on `env` opened: if it is another agent's, that agent's run continues if
    /// one was set aside, else a fresh one starts there (paused), with that agent's settings
    /// in force; the run left behind is set aside in its agent's slot, not thrown away. Says
    /// which, when the agent changed.
    pub fn follow(&mut self, env: AgentKind) -> Option<String> {
        if env == self.agent {
            return None;
        }
        let config = self.config_for(env);
        self.id += 1;
        self.outbox.push(Command::Switch {
            config: Box::new(config.clone()),
            seed: self.seed,
            run: self.id,
        });
        let first = config.first_snapshot(self.seed);
        let left = ParkedRun {
            snapshot: std::mem::replace(&mut self.snapshot, first),
            seed: self.seed,
            train: match self.train {
                TrainState::Running => TrainState::Paused,
                other => other,
            },
            previous: self.previous.take(),
        };
        self.parked[self.agent] = Some(left);
        self.frame = 0;
        self.agent = env;
        self.train = TrainState::Paused;
        let said = match self.parked[env].take() {
            Some(back) => {
                let episodes = back.snapshot.episodes;
                self.show(back.snapshot);
                self.seed = back.seed;
                self.train = back.train;
                self.previous = back.previous;
                tr!(
                    "a {} lesson: its run continues after episode {episodes}, seed {} (t trains)",
                    "这是 {} 的课：接着之前的训练（已训练 {episodes} 个回合，随机种子 {}；t 训练）",
                    env.as_str(),
                    self.seed
                )
            }
            None => tr!(
                "a {} lesson: fresh agent, seed {} (t trains, e one episode)",
                "这是 {} 的课：新的智能体，随机种子 {}（t 训练，e 训练一个回合）",
                env.as_str(),
                self.seed
            ),
        };
        Some(said)
    }
}
