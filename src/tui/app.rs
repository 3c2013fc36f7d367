//! The app's state and its one `update`: every key and worker event goes through here.

use std::collections::BTreeMap;
use std::path::PathBuf;

use crate::grade::Report;
use crate::i18n::{Lang, LangGuard, t};
use crate::lesson::quiz::QuestionKind;
use crate::lesson::{Course, Environment, Lesson, Progress, RunConfig, Snapshot, Step};
use crate::ppo::lab::Experiment;
use crate::ppo::{PpoConfig, PpoContinuousConfig};

use super::keys::Action;
use super::sandbox::{Outcome, Sandbox};
use super::widgets::lab::LabState;
use super::worker::{Command, WorkerEvent};

/// Prefix of a status message that episode updates must not overwrite (English; see
/// [`warning`] for the current language's).
pub const WARNING: &str = "warning: ";

/// The current language's prefix of a status message that episode updates must not
/// overwrite: `warning: ` or `警告：`.
#[must_use]
pub fn warning() -> &'static str {
    t(WARNING, "警告：")
}

/// Whether `status` is a warning (in either language), which episode updates keep.
#[must_use]
pub fn is_warning(status: &str) -> bool {
    Lang::ALL
        .iter()
        .any(|l| status.starts_with(l.pick(WARNING, "警告：")))
}

/// Which overlay covers the lesson, if any.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Overlay {
    /// None: the lesson step.
    #[default]
    None,
    /// The key map.
    Help,
    /// The lesson list; the field is the highlighted row.
    Lessons(usize),
    /// The sandbox (its state, the highlighted setting included, is [`App::sandbox`]).
    Sandbox,
    /// The exercise panel (status, hints, grading result); the field is the scroll offset.
    Exercise(u16),
    /// The open lesson's quiz, after its last step; the field is the question (from 0).
    Quiz(usize),
}

/// The answer being typed to the open quiz question, and its verdict once given.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct QuizState {
    /// The prediction typed so far (digits, `.`, `-`).
    pub input: String,
    /// The verdict on the latest answer (or why it could not be graded yet).
    pub verdict: Option<crate::lesson::quiz::Verdict>,
}

/// The grading of one exercise function: its report, or why grading could not run.
#[derive(Debug, Clone)]
pub struct Graded {
    /// The function graded, as `ppo-tutor grade` names it.
    pub name: String,
    /// The grader's report, or why grading could not run.
    pub result: Result<Report, String>,
}

impl From<(String, Result<Report, String>)> for Graded {
    /// A `(name, result)` pair, as a grading loop builds it.
    fn from((name, result): (String, Result<Report, String>)) -> Self {
        Self { name, result }
    }
}

impl Graded {
    /// Whether the function was graded and passed every check.
    #[must_use]
    pub fn passed(&self) -> bool {
        self.result.as_ref().is_ok_and(Report::passed)
    }
}

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

