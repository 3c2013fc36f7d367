//! The clip lab (`x` on a lab step): the experiments started in this session, their
//! progress and results, and their panel in the live pane.

use std::collections::BTreeMap;

use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::widgets::Widget;

use super::{Message, panel};
use crate::i18n::t;
use crate::ppo::PpoConfig;
use crate::ppo::lab::Experiment;
use crate::tr;
use crate::tui::theme::Theme;
use crate::tui::widgets::lab::{Guess, LabPanel, LabState};

/// Seeds every clip-lab experiment runs in the app (as `ppo-tutor lab`'s default).
pub const LAB_SEEDS: [u64; 5] = [0, 1, 2, 3, 4];

/// The experiments started in this session.
#[derive(Debug, Clone, Default)]
pub struct Lab {
    /// Each experiment's state, once started.
    pub states: BTreeMap<Experiment, LabState>,
    /// An experiment to start, taken by the event loop (which runs it off the UI thread).
    pub request: Option<(Experiment, PpoConfig)>,
    /// The experiment whose step asks for the learner's prediction before it runs (`x`
    /// pressed, no letter yet).
    pub asking: Option<Experiment>,
}

impl Lab {
    /// The state of `experiment`, `None` before it starts.
    #[must_use]
    pub fn get(&self, experiment: &Experiment) -> Option<&LabState> {
        self.states.get(experiment)
    }

    /// Starts `experiment` from `base` (the step's, `None` on a step without one), unless
    /// it is running or done; says what happened. `lessons` are the numbers of the lessons
    /// with an experiment, named when there is none here.
    pub fn start(
        &mut self,
        experiment: Option<Experiment>,
        base: PpoConfig,
        lessons: &[u32],
    ) -> String {
        let Some(experiment) = experiment else {
            let list: Vec<String> = lessons.iter().map(ToString::to_string).collect();
            return tr!(
                "this step has no experiment to run (lessons {} have them)",
                "本节没有可运行的实验（第 {} 课里有）",
                list.join(t(", ", "、")),
            );
        };
        if matches!(
            self.states.get(&experiment),
            Some(LabState::Running { .. } | LabState::Done(_))
        ) {
            return tr!(
                "lab {}: already started in this session",
                "实验 {}：本次会话中已经启动过",
                experiment.name()
            );
        }
        let total = experiment.arms(&base).len() * LAB_SEEDS.len() * base.num_episodes;
        self.states
            .insert(experiment, LabState::Running { done: 0, total });
        self.request = Some((experiment, base));
        tr!(
            "lab {}: running on every core",
            "实验 {}：正在所有 CPU 核心上运行",
            experiment.name()
        )
    }

    /// Applies an experiment's progress or its end; its end is said.
    pub fn on_event(&mut self, experiment: Experiment, state: LabState) -> Option<Message> {
        let said = match &state {
            LabState::Done(_) => Some(Message::Info(tr!(
                "lab {}: done",
                "实验 {}：完成",
                experiment.name()
            ))),
            LabState::Failed(m) => Some(Message::Warning(tr!(
                "lab {}: {m}",
                "实验 {}：{m}",
                experiment.name()
            ))),
            LabState::Running { .. } => None,
        };
        self.states.insert(experiment, state);
        said
    }

    /// Draws `experiment`'s panel: what it will run from `base`, its progress, its result.
    pub fn render(
        &self,
        experiment: Experiment,
        base: &PpoConfig,
        guess: Guess,
        theme: Theme,
        area: Rect,
        buf: &mut Buffer,
    ) {
        LabPanel {
            guess,
            experiment,
            arms: experiment.arms(base).into_iter().map(|a| a.label).collect(),
            seeds: LAB_SEEDS.len(),
            episodes: base.num_episodes,
            state: self.states.get(&experiment),
            block: panel(
                &tr!("clip lab: {}", "截断实验室：{}", experiment.name()),
                theme,
            ),
            theme,
        }
        .render(area, buf);
    }
}
