//! Lessons as data: the course the tutor, the headless commands and the notebooks share.
//!
//! A lesson is a folder `lessons/NN-slug/` holding `lesson.md`: TOML front matter
//! between `+++` lines (id, title, summary, one `[[steps]]` table per step naming the
//! seed's Python line, the Rust code anchor and the live values it shows), then a markdown
//! body split into steps by `## ` headings. A lesson with an exercise also holds its
//! starter, its reference solution and `exercise.toml`: one `[[exercise]]` per graded
//! function with the hints the learner reads and the grader's hint for each typical
//! mistake.
//! The folders are embedded in the binary, so an installed `ppo-tutor` works anywhere.
//!
//! - [`loader`]: parsing and validation ([`Course::embedded`]).
//! - [`anchor`]: Rust code pulled from `src/` by `// ANCHOR: name` markers.
//! - [`details`]: collapsible `<details>` blocks inside a step.
//! - [`face`]: passages for one face only, `<app>` (the terminal) or `<notebook>`.
//! - [`live`]: the live training [`Session`] and the [`Snapshot`] of named values it keeps
//!   up to date, episode by episode, for every face.
//! - [`progress`]: where the learner is, saved atomically.
//! - [`reveal`]: the code each exercise gives away, hidden until it is passed.

pub mod anchor;
pub mod details;
pub mod face;
pub mod files;
pub mod live;
pub mod loader;
pub mod progress;
pub mod quiz;
pub mod reveal;

pub use crate::run::{AgentKind, RunConfig};
pub use live::{Index, Mark, PolicyMap, Session, Snapshot, TensorView};
pub use loader::{Course, LessonError};
pub use progress::Progress;

/// One lesson: a folder of `lessons/`.
#[derive(Debug, Clone, PartialEq)]
pub struct Lesson {
    /// The stable id (the folder name without its `NN-` prefix), e.g. `td-target`.
    pub id: String,
    /// The title shown in lists and headers.
    pub title: String,
    /// One sentence for the lesson list.
    pub summary: String,
    /// The position in the course, from the folder's `NN-` prefix.
    pub order: u32,
    /// The steps, in order.
    pub steps: Vec<Step>,
    /// The exercise the learner writes in this lesson, if any.
    pub exercise: Option<Exercise>,
    /// The check-your-understanding questions asked after the last step
    /// (`quiz.toml`).
    pub quiz: Vec<quiz::Question>,
    /// The environment whose live run the lesson shows (front matter `env`, by default
    /// CartPole-v1).
    pub env: AgentKind,
}

/// One step of a lesson: an explanation, the code that runs, and live values.
#[derive(Debug, Clone, PartialEq)]
pub struct Step {
    /// The step's heading.
    pub title: String,
    /// The seed's Python line(s) this step explains (may be empty).
    pub python: String,
    /// The anchor name of the Rust code shown (may be empty).
    pub code: String,
    /// Live values and views shown beside the text (`td_target`, `plot`, ...).
    pub show: Vec<String>,
    /// The explanation, in markdown, with the passages of both faces: read it through
    /// [`Step::text`].
    pub body: String,
    /// The clip-lab experiment this step runs (shown by the `lab` view), if any.
    pub lab: Option<crate::ppo::lab::Experiment>,
    /// What the learner predicts before the step's experiment runs (`predict = "..."`):
    /// the text after [`AFTER_THE_RUN`] stays hidden until the prediction is made.
    pub predict: Option<crate::ppo::lab::Outcome>,
}

/// The line that splits a lab step's text: what comes after it is what the run found, which
/// the app shows once the learner has committed to a prediction and a notebook puts after
/// the experiment's cells.
pub const AFTER_THE_RUN: &str = "<!-- after the run -->";

impl Step {
    /// The explanation as `face` reads it: the `<app>` or `<notebook>` passages of that
    /// face kept (without their tags), the other face's dropped (see [`face`]). The
    /// [`AFTER_THE_RUN`] line is dropped; the text on both sides of it is kept.
    #[must_use]
    pub fn text(&self, face: face::Face) -> String {
        let (before, after) = self.parts(face);
        match after {
            Some(after) => format!("{before}{after}"),
            None => before,
        }
    }

