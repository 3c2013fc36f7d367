//! The app: what it shares (the course, the live run, the progress, the status line) and
//! the routing of every key to the face that is open. Each face owns its state, its keys
//! and its drawing (`super::components`); `update` hands the action to the open one and
//! applies its [`Reply`].

use std::path::PathBuf;

use crate::i18n::{Lang, LangGuard, t};
use crate::lesson::{AgentKind, Course, Lesson, Progress, RunConfig, Snapshot, Step};
use crate::ppo::PpoConfig;
use crate::ppo::lab::Experiment;

use super::components::exercise::{self, ExercisePanel};
use super::components::explanation::Explanation;
use super::components::help::Help;
use super::components::lab::Lab;
use super::components::lessons::LessonList;
use super::components::quiz::Quiz;
use super::components::sandbox::Sandbox;
use super::components::{Component, Ctx, Owner, Reply, Status};
use super::keys::Action;
use super::widgets::lab::LabState;
use super::worker::{Command, WorkerEvent};

pub use super::components::Message;
pub use super::components::exercise::Graded;
pub use super::components::lab::LAB_SEEDS;
pub use super::run::{ParkedRun, PreviousCurve, Run, TrainState, return_text};

/// Which face covers the lesson, if any (each face's state is its component in [`App`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Overlay {
    /// None: the lesson step.
    #[default]
    None,
    /// The key map ([`App::help`]).
    Help,
    /// The lesson list ([`App::lesson_list`]).
    Lessons,
    /// The sandbox ([`App::sandbox`]).
    Sandbox,
    /// The exercise panel ([`App::exercise`]).
    Exercise,
    /// The open lesson's quiz, after its last step ([`App::quiz`]).
    Quiz,
}

impl Overlay {
    /// The owner of the status messages this face sets.
    #[must_use]
    pub fn owner(self) -> Owner {
        match self {
            Self::None | Self::Help => Owner::App,
            Self::Lessons => Owner::Lessons,
            Self::Sandbox => Owner::Sandbox,
            Self::Exercise => Owner::Exercise,
            Self::Quiz => Owner::Quiz,
        }
    }
}

/// Everything the app shows and remembers.
#[derive(Debug)]
pub struct App {
    /// The course.
    pub course: Course,
    /// Current lesson index.
    pub lesson: usize,
    /// Current step index within the lesson.
    pub step: usize,
    /// The step's explanation: its scroll and details blocks.
    pub explanation: Explanation,
    /// Scroll offset of the live tensors.
    pub tensor_scroll: usize,
    /// The first column of the live tables shown (after the step column), `<`/`>`.
    pub tensor_hscroll: usize,
    /// How the latest drawing showed the live tables' rows: a page for PgDn/PgUp, and the
    /// last useful scroll for End.
    pub tensor_rows: std::cell::Cell<super::widgets::tensors::Rows>,
    /// The first line of the code pane shown (`[`/`]`).
    pub code_scroll: usize,
    /// The largest useful [`App::code_scroll`], as the latest drawing measured it.
    pub code_max: std::cell::Cell<usize>,
    /// The open face.
    pub overlay: Overlay,
    /// The key map.
    pub help: Help,
    /// The lesson list.
    pub lesson_list: LessonList,
    /// The sandbox's settings being edited.
    pub sandbox: Sandbox,
    /// The open lesson's exercise: grading, hints, the panel.
    pub exercise: ExercisePanel,
    /// The open quiz question and its answer.
    pub quiz: Quiz,
    /// The clip-lab experiments started in this session.
    pub lab: Lab,
    /// The trust-region probe of the latest batch, for steps that show `trust_region`.
    pub probe: Probe,
    /// The live runs: the current environment's and the one set aside.
    pub run: Run,
    /// The one-line status message (warnings, errors, confirmations) and who set it.
    pub status: Status,
    /// Saved progress.
    pub progress: Progress,
    /// Where progress is saved (`None` in tests).
    pub progress_path: Option<PathBuf>,
    /// Set when the app should exit.
    pub quit: bool,
    /// The learner was told the progress cannot be saved: the next `q` quits anyway.
    quit_unsaved: bool,
    /// Whether the terminal is smaller than the layout needs: keys but `q` wait until it
    /// is enlarged (the screen says so).
    pub too_small: bool,
    /// The signal that ended the app, if one did (SIGTERM, SIGHUP, SIGINT).
    pub signal: Option<i32>,
    /// Whether the language key switches only this thread's language (tests, which render
    /// both languages on parallel threads) rather than the whole process's (the app).
    pub thread_language: bool,
    /// This thread's language while [`App::thread_language`] switched it.
    language_guard: Option<LangGuard>,
}

