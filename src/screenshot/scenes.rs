//! The screens the README shows, built as `tests/tui.rs` builds its snapshots: the app on a
//! real training session (seed 0, the seed's hyper-parameters), moved by its own keys, with
//! a real grading; every step is deterministic, so the same code gives the same screen.

use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::widgets::Widget as _;

use crate::grade::GradeOptions;
use crate::i18n::Lang;
use crate::lesson::{Course, Progress, Session};
use crate::ppo::PpoConfig;
use crate::tui::app::{App, Graded, TrainState};
use crate::tui::keys::Action;
use crate::tui::theme::Theme;
use crate::tui::ui::View;

/// The terminal's size in the pictures, the size `tests/tui.rs` snapshots.
pub const SIZE: (u16, u16) = (160, 50);

/// Episodes trained before the lesson and exercise pictures: the run the screen snapshots
/// of `tests/tui.rs` show (more episodes leave the clip chart's batch as close to r = 1).
const LESSON_EPISODES: usize = 3;

/// A learner's first try at lesson 8's exercise: GAE summed forwards, a catalogued
/// mistake the grader names.
const LEARNER_GAE: &str = "\
pub fn compute_advantage(gamma: f32, lmbda: f32, td_delta: &[f32]) -> Vec<f32> {
    let mut advantage = Vec::new();
    let mut adv = 0.0;
    for &delta in td_delta {
        adv = gamma * lmbda * adv + delta;
        advantage.push(adv);
    }
    advantage
}
";

/// One of the pictures' screens.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Scene {
    /// Lesson 11, step 3: the explanation, the code, the clip chart and live tensors.
    Lesson,
    /// Lesson 14, step 2: the seed's 500 episodes trained, the return plot.
    Training,
    /// Lesson 8's exercise panel: a hint and the grader's report on a wrong answer.
    Exercise,
}

impl Scene {
    /// Every scene, in the README's order.
    pub const ALL: [Scene; 3] = [Scene::Lesson, Scene::Training, Scene::Exercise];

    /// Its name in file names: `lesson`, `training`, `exercise`.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Scene::Lesson => "lesson",
            Scene::Training => "training",
            Scene::Exercise => "exercise",
        }
    }

    /// The app showing this scene, in the current language.
    ///
    /// # Errors
    /// The lessons cannot be loaded, training fails, or grading cannot run (no `rustc`).
    pub fn app(self) -> anyhow::Result<App> {
        let mut app = App::new(Course::embedded()?, Progress::default(), None);
        match self {
            Scene::Lesson => {
                app.show(Session::run(PpoConfig::default(), 0, LESSON_EPISODES)?);
                open(&mut app, "clipping", 3)?;
            }
            Scene::Training => {
                // What the worker sends after `t` has trained every episode of the run.
                open(&mut app, "training", 2)?;
                let config = PpoConfig::default();
                let episodes = config.num_episodes;
                app.show(Session::run(config, 0, episodes)?);
                app.run.train = TrainState::Finished;
            }
            Scene::Exercise => {
                app.show(Session::run(PpoConfig::default(), 0, LESSON_EPISODES)?);
                open(&mut app, "gae", 1)?;
                app.update(Action::Hint);
                app.update(Action::Grade);
                let names = app.exercise.request.take().unwrap_or_default();
                let options = GradeOptions::default();
                let mut graded = Vec::new();
                for name in names {
                    let exercise = crate::grade::find(&name)?;
                    let file = exercise.starter_path();
                    let result = exercise
                        .grade_source(LEARNER_GAE, &file, &options)
                        .map_err(|e| e.to_string());
                    graded.push(Graded { name, result });
                }
                app.on_graded(graded);
            }
        }
        Ok(app)
    }

    /// The scene drawn in `lang` at [`SIZE`], in colour.
    ///
    /// # Errors
    /// As [`Scene::app`].
    pub fn buffer(self, lang: Lang) -> anyhow::Result<Buffer> {
        let _lang = lang.scoped();
        let app = self.app()?;
        let area = Rect::new(0, 0, SIZE.0, SIZE.1);
        let mut buffer = Buffer::empty(area);
        (&View {
            app: &app,
            theme: Theme { color: true },
        })
            .render(area, &mut buffer);
        Ok(buffer)
    }
}

/// Opens step `step` (from 1) of lesson `id`: the lesson, as the lesson list opens it,
/// then → .
fn open(app: &mut App, id: &str, step: usize) -> anyhow::Result<()> {
    if !app.open_lesson(id) {
        anyhow::bail!(crate::tr!(
            "the course has no lesson `{id}` for the screenshots (src/screenshot/scenes.rs)",
            "课程里没有截图要用的课 `{id}`（src/screenshot/scenes.rs）"
        ));
    }
    for _ in 1..step {
        app.update(Action::Next);
    }
    Ok(())
}