    /// The explanation split at its [`AFTER_THE_RUN`] line: the text before it, and the
    /// text after it without its leading blank lines (`None` for a step without the line).
    #[must_use]
    pub fn parts(&self, face: face::Face) -> (String, Option<String>) {
        let text = face::text(&self.body, face);
        let mut before = String::new();
        let mut after: Option<String> = None;
        for line in text.split_inclusive('\n') {
            if line.trim_end() == AFTER_THE_RUN && after.is_none() {
                after = Some(String::new());
                continue;
            }
            match after.as_mut() {
                Some(a) if a.is_empty() && line.trim().is_empty() => {}
                Some(a) => a.push_str(line),
                None => before.push_str(line),
            }
        }
        (before, after)
    }
}

/// The exercise attached to a lesson, as the tutor presents it (from `exercise.toml`).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Exercise {
    /// The function the learner writes (also the name on the command line).
    pub name: String,
    /// Further functions graded in the same lesson, e.g. `td_delta` (in the same starter
    /// file) or `ppo_losses` (on candle tensors, in its own `exercise_candle.rs`).
    pub also: Vec<String>,
    /// Hints, from gentle to nearly the answer.
    pub hints: Vec<String>,
    /// The idea each function tests, in the order of [`Exercise::names`] (shown once the
    /// lesson's exercise is passed).
    pub ideas: Vec<String>,
}

impl Exercise {
    /// Every function graded in the lesson: `name`, then `also`.
    #[must_use]
    pub fn names(&self) -> Vec<&str> {
        std::iter::once(self.name.as_str())
            .chain(self.also.iter().map(String::as_str))
            .collect()
    }
}

/// A view a step can show instead of a tensor, by the name a lesson's `show` list gives it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum View {
    /// `plot`: the return curve and its moving average.
    Plot,
    /// `cartpole`: the cart and pole through the latest episode.
    CartPole,
    /// `clip_chart`: `L^CLIP` against the ratio over the latest update's last epoch.
    ClipChart,
    /// `lab`: the step's experiment over seeds.
    Lab,
    /// `pendulum`: the pendulum through the latest episode.
    Pendulum,
    /// `trust_region`: the trust-region probe of the latest batch
    /// ([`crate::lesson::live::probe::probe_snapshot`]), measured when the step opens.
    TrustRegion,
}

impl View {
    /// Every view, in the order [`VIEWS`] names them.
    pub const ALL: [View; 6] = [
        View::Plot,
        View::CartPole,
        View::ClipChart,
        View::Lab,
        View::Pendulum,
        View::TrustRegion,
    ];

    /// The name a lesson's `show` list gives the view.
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            View::Plot => "plot",
            View::CartPole => "cartpole",
            View::ClipChart => "clip_chart",
            View::Lab => "lab",
            View::Pendulum => "pendulum",
            View::TrustRegion => "trust_region",
        }
    }

    /// The view called `name`, if there is one.
    #[must_use]
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|v| v.name() == name)
    }

    /// The agent whose runs the view draws, `None` for a view of every run (the plot).
    #[must_use]
    pub const fn agent(self) -> Option<AgentKind> {
        match self {
            View::Plot => None,
            View::CartPole | View::ClipChart | View::Lab | View::TrustRegion => {
                Some(AgentKind::CartPole)
            }
            View::Pendulum => Some(AgentKind::Pendulum),
        }
    }
}

/// The names of the views ([`View::name`]), for checking a `show` list.
pub const VIEWS: [&str; View::ALL.len()] = {
    let mut names = [""; View::ALL.len()];
    let mut i = 0;
    while i < View::ALL.len() {
        names[i] = View::ALL[i].name();
        i += 1;
    }
    names
};

#[cfg(test)]
mod tests {
    use super::*;

    fn step(body: &str) -> Step {
        Step {
            title: "A".into(),
            python: String::new(),
            code: String::new(),
            show: Vec::new(),
            body: body.into(),
            lab: None,
            predict: None,
        }
    }

    #[test]
    fn the_text_after_the_run_starts_at_its_first_line_of_text() {
        let s = step("Predict.\n\n<!-- after the run -->\n\n\n- found 1\n\n- found 2\n");
        let (before, after) = s.parts(face::Face::Notebook);
        assert_eq!(before, "Predict.\n\n");
        assert_eq!(after.as_deref(), Some("- found 1\n\n- found 2"));
        assert_eq!(
            s.text(face::Face::Terminal),
            "Predict.\n\n- found 1\n\n- found 2"
        );
        assert_eq!(step("No marker.\n").parts(face::Face::Notebook).1, None);
    }
}