/// What the faces read of `app` (a macro, not a method, so that a face borrowed mutably
/// beside it is a disjoint field).
macro_rules! ctx {
    ($app:expr) => {{
        let lesson = $app.course.lessons.get($app.lesson);
        Ctx {
            course: &$app.course,
            lesson,
            step: lesson.and_then(|l| l.steps.get($app.step)),
            progress: &$app.progress,
            snapshot: &$app.run.snapshot,
            results_open: $app.results_open(),
        }
    }};
}

impl App {
    /// A new app at the saved position (or the first step).
    #[must_use]
    pub fn new(course: Course, mut progress: Progress, progress_path: Option<PathBuf>) -> Self {
        // Lessons, questions and exercises the course no longer has are not counted done,
        // and a lesson that is gone does not open another at its step number.
        progress.retain_known(&course, Some(&crate::grade::exercise_names()));
        let lesson = course.index_of(&progress.lesson).unwrap_or(0);
        let steps = course.lessons.get(lesson).map_or(1, |l| l.steps.len());
        let step = progress.step.min(steps.saturating_sub(1));
        let env = course
            .lessons
            .get(lesson)
            .map_or_else(AgentKind::default, |l| l.env);
        let run = Run::new(env);
        Self {
            course,
            lesson,
            step,
            explanation: Explanation::default(),
            tensor_scroll: 0,
            tensor_hscroll: 0,
            tensor_rows: std::cell::Cell::default(),
            code_scroll: 0,
            code_max: std::cell::Cell::new(0),
            overlay: Overlay::None,
            help: Help::default(),
            lesson_list: LessonList::default(),
            sandbox: Sandbox::default(),
            exercise: ExercisePanel::default(),
            quiz: Quiz::default(),
            lab: Lab::default(),
            probe: Probe::None,
            run,
            status: Status::default(),
            progress,
            progress_path,
            quit: false,
            quit_unsaved: false,
            too_small: false,
            signal: None,
            thread_language: false,
            language_guard: None,
        }
    }

    /// Sets the status line on behalf of the lesson view and the run.
    pub fn say(&mut self, text: impl Into<String>) {
        self.status.set(Owner::App, text);
    }

    /// Shows a warning on the status line (`warning: ` and `text`), kept until it is read.
    pub fn warn(&mut self, text: &str) {
        self.status.warn(Owner::App, text);
    }