/// The exercise of the open lesson: grading, its last result, and the hints revealed.
#[derive(Debug, Clone, Default)]
pub struct ExerciseState {
    /// A grading is running on a background thread.
    pub grading: bool,
    /// The last grading of this lesson's functions.
    pub graded: Vec<Graded>,
    /// How many of the lesson's hints are shown.
    pub hints_shown: usize,
    /// Functions to grade, taken by the event loop (which runs the grader off the UI thread).
    pub request: Option<Vec<String>>,
    /// A save came in while grading: grade again when this grading ends.
    pub regrade: bool,
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

/// Everything the app shows and remembers.
#[derive(Debug)]
pub struct App {
    /// The course.
    pub course: Course,
    /// Current lesson index.
    pub lesson: usize,
    /// Current step index within the lesson.
    pub step: usize,
    /// Scroll offset of the explanation.
    pub text_scroll: u16,
    /// Whether the explanation shows its details blocks opened (`d`).
    pub details_open: bool,
    /// Scroll offset of the live tensors.
    pub tensor_scroll: usize,
    /// The first column of the live tables shown (after the step column), `<`/`>`.
    pub tensor_hscroll: usize,
    /// The open overlay.
    pub overlay: Overlay,
    /// Training state.
    pub train: TrainState,
    /// The live values after the latest episode, as the worker's session sent them.
    pub snapshot: Snapshot,
    /// The cart-pole animation's frame: an index into the latest episode's observations
    /// ([`Snapshot::observation`]).
    pub frame: usize,
    /// The previous run's curve, overlaid on the plot after a sandbox retrain.
    pub previous: Option<PreviousCurve>,
    /// The other environment's run while its lessons are not open (the worker keeps its
    /// session): browsing back continues it.
    pub parked: Option<ParkedRun>,
    /// Hyper-parameters of the current CartPole run (or of the next one, in a Pendulum
    /// lesson).
    pub config: PpoConfig,
    /// Hyper-parameters of the current Pendulum run (or of the next one).
    pub pendulum: PpoContinuousConfig,
    /// The environment of the current run: the open lesson's.
    pub env: Environment,
    /// Seed of the current run.
    pub seed: u64,
    /// The sandbox overlay's settings being edited.
    pub sandbox: Sandbox,
    /// A one-line status message (warnings, errors, confirmations).
    pub status: String,
    /// Saved progress.
    pub progress: Progress,
    /// Where progress is saved (`None` in tests).
    pub progress_path: Option<PathBuf>,
    /// Set when the app should exit.
    pub quit: bool,
    /// Commands for the worker, collected by `update` and sent by the event loop.
    pub outbox: Vec<Command>,
    /// The open lesson's exercise.
    pub exercise: ExerciseState,
    /// The clip-lab experiments started in this session, by experiment.
    pub labs: BTreeMap<Experiment, LabState>,
    /// An experiment to start, taken by the event loop (which runs it off the UI thread).
    pub lab_request: Option<(Experiment, PpoConfig)>,
    /// The open quiz question's answer.
    pub quiz: QuizState,
    /// Whether the language key switches only this thread's language (tests, which render
    /// both languages on parallel threads) rather than the whole process's (the app).
    pub thread_language: bool,
    /// This thread's language while [`App::thread_language`] switched it.
    language_guard: Option<LangGuard>,
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

/// Seeds every clip-lab experiment runs in the app (as `ppo-tutor lab`'s default).
pub const LAB_SEEDS: [u64; 5] = [0, 1, 2, 3, 4];

impl App {
    /// A new app at the saved position (or the first step).
    #[must_use]
    pub fn new(course: Course, mut progress: Progress, progress_path: Option<PathBuf>) -> Self {
        // Lessons, questions and exercises the course no longer has are not counted done,
        // and a lesson that is gone does not open another at its step number.
        progress.retain_known(&course, Some(&crate::grade::exercise_names()));
        let config = PpoConfig::default();
        let lesson = course.index_of(&progress.lesson).unwrap_or(0);
        let steps = course.lessons.get(lesson).map_or(1, |l| l.steps.len());
        let step = progress.step.min(steps.saturating_sub(1));
        let env = course
            .lessons
            .get(lesson)
            .map_or_else(Environment::default, |l| l.env);
        let pendulum = PpoContinuousConfig::default();
        let snapshot = match env {
            Environment::CartPole => Snapshot::new(&config, 0),
            Environment::Pendulum => Snapshot::new_pendulum(&pendulum, 0),
        };
        Self {
            course,
            lesson,
            step,
            text_scroll: 0,
            details_open: false,
            tensor_scroll: 0,
            tensor_hscroll: 0,
            overlay: Overlay::None,
            train: TrainState::Paused,
            snapshot,
            frame: 0,
            previous: None,
            parked: None,
            sandbox: Sandbox::new(config.clone(), 0),
            config,
            pendulum,
            env,
            seed: 0,
            status: String::new(),
            progress,
            progress_path,
            quit: false,
            outbox: Vec::new(),
            exercise: ExerciseState::default(),
            labs: BTreeMap::new(),
            lab_request: None,
            quiz: QuizState::default(),
            thread_language: false,
            language_guard: None,
        }
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
                match self.overlay {
                    Overlay::Quiz(i) if i >= quiz => self.overlay = Overlay::None,
                    Overlay::Lessons(i) if i >= self.course.lessons.len() => {
                        self.overlay = Overlay::Lessons(self.lesson);
                    }
                    _ => {}
                }
                self.quiz = QuizState::default();
                self.status = crate::tr!("language: {}", "语言：{}", next.name());
            }
            Err(e) => {
                self.status = crate::tr!(
                    "{}could not load the lessons in {}: {e}",
                    "{}无法加载{}课程：{e}",
                    warning(),
                    next.name()
                );
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

    /// Steps seen before the current one over the whole course, and the total.
    #[must_use]
    pub fn position(&self) -> (usize, usize) {
        let before: usize = self.course.lessons[..self.lesson.min(self.course.lessons.len())]
            .iter()
            .map(|l| l.steps.len())
            .sum();
        (before + self.step + 1, self.course.total_steps())
    }

    /// Applies one action from the keyboard or mouse.
    pub fn update(&mut self, action: Action) {
        if action == Action::Language {
            // Over every overlay: the same screen, in the other language.
            self.switch_language();
            return;
        }
        match self.overlay {
            Overlay::Help => match action {
                Action::Quit => self.quit(),
                Action::Help | Action::Back | Action::Enter => self.overlay = Overlay::None,
                _ => {}
            },
            Overlay::Lessons(i) => self.update_lessons(action, i),
            Overlay::Sandbox => self.update_sandbox(action),
            Overlay::Exercise(scroll) => self.update_exercise(action, scroll),
            Overlay::Quiz(i) => self.update_quiz(action, i),
            Overlay::None => self.update_main(action),
        }
    }

    fn update_main(&mut self, action: Action) {
        match action {
            Action::Quit => self.quit(),
            Action::Next => self.next_step(),
            Action::Prev => self.prev_step(),
            Action::ScrollDown => self.text_scroll = self.text_scroll.saturating_add(1),
            Action::ScrollUp => self.text_scroll = self.text_scroll.saturating_sub(1),
            Action::Details => self.details_open = !self.details_open,
            Action::TensorDown => self.tensor_scroll = self.tensor_scroll.saturating_add(5),
            Action::TensorUp => self.tensor_scroll = self.tensor_scroll.saturating_sub(5),
            Action::TensorRight => {
                let last = self.current_step().map_or(0, |s| {
                    super::widgets::tensors::max_hscroll(&self.snapshot, &s.show)
                });
                self.tensor_hscroll = self.tensor_hscroll.saturating_add(1).min(last);
            }
            Action::TensorLeft => self.tensor_hscroll = self.tensor_hscroll.saturating_sub(1),
            Action::Lessons => self.overlay = Overlay::Lessons(self.lesson),
            Action::Help => self.overlay = Overlay::Help,
            Action::Sandbox => {
                self.sandbox = Sandbox::for_run(&self.run_config(), &self.config, self.seed);
                self.overlay = Overlay::Sandbox;
            }
            Action::TrainToggle => self.toggle_training(),
            Action::OneEpisode => {
                if self.train != TrainState::Finished {
                    self.train = TrainState::Paused;
                    self.outbox.push(Command::OneEpisode);
                    self.status = t("training one episode", "正在训练一个回合").into();
                }
            }
            Action::ResetAgent => self.reset_agent(self.run_config(), self.seed, false),
            Action::Grade => self.request_grade(),
            Action::Hint => self.reveal_hint(),
            Action::RunLab => self.request_lab(),
            Action::Back
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

    /// Question `i` of the open lesson's quiz.
    #[must_use]
    pub fn quiz_question(&self, i: usize) -> Option<&crate::lesson::quiz::Question> {
        self.current_lesson()?.quiz.get(i)
    }

    /// `(answered, right, total)` over the whole course's quizzes.
    #[must_use]
    pub fn quiz_score(&self) -> (usize, usize, usize) {
        let total = self.course.lessons.iter().map(|l| l.quiz.len()).sum();
        let (answered, right) = self.progress.quiz_score();
        (answered, right, total)
    }

    fn open_question(&mut self, i: usize) {
        self.quiz = QuizState::default();
        self.overlay = Overlay::Quiz(i);
        let total = self.current_lesson().map_or(0, |l| l.quiz.len());
        let how = match self.quiz_question(i).map(|q| &q.kind) {
            Some(QuestionKind::Predict { .. }) => t("type a number, Enter", "输入一个数，按 Enter"),
            _ => t("a–d answers", "按 a–d 作答"),
        };
        self.status = crate::tr!(
            "check your understanding: question {}/{total} ({how})",
            "检验一下：第 {}/{total} 题（{how}）",
            i + 1
        );
    }

    fn update_quiz(&mut self, action: Action, i: usize) {
        let Some(question) = self.quiz_question(i).cloned() else {
            self.overlay = Overlay::None;
            return;
        };
        match action {
            Action::Type(c) => match &question.kind {
                QuestionKind::Choice { .. } => {
                    if c.is_ascii_lowercase() {
                        let verdict = question.choose(c);
                        self.answered(i, verdict);
                    }
                }
                QuestionKind::Predict { .. } => {
                    if self.quiz.verdict.as_ref().is_none_or(|v| !v.answered)
                        && (c.is_ascii_digit() || c == '.' || c == '-')
                        && self.quiz.input.len() < 16
                    {
                        self.quiz.input.push(c);
                    }
                }
            },
            Action::Erase => {
                if self.quiz.verdict.as_ref().is_none_or(|v| !v.answered) {
                    self.quiz.input.pop();
                }
            }
            Action::Enter => {
                if let QuestionKind::Predict { .. } = question.kind {
                    if self.quiz.verdict.as_ref().is_some_and(|v| v.answered) {
                        return;
                    }
                    let verdict = match self.quiz.input.parse::<f64>() {
                        Ok(v) => question.predict(v, &self.snapshot),
                        Err(_) => {
                            self.status = t(
                                "type a number first (digits, '.', '-')",
                                "先输入一个数（数字、'.'、'-'）",
                            )
                            .into();
                            return;
                        }
                    };
                    self.answered(i, verdict);
                }
            }
            Action::Next => {
                let total = self.current_lesson().map_or(0, |l| l.quiz.len());
                if i + 1 < total {
                    self.open_question(i + 1);
                } else {
                    self.overlay = Overlay::None;
                    self.leave_lesson();
                }
            }
            Action::Prev => {
                if i > 0 {
                    self.open_question(i - 1);
                } else {
                    self.overlay = Overlay::None;
                }
            }
            Action::Back => self.overlay = Overlay::None,
            Action::Up | Action::ScrollUp | Action::Down | Action::ScrollDown => {}
            other => self.update_main(other),
        }
    }

    /// Shows `verdict` and records a real answer (the first one counts).
    fn answered(&mut self, i: usize, verdict: crate::lesson::quiz::Verdict) {
        if verdict.answered {
            let id = self
                .current_lesson()
                .map(|l| l.id.clone())
                .unwrap_or_default();
            self.progress.record_quiz(&id, i + 1, verdict.right);
            let questions = self.current_lesson().map_or(0, |l| l.quiz.len());
            if self.progress.quiz_answered(&id, questions) {
                self.progress.lessons_done.insert(id);
            }
            self.save_progress();
            let (answered, right, total) = self.quiz_score();
            self.status = crate::tr!(
                "{} · quiz {right} right of {answered} answered ({total} questions) · n next",
                "{} · 小测验已答 {answered} 题，答对 {right} 题（共 {total} 题）· n 下一题",
                if verdict.right {
                    t("right", "答对了")
                } else {
                    t("not quite", "不太对")
                }
            );
        } else {
            self.status = verdict.text.lines().next().unwrap_or_default().to_string();
        }
        self.quiz.verdict = Some(verdict);
    }

    fn update_exercise(&mut self, action: Action, scroll: u16) {
        match action {
            Action::Quit => self.quit(),
            Action::Grade => self.request_grade(),
            Action::Hint => self.reveal_hint(),
            Action::Up | Action::ScrollUp => {
                self.overlay = Overlay::Exercise(scroll.saturating_sub(1))
            }
            Action::Down | Action::ScrollDown => {
                self.overlay = Overlay::Exercise(scroll.saturating_add(1));
            }
            Action::Back | Action::Enter => self.overlay = Overlay::None,
            _ => {}
        }
    }

    /// The function names the open lesson grades (empty without an exercise).
    #[must_use]
    pub fn exercise_names(&self) -> Vec<String> {
        self.current_lesson()
            .and_then(|l| l.exercise.as_ref())
            .map(|e| e.names().into_iter().map(String::from).collect())
            .unwrap_or_default()
    }

    /// Whether every function of the open lesson's exercise has passed (then its reference
    /// solution may be shown).
    #[must_use]
    pub fn exercise_done(&self) -> bool {
        let names = self.exercise_names();
        !names.is_empty()
            && names
                .iter()
                .all(|n| self.progress.exercises_done.contains(n))
    }

    /// The open lesson's exercise files, as `ppo-tutor grade` finds them (relative to the
    /// current folder), each once.
    #[must_use]
    pub fn exercise_files(&self) -> Vec<PathBuf> {
        let mut files: Vec<PathBuf> = self
            .exercise_names()
            .iter()
            .filter_map(|n| crate::grade::find(n).ok())
            .map(|e| PathBuf::from(e.starter_path()))
            .collect();
        files.sort();
        files.dedup();
        files
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
        self.status = crate::tr!("saved: {}", "已保存：{}", self.status);
    }

    fn request_grade(&mut self) {
        let names = self.exercise_names();
        if names.is_empty() {
            self.status = t(
                "this lesson has no exercise to grade",
                "本课没有要评测的练习",
            )
            .into();
            return;
        }
        self.overlay = Overlay::Exercise(0);
        if self.exercise.grading {
            self.status = t("already grading…", "正在评测……").into();
            return;
        }
        self.exercise.grading = true;
        self.status = crate::tr!("grading {}…", "正在评测 {}……", names.join(", "));
        self.exercise.request = Some(names);
    }

    fn reveal_hint(&mut self) {
        let Some(exercise) = self.current_lesson().and_then(|l| l.exercise.as_ref()) else {
            self.status = t("this lesson has no exercise", "本课没有练习").into();
            return;
        };
        let total = exercise.hints.len();
        self.overlay = Overlay::Exercise(0);
        if self.exercise.hints_shown < total {
            self.exercise.hints_shown += 1;
            self.status = crate::tr!(
                "hint {}/{total}",
                "提示 {}/{total}",
                self.exercise.hints_shown
            );
        } else {
            self.status = crate::tr!("all {total} hints are shown", "{total} 条提示已全部显示");
        }
    }

    /// What the clip-lab experiments start from in the app: the seed's settings, with the
    /// episode count of the current run.
    #[must_use]
    pub fn lab_base(&self) -> PpoConfig {
        PpoConfig {
            num_episodes: self.config.num_episodes,
            ..PpoConfig::default()
        }
    }

    /// Starts the current step's experiment (`x`), unless it is running or done.
    fn request_lab(&mut self) {
        let Some(experiment) = self.current_step().and_then(|s| s.lab) else {
            self.status = t(
                "this step has no experiment to run (the clip-lab lesson has them)",
                "本节没有可运行的实验（截断实验室那一课里有）",
            )
            .into();
            return;
        };
        if matches!(
            self.labs.get(&experiment),
            Some(LabState::Running { .. } | LabState::Done(_))
        ) {
            self.status = crate::tr!(
                "lab {}: already started in this session",
                "实验 {}：本次会话中已经启动过",
                experiment.name()
            );
            return;
        }
        let base = self.lab_base();
        let total = experiment.arms(&base).len() * LAB_SEEDS.len() * base.num_episodes;
        self.labs
            .insert(experiment, LabState::Running { done: 0, total });
        self.lab_request = Some((experiment, base));
        self.status = crate::tr!(
            "lab {}: running on every core",
            "实验 {}：正在所有 CPU 核心上运行",
            experiment.name()
        );
    }

    /// Applies an experiment's progress or its end.
    pub fn on_lab(&mut self, experiment: Experiment, state: LabState) {
        match &state {
            LabState::Done(_) => {
                self.status = crate::tr!("lab {}: done", "实验 {}：完成", experiment.name());
            }
            LabState::Failed(m) => {
                self.status = crate::tr!(
                    "{}lab {}: {m}",
                    "{}实验 {}：{m}",
                    warning(),
                    experiment.name()
                );
            }
            LabState::Running { .. } => {}
        }
        self.labs.insert(experiment, state);
    }

    /// Applies a finished grading: shows it, and records passed exercises in the progress.
    pub fn on_graded(&mut self, graded: impl IntoIterator<Item = impl Into<Graded>>) {
        let graded: Vec<Graded> = graded.into_iter().map(Into::into).collect();
        self.exercise.grading = false;
        let passed: Vec<&str> = graded
            .iter()
            .filter(|g| g.passed())
            .map(|g| g.name.as_str())
            .collect();
        for name in &passed {
            self.progress.exercises_done.insert((*name).to_string());
        }
        self.status = if passed.len() == graded.len() {
            t(
                "passed: the reference solution is shown in the exercise panel",
                "通过：练习面板里显示了参考答案",
            )
            .into()
        } else {
            crate::tr!(
                "{}/{} passed: see the exercise panel",
                "{}/{} 通过：详见练习面板",
                passed.len(),
                graded.len()
            )
        };
        self.exercise.graded = graded;
        self.save_progress();
        if std::mem::take(&mut self.exercise.regrade) {
            self.request_grade();
        }
    }

    fn update_lessons(&mut self, action: Action, i: usize) {
        let n = self.course.lessons.len();
        match action {
            Action::Quit => self.quit(),
            Action::Up | Action::ScrollUp => self.overlay = Overlay::Lessons(i.saturating_sub(1)),
            Action::Down | Action::ScrollDown => {
                self.overlay = Overlay::Lessons((i + 1).min(n.saturating_sub(1)))
            }
            Action::Enter => {
                self.go_to(i, 0);
                self.overlay = Overlay::None;
            }
            Action::Lessons | Action::Back => self.overlay = Overlay::None,
            _ => {}
        }
    }

    fn update_sandbox(&mut self, action: Action) {
        match self.sandbox.update(action) {
            Outcome::Stay => {}
            Outcome::Close => self.overlay = Overlay::None,
            Outcome::Quit => self.quit(),
            Outcome::Retrain => {
                self.overlay = Overlay::None;
                // Keep the current run's smoothed curve on the plot for comparison.
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
                self.reset_agent(self.sandbox.run_config(), self.sandbox.seed, true);
            }
        }
    }

    fn toggle_training(&mut self) {
        match self.train {
            TrainState::Paused => {
                self.train = TrainState::Running;
                self.outbox.push(Command::Run);
                self.status = t("training…", "训练中……").into();
            }
            TrainState::Running => {
                self.train = TrainState::Paused;
                self.outbox.push(Command::Pause);
                self.status = t("paused", "已暂停").into();
            }
            TrainState::Finished => {
                self.status = crate::tr!(
                    "all {} episodes done: r resets the agent, s opens the sandbox",
                    "全部 {} 个回合已训练完：按 r 重置智能体，按 s 打开沙盒",
                    self.run_config().num_episodes()
                );
            }
        }
    }

    /// The current run's environment and settings, as the worker's session was started.
    #[must_use]
    pub fn run_config(&self) -> RunConfig {
        self.config_for(self.env)
    }

    /// A run on `env` with that environment's settings in force.
    fn config_for(&self, env: Environment) -> RunConfig {
        match env {
            Environment::CartPole => RunConfig::CartPole(self.config.clone()),
            Environment::Pendulum => RunConfig::Pendulum(self.pendulum.clone()),
        }
    }

    fn reset_agent(&mut self, config: RunConfig, seed: u64, run: bool) {
        self.outbox.push(Command::Reset {
            config: Box::new(config.clone()),
            seed,
        });
        self.show(config.first_snapshot(seed));
        self.env = config.env();
        match config {
            RunConfig::CartPole(c) => self.config = c,
            RunConfig::Pendulum(p) => self.pendulum = p,
        }
        self.seed = seed;
        self.train = TrainState::Paused;
        if run {
            self.outbox.push(Command::Run);
            self.train = TrainState::Running;
        }
        self.status = crate::tr!("fresh agent, seed {seed}", "新的智能体，随机种子 {seed}");
    }

    /// Applies one event from the training worker.
    pub fn on_worker(&mut self, event: WorkerEvent) {
        match event {
            WorkerEvent::Episode(snapshot) => self.on_episode(*snapshot),
            WorkerEvent::Finished => {
                self.train = TrainState::Finished;
                self.status = crate::tr!(
                    "finished {} episodes",
                    "已训练完 {} 个回合",
                    self.snapshot.returns.len()
                );
            }
            WorkerEvent::Reset { seed } => {
                self.status = crate::tr!("fresh agent, seed {seed}", "新的智能体，随机种子 {seed}");
            }
            // The app showed the run it set aside already (`follow_lesson_env`).
            WorkerEvent::Resumed { .. } => {}
            WorkerEvent::Error(message) => {
                self.train = TrainState::Paused;
                self.status = crate::tr!("training stopped: {message}", "训练已停止：{message}");
            }
        }
    }

    fn on_episode(&mut self, snapshot: Snapshot) {
        // An episode of the run just set aside, finished before the worker switched.
        if snapshot.env != self.env {
            return;
        }
        self.show(snapshot);
        // A start-up warning stays until the learner does something.
        if self.train == TrainState::Paused
            && !is_warning(&self.status)
            && let Some(r) = self.snapshot.returns.last()
        {
            self.status = crate::tr!(
                "episode {}: return {}",
                "第 {} 回合：回报 {}",
                self.snapshot.episodes,
                return_text(*r)
            );
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
            self.save_progress();
            self.status = t(
                "that was the last step: l opens the lesson list",
                "这是最后一节了：按 l 打开课程列表",
            )
            .into();
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
            let grading = self.exercise.grading;
            self.exercise = ExerciseState {
                grading,
                ..ExerciseState::default()
            };
        }
        self.lesson = lesson;
        self.step = step;
        self.text_scroll = 0;
        self.tensor_scroll = 0;
        self.tensor_hscroll = 0;
        if let Some(l) = self.current_lesson() {
            self.progress.lesson = l.id.clone();
        }
        self.progress.step = self.step;
        // A message about the lesson left behind (its quiz, its hints, its grading) does
        // not follow the learner into another lesson; a warning stays until it is read.
        if changed && !is_warning(&self.status) {
            self.status.clear();
        }
        self.save_progress();
        if changed {
            self.follow_lesson_env();
        }
    }

    /// A lesson on the other environment continues that environment's run if one was set
    /// aside, else starts a fresh one there (paused), with that environment's settings in
    /// force; the run left behind is set aside, not thrown away (issue 25, bug 2).
    fn follow_lesson_env(&mut self) {
        let Some(env) = self.current_lesson().map(|l| l.env) else {
            return;
        };
        if env == self.env {
            return;
        }
        let config = self.config_for(env);
        self.outbox.push(Command::Switch {
            config: Box::new(config.clone()),
            seed: self.seed,
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
        self.frame = 0;
        self.env = env;
        self.train = TrainState::Paused;
        match self.parked.take().filter(|p| p.snapshot.env == env) {
            Some(back) => {
                let episodes = back.snapshot.episodes;
                self.show(back.snapshot);
                self.seed = back.seed;
                self.train = back.train;
                self.previous = back.previous;
                self.status = crate::tr!(
                    "a {} lesson: its run continues after episode {episodes}, seed {} (t trains)",
                    "这是 {} 的课：接着之前的训练（已训练 {episodes} 个回合，随机种子 {}；t 训练）",
                    env.as_str(),
                    self.seed
                );
            }
            None => {
                self.status = crate::tr!(
                    "a {} lesson: fresh agent, seed {} (t trains, e one episode)",
                    "这是 {} 的课：新的智能体，随机种子 {}（t 训练，e 训练一个回合）",
                    env.as_str(),
                    self.seed
                );
            }
        }
        self.parked = Some(left);
    }

    /// Writes the progress file (atomically); a failure becomes a status message.
    pub fn save_progress(&mut self) {
        if let Some(path) = &self.progress_path
            && let Err(e) = self.progress.save(path)
        {
            self.status = crate::tr!(
                "could not save progress to {}: {e}",
                "无法把进度保存到 {}：{e}",
                path.display()
            );
        }
    }

    fn quit(&mut self) {
        self.save_progress();
        self.outbox.push(Command::Quit);
        self.quit = true;
    }
}