    /// Switches the language live (the `L` key): English ⇄ 中文. The course is reloaded in
    /// the new language at the same lesson, step and overlay; an answer being typed and
    /// the verdict shown are cleared (they were written in the old language).
    pub fn switch_language(&mut self) {
        let next = Lang::current().other();
        if self.thread_language {
            // Dropping this app's own override first restores the thread's language as it
            // was before; a new override is only needed when that is not `next`.
            self.language_guard = None;
            if Lang::current() != next {
                self.language_guard = Some(next.scoped());
            }
        } else {
            next.set_current();
        }
        match Course::embedded() {
            Ok(course) => {
                let (lesson, step) = (self.lesson, self.step);
                self.course = course;
                self.lesson = lesson.min(self.course.lessons.len().saturating_sub(1));
                let steps = self.current_lesson().map_or(1, |l| l.steps.len());
                self.step = step.min(steps.saturating_sub(1));
                let quiz = self.current_lesson().map_or(0, |l| l.quiz.len());
                if self.overlay == Overlay::Quiz && self.quiz.question() >= quiz {
                    self.overlay = Overlay::None;
                }
                let lessons = self.course.lessons.len();
                if self.lesson_list.selected >= lessons {
                    self.lesson_list.open(self.lesson);
                }
                self.quiz.clear_answer();
                // Kept for the next start (unless `--lang` or PPO_TUTOR_LANG says otherwise).
                self.progress.set_language(next);
                let saved = self.save_progress();
                if saved.is_ok() {
                    self.status.set(
                        self.overlay.owner(),
                        crate::tr!("language: {}", "语言：{}", next.name()),
                    );
                }
            }
            Err(e) => {
                self.warn(&crate::tr!(
                    "could not load the lessons in {}: {e}",
                    "无法加载{}课程：{e}",
                    next.name()
                ));
            }
        }
    }

    /// The open lesson.
    #[must_use]
    pub fn current_lesson(&self) -> Option<&Lesson> {
        self.course.lessons.get(self.lesson)
    }

    /// The open step.
    #[must_use]
    pub fn current_step(&self) -> Option<&Step> {
        self.current_lesson()?.steps.get(self.step)
    }

    /// What the faces read of the app.
    #[must_use]
    pub fn ctx(&self) -> Ctx<'_> {
        ctx!(self)
    }

    /// Steps seen before the current one over the whole course, and the total.
    #[must_use]
    pub fn position(&self) -> (usize, usize) {
        let before: usize = self.course.lessons[..self.lesson.min(self.course.lessons.len())]
            .iter()
            .map(|l| l.steps.len())
            .sum();
        (before + self.step + 1, self.course.total_steps())
    }

    /// Applies one action from the keyboard or mouse: the open face answers it, the app
    /// applies the reply.
    pub fn update(&mut self, action: Action) {
        if action == Action::Language {
            // Over every overlay: the same screen, in the other language.
            self.switch_language();
            return;
        }
        let open = self.overlay;
        let ctx = ctx!(self);
        let reply = match open {
            Overlay::None => self.explanation.handle(action, &ctx),
            Overlay::Help => self.help.handle(action, &ctx),
            Overlay::Lessons => self.lesson_list.handle(action, &ctx),
            Overlay::Sandbox => self.sandbox.handle(action, &ctx),
            Overlay::Exercise => self.exercise.handle(action, &ctx),
            Overlay::Quiz => self.quiz.handle(action, &ctx),
        };
        self.apply(open, reply);
    }

    /// Applies what the face `from` replied.
    fn apply(&mut self, from: Overlay, reply: Reply) {
        let owner = from.owner();
        match reply {
            Reply::Stay => {}
            Reply::Say(text) => self.status.set(owner, text),
            Reply::Close => self.close(from),
            Reply::Pass(action) => self.update_main(action),
            Reply::Quit => self.quit(),
            Reply::Open(lesson) => {
                self.close(from);
                self.go_to(lesson, 0);
            }
            Reply::Retrain => {
                self.close(from);
                let said = self
                    .run
                    .retrain(self.sandbox.run_config(), self.sandbox.seed);
                let changed = self.run.changed_settings();
                if changed.is_empty() {
                    self.say(crate::tr!(
                        "{said}, with the lessons' settings",
                        "{said}，用的是课程里的设置"
                    ));
                } else {
                    self.say(crate::tr!(
                        "{said}, not the lessons' settings: {} (the lessons' value in brackets); the lessons' figures are for theirs",
                        "{said}，不是课程里的设置：{}；括号里是课程用的值，课程里的数字对应课程的设置",
                        changed.join(", ")
                    ));
                }
            }
            Reply::Answered(i, verdict, answer) => self.record_answer(i, verdict.right, &answer),
            Reply::Finished => {
                self.close(from);
                self.leave_lesson();
            }
        }
    }

    /// Closes the face `which` (if open), and the status messages it set.
    fn close(&mut self, which: Overlay) {
        if self.overlay == which {
            self.overlay = Overlay::None;
        }
        self.status.close(which.owner());
    }

    /// Opens the face `which` over the lesson (closing the one open, and its messages).
    fn open(&mut self, which: Overlay) {
        if self.overlay != which {
            self.close(self.overlay);
            self.overlay = which;
        }
    }

    /// Whether the open step's experiment is waiting for the learner's prediction (its
    /// choice letters are then typed, not mapped to the lesson view's keys).
    #[must_use]
    pub fn asking_prediction(&self) -> bool {
        self.lab.asking.is_some() && self.lab.asking == self.current_step().and_then(|s| s.lab)
    }

    /// The prediction recorded for `experiment`: `Some(Some(i))` the learner chose arm `i`,
    /// `Some(None)` it ran without one, `None` not asked yet.
    #[must_use]
    pub fn prediction(&self, experiment: crate::ppo::lab::Experiment) -> Option<Option<usize>> {
        let letter = self.progress.predictions.get(experiment.name())?;
        let arms = experiment.arms(&self.lab_base()).len();
        Some(
            letter
                .chars()
                .next()
                .and_then(|c| crate::ppo::lab::choice_index(c, arms)),
        )
    }

    /// Whether the open step shows what its experiment's run found: always, unless it asks
    /// for a prediction the learner has not made yet.
    #[must_use]
    pub fn results_open(&self) -> bool {
        match self.current_step().map(|s| (s.lab, s.predict)) {
            Some((Some(e), Some(_))) => self.prediction(e).is_some(),
            _ => true,
        }
    }

    /// A key while the open step asks for a prediction: a choice letter records it and
    /// starts the run, Esc starts it without one; `false` for any other key (the
    /// question stays open).
    fn answer_prediction(&mut self, action: Action) -> bool {
        let Some(experiment) = self.lab.asking.filter(|_| self.asking_prediction()) else {
            return false;
        };
        let arms = experiment.arms(&self.lab_base()).len();
        let letter = match action {
            Action::Type(c) => {
                if crate::ppo::lab::choice_index(c, arms).is_none() {
                    let last = crate::ppo::lab::letters()
                        .nth(arms.saturating_sub(1))
                        .unwrap_or('a');
                    self.say(crate::tr!(
                        "choose a letter from a to {last} (Esc runs it without a prediction)",
                        "请在 a 到 {last} 之间选一个字母（按 Esc 则不预测直接运行）"
                    ));
                    return true;
                }
                c.to_string()
            }
            Action::Back => String::new(),
            _ => return false,
        };
        self.lab.asking = None;
        self.progress
            .predictions
            .insert(experiment.name().to_string(), letter);
        let _ = self.save_progress();
        let said = self.lab.start(Some(experiment), self.lab_base(), &[]);
        self.say(said);
        true
    }

    /// The lesson view's keys (no face open, or a key the open face passed on).
    fn update_main(&mut self, action: Action) {
        if self.answer_prediction(action) {
            return;
        }
        match action {
            Action::Quit => self.quit(),
            Action::Next => self.next_step(),
            Action::Prev => self.prev_step(),
            Action::TensorDown => self.scroll_tensors(1, true),
            Action::TensorUp => self.scroll_tensors(1, false),
            Action::TensorPageDown => self.scroll_tensors(self.tensor_page(), true),
            Action::TensorPageUp => self.scroll_tensors(self.tensor_page(), false),
            Action::TensorFirst => self.tensor_scroll = 0,
            Action::TensorLast => self.tensor_scroll = self.max_tensor_scroll(),
            Action::CodeDown => {
                self.code_scroll = (self.code_scroll + 1).min(self.code_max.get());
            }
            Action::CodeUp => self.code_scroll = self.code_scroll.saturating_sub(1),
            Action::TensorRight => {
                let last = self.current_step().map_or(0, |s| {
                    super::widgets::tensors::max_hscroll(&self.run.snapshot, &s.show)
                });
                self.tensor_hscroll = self.tensor_hscroll.saturating_add(1).min(last);
            }
            Action::TensorLeft => self.tensor_hscroll = self.tensor_hscroll.saturating_sub(1),
            Action::Lessons => {
                self.lesson_list.open(self.lesson);
                self.open(Overlay::Lessons);
            }
            Action::Help => self.open(Overlay::Help),
            Action::Sandbox => {
                self.sandbox = Sandbox::for_run(
                    self.run.config(),
                    self.run.config_for(AgentKind::default()),
                    self.run.seed,
                );
                self.open(Overlay::Sandbox);
            }
            Action::TrainToggle => {
                let said = self.run.toggle();
                self.say(said);
            }
            Action::OneEpisode => {
                if let Some(said) = self.run.one_episode() {
                    self.say(said);
                }
            }
            Action::ResetAgent => {
                let said = self.run.reset(self.run.config(), self.run.seed, false);
                self.say(said);
            }
            Action::Grade => self.request_grade(),
            Action::Hint => self.reveal_hint(),
            Action::RunLab => {
                let step = self.current_step();
                let experiment = step.and_then(|s| s.lab);
                if let (Some(e), Some(_)) = (experiment, step.and_then(|s| s.predict))
                    && !self.progress.predictions.contains_key(e.name())
                    && self.lab.get(&e).is_none()
                {
                    self.lab.asking = Some(e);
                    self.say(t(
                        "predict first: press the letter of your answer; Esc runs it without a prediction",
                        "先预测：按下答案的字母；按 Esc 则不预测直接运行",
                    ));
                    return;
                }
                let lessons: Vec<u32> = self
                    .course
                    .lessons
                    .iter()
                    .filter(|l| l.steps.iter().any(|s| s.lab.is_some()))
                    .map(|l| l.order)
                    .collect();
                let said = self.lab.start(experiment, self.lab_base(), &lessons);
                self.say(said);
            }
            Action::ScrollDown
            | Action::ScrollUp
            | Action::Details
            | Action::Back
            | Action::Enter
            | Action::Up
            | Action::Down
            | Action::Increase
            | Action::Decrease
            | Action::Type(_)
            | Action::Erase
            | Action::Language => {}
        }
    }

    /// The largest useful [`App::tensor_scroll`] on the open step, as last drawn: the first
    /// row of its longest table's last page.
    #[must_use]
    pub fn max_tensor_scroll(&self) -> usize {
        self.tensor_rows.get().last_start
    }

    /// What PgDn/PgUp move: the rows a table with hidden rows showed, less one kept for
    /// context.
    fn tensor_page(&self) -> usize {
        self.tensor_rows.get().shown.saturating_sub(1).max(1)
    }

    /// Moves the live tables' rows by `rows`, down or up, within the longest table.
    fn scroll_tensors(&mut self, rows: usize, down: bool) {
        let last = self.max_tensor_scroll();
        let from = self.tensor_scroll.min(last);
        self.tensor_scroll = if down {
            from.saturating_add(rows).min(last)
        } else {
            from.saturating_sub(rows)
        };
    }

    /// Question `i` of the open lesson's quiz.
    #[must_use]
    pub fn quiz_question(&self, i: usize) -> Option<&crate::lesson::quiz::Question> {
        self.current_lesson()?.quiz.get(i)
    }

    /// Whether the live values are hidden behind the open quiz question: it asks for a
    /// number of the run (a prediction, or a choice the run decides) and has no answer yet.
    #[must_use]
    pub fn live_hidden(&self) -> bool {
        self.overlay == Overlay::Quiz
            && !self.quiz.answered()
            && self
                .quiz_question(self.quiz.question())
                .is_some_and(crate::lesson::quiz::Question::uses_the_run)
    }

    /// `(answered, right, total)` over the whole course's quizzes.
    #[must_use]
    pub fn quiz_score(&self) -> (usize, usize, usize) {
        let total = self.course.lessons.iter().map(|l| l.quiz.len()).sum();
        let (answered, right) = self.progress.quiz_score();
        (answered, right, total)
    }

    /// Opens question `i` of the open lesson's quiz.
    fn open_question(&mut self, i: usize) {
        let said = self.quiz.open(i, &ctx!(self));
        self.open(Overlay::Quiz);
        self.status.set(Owner::Quiz, said);
    }

    /// Records an answer to question `i` (from 0) of the open lesson's quiz (the first
    /// one counts), marks the lesson done once every question has one, and says the score.
    fn record_answer(&mut self, i: usize, right: bool, answer: &str) {
        let id = self
            .current_lesson()
            .map(|l| l.id.clone())
            .unwrap_or_default();
        self.progress.record_quiz(&id, i + 1, right);
        self.progress.record_answer(&id, i + 1, answer);
        let questions = self.current_lesson().map_or(0, |l| l.quiz.len());
        if self.progress.quiz_answered(&id, questions) {
            self.progress.lessons_done.insert(id);
        }
        let _ = self.save_progress();
        let (answered, right_total, total) = self.quiz_score();
        self.status.set(
            Owner::Quiz,
            crate::tr!(
                "{} · quiz {right_total} right of {answered} answered ({total} questions) · n next",
                "{} · 小测验已答 {answered} 题，答对 {right_total} 题（共 {total} 题）· n 下一题",
                if right {
                    t("right", "答对了")
                } else {
                    t("not quite", "不太对")
                }
            ),
        );
    }

    /// The function names the open lesson grades (empty without an exercise).
    #[must_use]
    pub fn exercise_names(&self) -> Vec<String> {
        exercise::names(self.current_lesson())
    }

    /// Whether every function of the open lesson's exercise has passed (then its reference
    /// solution may be shown).
    #[must_use]
    pub fn exercise_done(&self) -> bool {
        exercise::done(self.current_lesson(), &self.progress)
    }

    /// The open lesson's exercise files, as `ppo-tutor grade` finds them (relative to the
    /// current folder), each once.
    #[must_use]
    pub fn exercise_files(&self) -> Vec<PathBuf> {
        exercise::files(self.current_lesson())
    }

    /// An exercise file of the open lesson was saved: grade it (after the grading under
    /// way, if any), as `g` does.
    pub fn on_saved(&mut self) {
        if self.exercise_names().is_empty() {
            return;
        }
        if self.exercise.grading {
            self.exercise.regrade = true;
            return;
        }
        self.request_grade();
        let said = crate::tr!("saved: {}", "已保存：{}", self.status);
        self.status.set(Owner::Exercise, said);
    }

    fn request_grade(&mut self) {
        let names = self.exercise_names();
        if names.is_empty() {
            self.say(t(
                "this lesson has no exercise to grade",
                "本课没有要评分的练习",
            ));
            return;
        }
        self.open(Overlay::Exercise);
        let said = self.exercise.request_grade(names);
        self.status.set(Owner::Exercise, said);
    }

    fn reveal_hint(&mut self) {
        let Some(total) = self
            .current_lesson()
            .and_then(|l| l.exercise.as_ref())
            .map(|e| e.hints.len())
        else {
            self.say(t("this lesson has no exercise", "本课没有练习"));
            return;
        };
        self.open(Overlay::Exercise);
        let said = self.exercise.reveal_hint(total);
        self.status.set(Owner::Exercise, said);
    }

    /// What the clip-lab experiments start from in the app: the seed's settings, with the
    /// episode count of the current run.
    #[must_use]
    pub fn lab_base(&self) -> PpoConfig {
        PpoConfig {
            num_episodes: self.run.cartpole().num_episodes,
            ..PpoConfig::default()
        }
    }

    /// The episode count whose batch the open step's trust-region view should be measured
    /// on, when it is not measured or being measured yet (`None` otherwise).
    #[must_use]
    pub fn wants_probe(&self) -> Option<usize> {
        let shows = self.current_step().is_some_and(|s| {
            s.show
                .iter()
                .any(|v| v == crate::lesson::View::TrustRegion.name())
        });
        let s = &self.run.snapshot;
        if !shows || s.cartpole_update().is_none() {
            return None;
        }
        let episodes = s.episodes;
        match &self.probe {
            Probe::Measuring(_) => None,
            Probe::Done(e, _) if *e == episodes => None,
            _ => Some(episodes),
        }
    }

    /// Keeps a finished trust-region probe.
    pub fn on_probe(
        &mut self,
        episodes: usize,
        result: Result<Box<crate::ppo::trust_region::TrustRegionProbe>, String>,
    ) {
        self.probe = Probe::Done(episodes, result);
    }

    /// Applies an experiment's progress or its end.
    pub fn on_lab(&mut self, experiment: Experiment, state: LabState) {
        if let Some(said) = self.lab.on_event(experiment, state) {
            self.status.say(Owner::App, said);
        }
    }

    /// Shows what the grading under way is doing (its build, cargo's progress through it,
    /// its checks) in the exercise panel and on the status line.
    pub fn on_grade_progress(&mut self, progress: crate::grade::GradeProgress) {
        if self.exercise.grading {
            self.status.set(Owner::Exercise, progress.to_string());
            self.exercise.progress = Some(progress);
        }
    }

    /// Applies a finished grading: shows it, and records passed exercises in the progress.
    pub fn on_graded(&mut self, graded: impl IntoIterator<Item = impl Into<Graded>>) {
        let graded: Vec<Graded> = graded.into_iter().map(Into::into).collect();
        let said = self.exercise.on_graded(graded, &mut self.progress);
        self.status.set(Owner::Exercise, said);
        let _ = self.save_progress();
        if std::mem::take(&mut self.exercise.regrade) {
            self.request_grade();
        }
    }

    /// The current run's environment and settings, as the worker's session was started.
    #[must_use]
    pub fn run_config(&self) -> RunConfig {
        self.run.config()
    }

    /// Applies one event from the training worker (an episode's return does not replace
    /// a warning).
    pub fn on_worker(&mut self, event: WorkerEvent) {
        if let Some((said, quiet)) = self.run.on_worker(event)
            && !(quiet && self.status.is_warning())
        {
            self.say(said);
        }
    }

    /// Shows `snapshot` (from the worker's session) and restarts the animation on it.
    pub fn show(&mut self, snapshot: Snapshot) {
        self.run.show(snapshot);
        if self.overlay == Overlay::Quiz {
            let question = self
                .course
                .lessons
                .get(self.lesson)
                .and_then(|l| l.quiz.get(self.quiz.question()));
            self.quiz.offer(question, &self.run.snapshot);
        }
    }

    /// Advances the animation by one frame (called on each tick).
    pub fn tick(&mut self) {
        self.run.tick();
    }

    /// Opens lesson `id` at its first step (closing what is open), as the lesson list's
    /// Enter does; `false` when the course has no such lesson.
    pub fn open_lesson(&mut self, id: &str) -> bool {
        let Some(index) = self.course.index_of(id) else {
            return false;
        };
        self.close(self.overlay);
        self.go_to(index, 0);
        true
    }

    fn next_step(&mut self) {
        let Some(lesson) = self.current_lesson() else {
            return;
        };
        if self.step + 1 < lesson.steps.len() {
            self.go_to(self.lesson, self.step + 1);
        } else if !lesson.quiz.is_empty() {
            // Done once its quiz is answered (see `answered`), not by reaching it.
            self.open_question(0);
        } else {
            self.leave_lesson();
        }
    }

    /// Opens the next lesson, marking the open one done unless its quiz has a question
    /// without an answer (skipping the quiz with → does not make a lesson done).
    fn leave_lesson(&mut self) {
        let Some(lesson) = self.current_lesson() else {
            return;
        };
        let id = lesson.id.clone();
        if self.progress.quiz_answered(&id, lesson.quiz.len()) {
            self.progress.lessons_done.insert(id);
        }
        if self.lesson + 1 < self.course.lessons.len() {
            self.go_to(self.lesson + 1, 0);
        } else {
            let _ = self.save_progress();
            self.say(t(
                "that was the last step: l opens the lesson list",
                "这是最后一节了：按 l 打开课程列表",
            ));
        }
    }

    fn prev_step(&mut self) {
        if self.step > 0 {
            self.go_to(self.lesson, self.step - 1);
        } else if self.lesson > 0 {
            let steps = self.course.lessons[self.lesson - 1].steps.len();
            self.go_to(self.lesson - 1, steps.saturating_sub(1));
        }
    }

    fn go_to(&mut self, lesson: usize, step: usize) {
        let lesson = lesson.min(self.course.lessons.len().saturating_sub(1));
        let changed = lesson != self.lesson;
        if changed {
            self.exercise.lesson_changed();
        }
        self.lesson = lesson;
        self.step = step;
        self.explanation.top();
        self.tensor_scroll = 0;
        self.tensor_hscroll = 0;
        self.code_scroll = 0;
        if let Some(l) = self.current_lesson() {
            self.progress.lesson = l.id.clone();
        }
        self.progress.step = self.step;
        // A message about the lesson left behind (its quiz, its hints, its grading) does
        // not follow the learner into another lesson; a warning stays until it is read.
        if changed {
            self.status.clear_unless_warning();
        }
        let _ = self.save_progress();
        if changed {
            self.follow_lesson_env();
        }
    }

    /// The open lesson's environment becomes the run's ([`Run::follow`]).
    fn follow_lesson_env(&mut self) {
        if let Some(env) = self.current_lesson().map(|l| l.env)
            && let Some(said) = self.run.follow(env)
        {
            self.say(said);
        }
    }

    /// Writes the progress file (atomically); a failure becomes a warning on the status
    /// line, and is returned as the sentence it says.
    ///
    /// # Errors
    /// The sentence saying which file could not be written, and why.
    pub fn save_progress(&mut self) -> Result<(), String> {
        let Some(path) = &self.progress_path else {
            return Ok(());
        };
        let Err(e) = self.progress.save(path) else {
            return Ok(());
        };
        // One sentence naming the file, the cause and the fix.
        let said = e.to_string();
        self.warn(&said);
        Err(said)
    }

    /// `q`: saves the progress and leaves. When the progress cannot be saved, the first `q`
    /// says so and stays (the learner may free the disk or fix the folder); a second one
    /// leaves without it.
    /// The terminal is now `width`×`height`.
    pub fn resize(&mut self, width: u16, height: u16) {
        self.too_small = width < super::ui::MIN_SIZE.0 || height < super::ui::MIN_SIZE.1;
    }

    /// The process was asked to end: save and leave, without asking again.
    pub fn on_signal(&mut self, signal: i32) {
        self.signal = Some(signal);
        let _ = self.save_progress();
        self.run.outbox.push(Command::Quit);
        self.quit = true;
    }

    fn quit(&mut self) {
        if let Err(said) = self.save_progress()
            && !self.quit_unsaved
        {
            self.quit_unsaved = true;
            self.warn(&format!(
                "{said} {}",
                t(
                    "(q again quits without saving)",
                    "（再按一次 q 不保存直接退出）"
                )
            ));
            return;
        }
        self.run.outbox.push(Command::Quit);
        self.quit = true;
    }
}

/// The trust-region view's probe (lesson 10): measured off the UI thread for the batch of
/// the latest episode, again after each new episode while a step shows it.
#[derive(Debug, Clone, Default)]
pub enum Probe {
    /// Never measured.
    #[default]
    None,
    /// Being measured for the batch after this many episodes.
    Measuring(usize),
    /// Measured for the batch after this many episodes (or why it could not be).
    Done(
        usize,
        Result<Box<crate::ppo::trust_region::TrustRegionProbe>, String>,
    ),
}
