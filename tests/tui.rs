//! The terminal app without a terminal: every lesson step's screen as an insta snapshot
//! (drawn on ratatui's `TestBackend` from a real 3-episode session, seed 0), in English and
//! in Chinese (at 160×50 and at 80×24, every screen checked for cut CJK glyphs and
//! misaligned rows), key → state, the live language switch, and the worker thread against
//! the same session.

use std::sync::mpsc;
use std::time::Duration;

use ppo_tutor::i18n::Lang;
use ppo_tutor::lesson::{AgentKind, Course, Progress, RunConfig, Session};
use ppo_tutor::ppo::{PpoConfig, PpoContinuousConfig};
use ppo_tutor::tui::app::{App, Overlay, TrainState};
use ppo_tutor::tui::keys::Action;
use ppo_tutor::tui::theme::Theme;
use ppo_tutor::tui::ui::View;
use ppo_tutor::tui::worker::{self, Command, WorkerEvent};
use ratatui::Terminal;
use ratatui::backend::TestBackend;

type TestResult = Result<(), Box<dyn std::error::Error>>;

fn app() -> Result<App, Box<dyn std::error::Error>> {
    let mut app = App::new(Course::embedded()?, Progress::default(), None);
    app.show(Session::run(PpoConfig::default(), 0, 3)?);
    Ok(app)
}

/// The screen as text, checked for cut glyphs and misaligned rows ([`checked_screen`]).
fn screen(app: &App, width: u16, height: u16) -> Result<String, Box<dyn std::error::Error>> {
    checked_screen(app, width, height)
}

/// The text inside the box whose top border starts with `title` (like `┌ quiz`), its rows
/// joined: what the box shows without the panes drawn beside it. One-column characters
/// only (the English screens).
fn inside_box(screen: &str, title: &str) -> String {
    let rows: Vec<Vec<char>> = screen.lines().map(|l| l.chars().collect()).collect();
    let Some((top, left)) = rows.iter().enumerate().find_map(|(i, r)| {
        let line: String = r.iter().collect();
        line.find(title).map(|b| (i, line[..b].chars().count()))
    }) else {
        return String::new();
    };
    let Some(right) = rows[top]
        .iter()
        .skip(left)
        .position(|&c| c == '┐')
        .map(|p| p + left)
    else {
        return String::new();
    };
    rows[top + 1..]
        .iter()
        .take_while(|r| r.get(left) != Some(&'└'))
        .map(|r| {
            r.iter()
                .skip(left + 1)
                .take(right - left - 1)
                .collect::<String>()
        })
        .collect()
}

/// A Pendulum lesson starts a fresh Pendulum run: the screens show a real 3-episode one
/// (seed 0), as CartPole lessons show a 3-episode CartPole run.
fn show_pendulum_run(app: &mut App) -> TestResult {
    if app.run.agent == AgentKind::Pendulum && app.run.snapshot.episodes == 0 {
        app.show(Session::run(PpoContinuousConfig::default(), 0, 3)?);
    }
    Ok(())
}

#[test]
fn a_pendulum_lesson_runs_pendulum_and_a_cartpole_lesson_cartpole() -> TestResult {
    let mut app = app()?;
    // A CartPole run of 3 episodes, then a Pendulum lesson.
    app.show(Session::run(PpoConfig::default(), 0, 3)?);
    open(&mut app, "continuous-actions")?;
    assert_eq!(app.run.agent, AgentKind::Pendulum);
    let sent: Vec<Command> = app.run.outbox.drain(..).collect();
    assert!(
        sent.iter()
            .any(|c| matches!(c, Command::Switch { config, seed: 0, .. }
            if config.as_ref() == &RunConfig::Pendulum(PpoContinuousConfig::default()))),
        "{sent:?}"
    );
    assert_eq!(app.run.snapshot.episodes, 0, "a fresh Pendulum agent");
    assert_eq!(
        app.run
            .snapshot
            .hyper
            .iter()
            .find(|(k, _)| k == "env_name")
            .map(|(_, v)| v.as_str()),
        Some("Pendulum-v1")
    );
    app.show(Session::run(PpoContinuousConfig::default(), 0, 2)?);
    let frames = app.run.snapshot.observation_count();
    assert_eq!(frames, 201, "200 steps and where the episode ended");
    app.tick();
    assert_eq!(app.run.frame, 1);
    let text = screen(&app, 140, 45)?;
    assert!(text.contains("the latest episode, step 1/200"), "{text}");
    assert!(text.contains("mu (200, 1) float32"), "{text}");
    open(&mut app, "pendulum")?;
    assert!(
        app.run.outbox.is_empty(),
        "the same environment keeps the run"
    );
    open(&mut app, "beyond-the-seed")?;
    assert_eq!(app.run.agent, AgentKind::CartPole);
    assert!(matches!(
        app.run.outbox.pop(),
        Some(Command::Switch { config, .. }) if matches!(config.as_ref(), RunConfig::CartPole(_))
    ));
    // Browsing back continues the CartPole run, and the Pendulum one waits.
    assert_eq!(
        app.run.snapshot.episodes, 3,
        "the CartPole run was thrown away"
    );
    assert!(
        app.status.text().contains("continues after episode 3"),
        "{}",
        app.status
    );
    open(&mut app, "pendulum")?;
    assert_eq!(
        (app.run.agent, app.run.snapshot.episodes),
        (AgentKind::Pendulum, 2)
    );
    Ok(())
}

#[test]
fn the_sandbox_switches_the_environment_to_pendulum() -> TestResult {
    let mut app = app()?;
    app.update(Action::Sandbox);
    while app.sandbox.selected != "env" {
        app.update(Action::Down);
    }
    app.update(Action::Increase); // CartPole-v1 -> CartPole-v0
    app.update(Action::Increase); // -> Pendulum-v1, the book's defaults
    assert_eq!(app.sandbox.env(), AgentKind::Pendulum);
    insta::assert_snapshot!("sandbox_pendulum", screen(&app, 140, 45)?);
    app.update(Action::Enter);
    assert_eq!(app.run.agent, AgentKind::Pendulum);
    let sent: Vec<Command> = app.run.outbox.drain(..).collect();
    assert!(
        matches!(sent.first(), Some(Command::Reset { config, .. })
            if config.as_ref() == &RunConfig::Pendulum(PpoContinuousConfig::default())),
        "{sent:?}"
    );
    assert_eq!(sent.last(), Some(&Command::Run));
    Ok(())
}

#[test]
fn overlays_and_small_terminals() -> TestResult {
    let mut app = app()?;
    app.update(Action::Help);
    insta::assert_snapshot!("help", screen(&app, 140, 45)?);
    app.update(Action::Back);
    app.update(Action::Lessons);
    insta::assert_snapshot!("lesson_list", screen(&app, 140, 45)?);
    app.update(Action::Back);
    app.update(Action::Sandbox);
    insta::assert_snapshot!("sandbox", screen(&app, 140, 45)?);
    app.update(Action::Back);
    let small = screen(&app, 60, 20)?;
    assert!(small.contains("needs at least 80×24"), "{small}");
    Ok(())
}

#[test]
fn keys_move_through_the_course() -> TestResult {
    let mut app = app()?;
    app.update(Action::Prev);
    assert_eq!((app.lesson, app.step), (0, 0), "← at the start stays");
    app.update(Action::Next);
    assert_eq!((app.lesson, app.step), (0, 1));
    let steps = app.course.lessons[0].steps.len();
    for _ in 1..steps {
        app.update(Action::Next);
    }
    assert_eq!(
        (app.overlay, app.quiz.question()),
        (Overlay::Quiz, 0),
        "→ at a lesson's end opens its quiz"
    );
    for _ in 0..app.course.lessons[0].quiz.len() {
        app.update(Action::Next);
    }
    assert_eq!(
        (app.lesson, app.step),
        (1, 0),
        "→ at a lesson's end opens the next"
    );
    assert!(
        !app.progress.lessons_done.contains("what-is-ppo"),
        "skipping the quiz with → does not make the lesson done"
    );
    app.update(Action::Prev);
    assert_eq!((app.lesson, app.step), (0, steps - 1));
    app.update(Action::Lessons);
    assert_eq!(
        (app.overlay, app.lesson_list.selected),
        (Overlay::Lessons, 0)
    );
    app.update(Action::Down);
    app.update(Action::Down);
    app.update(Action::Enter);
    assert_eq!((app.lesson, app.step, app.overlay), (2, 0, Overlay::None));
    assert_eq!(app.progress.lesson, app.course.lessons[2].id);
    Ok(())
}

#[test]
fn training_keys_send_commands_to_the_worker() -> TestResult {
    let mut app = app()?;
    app.update(Action::TrainToggle);
    assert_eq!(app.run.train, TrainState::Running);
    assert_eq!(app.run.outbox.pop(), Some(Command::Run));
    app.update(Action::TrainToggle);
    assert_eq!(
        (app.run.train, app.run.outbox.pop()),
        (TrainState::Paused, Some(Command::Pause))
    );
    app.update(Action::OneEpisode);
    assert_eq!(app.run.outbox.pop(), Some(Command::OneEpisode));
    app.update(Action::ResetAgent);
    assert!(matches!(
        app.run.outbox.pop(),
        Some(Command::Reset { seed: 0, .. })
    ));
    assert!(
        app.run.snapshot.returns.is_empty(),
        "reset clears the curve"
    );
    Ok(())
}

#[test]
fn the_sandbox_changes_settings_and_keeps_the_old_curve() -> TestResult {
    let mut app = app()?;
    let old_curve = app.run.snapshot.moving_average.clone();
    assert!(!old_curve.is_empty() || app.run.snapshot.returns.len() < 9);
    let old_curve = if old_curve.is_empty() {
        app.run.snapshot.returns.clone()
    } else {
        old_curve
    };
    app.update(Action::Sandbox);
    app.update(Action::Increase); // eps 0.2 -> 0.25
    app.update(Action::Down);
    app.update(Action::Decrease); // gamma 0.98 -> 0.97
    assert_eq!(app.sandbox.selected, "gamma");
    let edited = app
        .sandbox
        .config
        .get::<PpoConfig>()
        .cloned()
        .unwrap_or_default();
    assert!((edited.eps - 0.25).abs() < 1e-12);
    assert!((edited.gamma - 0.97).abs() < 1e-12);
    assert!(
        (app.run.cartpole().eps - 0.2).abs() < 1e-12,
        "nothing changes before Enter"
    );
    app.update(Action::Enter);
    assert!((app.run.cartpole().eps - 0.25).abs() < 1e-12);
    assert_eq!(
        app.run.previous.as_ref().map(|p| p.values.clone()),
        Some(old_curve)
    );
    let sent: Vec<Command> = app.run.outbox.drain(..).collect();
    assert!(matches!(sent.first(), Some(Command::Reset { config, .. })
            if matches!(config.as_ref(), RunConfig::CartPole(c) if (c.eps - 0.25).abs() < 1e-12)));
    assert_eq!(sent.last(), Some(&Command::Run));
    Ok(())
}

#[test]
fn quitting_saves_progress() -> TestResult {
    let dir = tempfile::tempdir()?;
    let path = dir.path().join("state.json");
    let mut app = App::new(Course::embedded()?, Progress::default(), Some(path.clone()));
    app.update(Action::Next);
    app.update(Action::Quit);
    assert!(app.quit);
    assert_eq!(app.run.outbox.last(), Some(&Command::Quit));
    let (saved, warning) = Progress::load(&path);
    assert!(warning.is_none());
    assert_eq!((saved.lesson.as_str(), saved.step), ("what-is-ppo", 1));
    let restored = App::new(Course::embedded()?, saved, None);
    assert_eq!((restored.lesson, restored.step), (0, 1));
    Ok(())
}

/// The worker keeps one session per environment: switching to Pendulum and
/// back continues the CartPole run where it stopped.
#[test]
fn the_worker_keeps_one_session_per_environment() -> TestResult {
    let config = PpoConfig::default();
    let (cmd_tx, cmd_rx) = mpsc::channel();
    let (event_tx, events) = mpsc::channel();
    let handle = worker::spawn(config.clone(), 5, cmd_rx, event_tx);
    let wait = || events.recv_timeout(Duration::from_secs(60));
    let episode = |event: WorkerEvent| match event {
        WorkerEvent::Episode { snapshot, .. } => Ok(*snapshot),
        other => Err(format!("expected an episode, got {other:?}")),
    };
    for _ in 0..2 {
        cmd_tx.send(Command::OneEpisode)?;
        episode(wait()?)?;
    }
    let pendulum = RunConfig::Pendulum(PpoContinuousConfig::default());
    cmd_tx.send(Command::Switch {
        config: Box::new(pendulum),
        seed: 0,
        run: 1,
    })?;
    assert!(matches!(wait()?, WorkerEvent::Reset { seed: 0 }));
    cmd_tx.send(Command::OneEpisode)?;
    let s = episode(wait()?)?;
    assert_eq!((s.agent(), s.episodes), (AgentKind::Pendulum, 1));
    cmd_tx.send(Command::Switch {
        config: Box::new(RunConfig::CartPole(config.clone())),
        seed: 9,
        run: 2,
    })?;
    assert!(matches!(wait()?, WorkerEvent::Resumed { episodes: 2 }));
    cmd_tx.send(Command::OneEpisode)?;
    let s = episode(wait()?)?;
    cmd_tx.send(Command::Quit)?;
    handle.join().map_err(|_| "the worker panicked")?;
    assert_eq!(
        s,
        Session::run(config, 5, 3)?,
        "the CartPole run went on from episode 2"
    );
    Ok(())
}

#[test]
fn the_worker_sends_its_session_snapshot_after_each_episode() -> TestResult {
    let config = PpoConfig::default();
    let (cmd_tx, cmd_rx) = mpsc::channel();
    let (event_tx, events) = mpsc::channel();
    let handle = worker::spawn(config.clone(), 5, cmd_rx, event_tx);
    let mut app = App::new(Course::embedded()?, Progress::default(), None);
    for _ in 0..2 {
        cmd_tx.send(Command::OneEpisode)?;
        let event = events.recv_timeout(Duration::from_secs(60))?;
        assert!(
            matches!(event, WorkerEvent::Episode { run: 0, .. }),
            "{event:?}"
        );
        app.on_worker(event);
    }
    cmd_tx.send(Command::Quit)?;
    handle.join().map_err(|_| "the worker panicked")?;
    let expected = Session::run(config, 5, 2)?;
    assert_eq!(
        app.run.snapshot, expected,
        "the app shows what the session computed"
    );
    let last = expected.returns.last().ok_or("no return")?;
    assert_eq!(app.status.text(), format!("episode 2: return {last}"));
    let frames = expected.observation_count();
    assert!(frames > 1);
    for _ in 0..frames {
        app.tick();
    }
    assert_eq!(
        app.run.frame, 0,
        "the animation loops over the episode's observations"
    );
    Ok(())
}

#[test]
fn a_worker_that_cannot_start_says_why() -> TestResult {
    let bad = PpoConfig {
        gamma: 0.0,
        ..PpoConfig::default()
    };
    let (_cmd_tx, cmd_rx) = mpsc::channel::<Command>();
    let (event_tx, events) = mpsc::channel();
    let _handle = worker::spawn(bad, 0, cmd_rx, event_tx);
    match events.recv_timeout(Duration::from_secs(10))? {
        WorkerEvent::Error { message, .. } => assert!(message.contains("gamma"), "{message}"),
        other => return Err(format!("expected an error, got {other:?}").into()),
    }
    Ok(())
}

/// Moves the app to the first step of lesson `id`.
fn open(app: &mut App, id: &str) -> TestResult {
    let index = app.course.index_of(id).ok_or("no such lesson")?;
    app.update(Action::Lessons);
    // The list opens on the current lesson: go to the top first.
    for _ in 0..app.course.lessons.len() {
        app.update(Action::Up);
    }
    for _ in 0..index {
        app.update(Action::Down);
    }
    app.update(Action::Enter);
    assert_eq!(app.current_lesson().map(|l| l.id.as_str()), Some(id));
    Ok(())
}

#[test]
fn d_opens_and_folds_the_details() -> TestResult {
    let mut app = app()?;
    open(&mut app, "cartpole")?;
    while !app
        .current_step()
        .is_some_and(|s| ppo_tutor::lesson::details::has_details(&s.body))
    {
        app.update(Action::Next);
    }
    let folded = screen(&app, 140, 45)?;
    assert!(folded.contains("Details: The equations of motion") && folded.contains("(d opens)"));
    assert!(!folded.contains("explicit Euler"), "folded text is hidden");
    app.update(Action::Details);
    let opened = screen(&app, 140, 45)?;
    assert!(
        opened.contains("explicit Euler") && opened.contains("(d folds)"),
        "{opened}"
    );
    app.update(Action::Details);
    assert_eq!(screen(&app, 140, 45)?, folded);
    Ok(())
}

#[test]
fn x_runs_the_step_s_experiment_and_the_panel_shows_its_result() -> TestResult {
    use ppo_tutor::ppo::lab::{self, Experiment};
    use ppo_tutor::tui::widgets::lab::LabState;
    let mut app = app()?;
    app.update(Action::RunLab);
    assert!(
        app.lab.request.is_none(),
        "no experiment outside the lab steps"
    );
    assert!(
        app.status.text().contains("no experiment"),
        "{}",
        app.status
    );
    open(&mut app, "clip-lab")?;
    app.update(Action::Next); // Experiment 1: the clip range
    let before = screen(&app, 140, 45)?;
    assert!(
        before.contains("x asks your prediction, then runs the experiment"),
        "{before}"
    );
    // What the seeds showed stays hidden until the learner commits to a prediction.
    assert!(
        before.contains("appears here once you have made your"),
        "{before}"
    );
    assert!(!before.contains("495.5"), "{before}");
    app.update(Action::RunLab);
    assert!(app.lab.request.is_none(), "x asks before it runs");
    let asking = screen(&app, 140, 45)?;
    assert!(
        asking.contains("which setting will end highest"),
        "{asking}"
    );
    assert!(asking.contains("c) no clip"), "{asking}");
    app.update(Action::Type('z'));
    assert!(app.lab.request.is_none(), "no such choice");
    assert!(app.status.text().contains("from a to c"), "{}", app.status);
    app.update(Action::Type('b'));
    assert_eq!(
        app.progress.predictions.get("eps").map(String::as_str),
        Some("b")
    );
    let (experiment, base) = app
        .lab
        .request
        .take()
        .ok_or("the prediction started no run")?;
    let revealed = screen(&app, 140, 45)?;
    assert!(
        revealed.contains("Your prediction: b) ε = 0.05"),
        "{revealed}"
    );
    assert!(!revealed.contains("appears here once"), "{revealed}");
    assert_eq!((experiment, base.num_episodes), (Experiment::Eps, 500));
    assert!(matches!(
        app.lab.get(&experiment),
        Some(LabState::Running { done: 0, .. })
    ));
    app.update(Action::RunLab);
    assert!(
        app.lab.request.is_none(),
        "a running experiment is not started twice"
    );
    // What the event loop's thread sends back, from a short run.
    let short = PpoConfig {
        num_episodes: 12,
        ..PpoConfig::default()
    };
    let result = lab::run(experiment, &short, &[0, 1], 2, |_, _| {})?;
    app.on_lab(
        experiment,
        LabState::Running {
            done: 30,
            total: 72,
        },
    );
    assert!(screen(&app, 140, 45)?.contains("running: 30/72 episodes"));
    let table = result.table();
    app.on_lab(experiment, LabState::Done(Box::new(result)));
    let after = screen(&app, 140, 45)?;
    for row in &table[1..] {
        let label = row.split("  ").next().unwrap_or_default().trim();
        assert!(after.contains(label), "{label} missing:\n{after}");
    }
    assert!(
        after.contains("ε = 0.05 vs ε = 0.2") && after.contains("no clip vs ε = 0.2"),
        "{after}"
    );
    // The prediction, graded against the run: the setting it found and the paired line.
    assert!(after.contains("Your prediction: ε = 0.05"), "{after}");
    assert!(after.contains("Paired seed by seed"), "{after}");
    assert!(app.status.text().contains("lab eps: done"));
    // Esc on the next experiment runs it without a prediction, and shows its results.
    app.update(Action::Next);
    app.update(Action::RunLab);
    assert!(app.lab.request.is_none());
    app.update(Action::Back);
    assert_eq!(
        app.progress.predictions.get("epochs").map(String::as_str),
        Some("")
    );
    assert_eq!(
        app.lab.request.take().map(|(e, _)| e),
        Some(Experiment::Epochs)
    );
    assert!(app.results_open());
    Ok(())
}

/// Saved progress names lessons by id, so a state file written before the course was
/// reordered (hyper-parameters was lesson 2, now 15) still opens the same lesson and step.
#[test]
fn progress_saved_before_the_reorder_opens_the_same_lesson() -> TestResult {
    let old: Progress = serde_json::from_str(
        r#"{"lesson":"hyperparameters","step":2,"lessons_done":["what-is-ppo"],"exercises_done":["compute_advantage"]}"#,
    )?;
    let app = App::new(Course::embedded()?, old, None);
    let lesson = app.current_lesson().ok_or("no lesson")?;
    assert_eq!(
        (lesson.id.as_str(), lesson.order, app.step),
        ("hyperparameters", 15, 2)
    );
    assert!(app.progress.lessons_done.contains("what-is-ppo"));
    Ok(())
}

/// What a progress file names that the course does not know is not
/// counted, and an unknown lesson opens the first lesson at its first step.
#[test]
fn unknown_lessons_in_the_progress_file_count_for_nothing() -> TestResult {
    let old: Progress = serde_json::from_str(
        r#"{"lesson":"gone","step":99,"lessons_done":["gone","also-gone","what-is-ppo"],"exercises_done":["nope","compute_advantage"]}"#,
    )?;
    let app = App::new(Course::embedded()?, old, None);
    assert_eq!((app.lesson, app.step), (0, 0));
    let done: Vec<&str> = app
        .progress
        .lessons_done
        .iter()
        .map(String::as_str)
        .collect();
    assert_eq!(done, ["what-is-ppo"]);
    assert_eq!(app.progress.exercises_done.len(), 1);
    let footer = screen(&app, 160, 50)?;
    let lessons = app.course.lessons.len();
    assert!(
        footer.contains(&format!("lessons done 1/{lessons}")),
        "{footer}"
    );
    Ok(())
}

/// Question `i` of the open quiz, a choice whose right letter does not depend on the run:
/// the right choice's index and the choices.
fn fixed_choice(app: &App, i: usize) -> Result<(usize, Vec<String>), String> {
    use ppo_tutor::lesson::quiz::{Answer, QuestionKind};
    match app.quiz_question(i).map(|q| q.kind.clone()) {
        Some(QuestionKind::Choice {
            answer: Answer::Letter(answer),
            choices,
            ..
        }) => Ok((answer, choices)),
        _ => Err(format!("question {} is not a fixed choice", i + 1)),
    }
}

/// Opens the quiz of lesson `id` (→ past its last step).
fn open_quiz(app: &mut App, id: &str) -> TestResult {
    open(app, id)?;
    let steps = app.current_lesson().map_or(0, |l| l.steps.len());
    for _ in 0..steps {
        app.update(Action::Next);
    }
    assert_eq!((app.overlay, app.quiz.question()), (Overlay::Quiz, 0));
    Ok(())
}

#[test]
fn quiz_questions_are_answered_with_keys_and_counted() -> TestResult {
    use ppo_tutor::lesson::quiz::QuestionKind;
    let mut app = app()?;
    let (_, _, total) = app.quiz_score();
    assert!(
        total >= 3 * app.course.lessons.len(),
        "at least 3 questions per lesson"
    );
    let mut answered = 0;
    for id in ["ratio", "clipping"] {
        open_quiz(&mut app, id)?;
        let questions = app.current_lesson().ok_or("no lesson")?.quiz.clone();
        for (i, q) in questions.iter().enumerate() {
            assert_eq!((app.overlay, app.quiz.question()), (Overlay::Quiz, i));
            match &q.kind {
                QuestionKind::Choice { explain, .. } => {
                    // Graded against the run as the quiz shows it (a choice the run decides).
                    let answer = &q.right_choice(&app.run.snapshot).ok_or("no right choice")?;
                    let wrong = ppo_tutor::lesson::quiz::letter_of((answer + 1) % explain.len());
                    app.update(Action::Type(wrong));
                    let verdict = app.quiz.verdict.clone().ok_or("no verdict")?;
                    assert!(verdict.answered && !verdict.right);
                    assert!(
                        verdict
                            .text
                            .contains(&explain[(answer + 1) % explain.len()])
                    );
                    let right = ppo_tutor::lesson::quiz::letter_of(*answer);
                    app.update(Action::Type(right));
                    assert!(app.quiz.verdict.as_ref().is_some_and(|v| v.right));
                    let key = Progress::quiz_key(id, i + 1);
                    assert_eq!(
                        app.progress.quiz.get(&key),
                        Some(&false),
                        "the first answer counts"
                    );
                }
                QuestionKind::Predict { measure, .. } => {
                    app.update(Action::Enter);
                    assert!(app.quiz.verdict.is_none(), "nothing typed, nothing graded");
                    let live = (measure.value)(&app.run.snapshot).ok_or("no live value")?;
                    for c in format!("{live:.6}").chars() {
                        app.update(Action::Type(c));
                    }
                    let before = screen(&app, 140, 45)?;
                    assert!(
                        !before.contains("the live value is"),
                        "revealed before the answer"
                    );
                    app.update(Action::Enter);
                    let verdict = app.quiz.verdict.clone().ok_or("no verdict")?;
                    assert!(verdict.right && verdict.live == Some(live), "{verdict}");
                    assert!(screen(&app, 140, 45)?.contains("the live value is"));
                }
            }
            answered += 1;
            app.update(Action::Next);
        }
    }
    let (done, _, total) = app.quiz_score();
    assert_eq!(done, answered);
    for id in ["ratio", "clipping"] {
        assert!(
            app.progress.lessons_done.contains(id),
            "{id}: every question answered makes the lesson done"
        );
    }
    let footer = screen(&app, 140, 45)?;
    let right = app.progress.quiz.values().filter(|r| **r).count();
    assert!(
        footer.contains(&format!("quiz {right}/{total} right ({answered} answered)")),
        "{footer}"
    );
    // Esc leaves the quiz for the lesson; ← from the first question goes back to its last step.
    open_quiz(&mut app, "gae")?;
    app.update(Action::Back);
    assert_eq!(app.overlay, Overlay::None);
    Ok(())
}

#[test]
fn saving_the_exercise_file_grades_it_one_grading_at_a_time() -> TestResult {
    let mut app = app()?;
    open(&mut app, "clip-lab")?;
    app.on_saved();
    assert!(app.exercise.grading);
    assert_eq!(app.overlay, Overlay::Exercise);
    let names = app.exercise.request.take().ok_or("no grading requested")?;
    assert_eq!(
        names,
        vec!["reverse_kl".to_string(), "kl_early_stop".to_string()]
    );
    app.on_saved();
    assert!(app.exercise.request.is_none(), "one grading at a time");
    app.on_graded(Vec::<ppo_tutor::tui::app::Graded>::new());
    assert!(
        app.exercise.request.is_some(),
        "the save during the grading is graded after it"
    );
    assert_eq!(
        app.exercise_files(),
        vec![std::path::PathBuf::from("lessons/13-clip-lab/exercise.rs")]
    );
    app.update(Action::Back);
    open(&mut app, "cartpole")?;
    app.exercise.grading = false;
    app.exercise.request = None;
    app.on_saved();
    assert!(
        app.exercise.request.is_none(),
        "a lesson without an exercise ignores saves"
    );
    Ok(())
}

/// The screen as rows of text (one cell a column, a wide glyph once), each row checked: no
/// wide glyph cut at the right edge or drawn over by its neighbour, and every row exactly
/// as wide as the terminal (so the right border lines up).
fn checked_screen(
    app: &App,
    width: u16,
    height: u16,
) -> Result<String, Box<dyn std::error::Error>> {
    let columns = |s: &str| ratatui::text::Span::raw(s).width();
    let mut terminal = Terminal::new(TestBackend::new(width, height))?;
    // The frame as drawn (a cell drawn over the right half of a wide glyph shows here; the
    // backend never receives it).
    let frame = terminal.draw(|f| {
        f.render_widget(
            &View {
                app,
                theme: Theme { color: false },
            },
            f.area(),
        )
    })?;
    let buffer = frame.buffer.clone();
    let mut out = String::new();
    let mut problems = Vec::new();
    for y in 0..height {
        let mut row = String::new();
        let mut covered = 0_usize;
        for x in 0..width {
            let symbol = buffer[(x, y)].symbol();
            if covered > 0 {
                covered -= 1;
                if !symbol.trim().is_empty() {
                    problems.push(format!(
                        "row {y}, column {x}: {symbol:?} drawn over the right half of a wide glyph"
                    ));
                }
                continue;
            }
            let w = columns(symbol);
            if w > 1 && usize::from(x) + w > usize::from(width) {
                problems.push(format!("row {y}: {symbol:?} cut at the right edge"));
            }
            covered = w.saturating_sub(1);
            row.push_str(symbol);
        }
        if columns(&row) != usize::from(width) {
            problems.push(format!(
                "row {y} is {} columns wide, not {width}: {row:?}",
                columns(&row)
            ));
        }
        out.push('"');
        out.push_str(&row);
        out.push_str("\"\n");
    }
    if problems.is_empty() {
        Ok(out)
    } else {
        Err(format!("{}\n{out}", problems.join("\n")).into())
    }
}

/// Every step of every lesson and each lesson's first quiz question, in Chinese at
/// `width`×`height`: snapshots, and no row cut or misaligned.
/// Walks every step and quiz of the course in `lang` at `width`×`height`, checking each
/// screen ([`checked_screen`]) and its snapshot (`zh-80x24-…`, `en-160x50-…`).
fn every_step_in(lang: Lang, width: u16, height: u16) -> TestResult {
    let _lang = lang.scoped();
    // The course is loaded in this thread, so in `lang`.
    let mut app = app()?;
    let total = app.course.total_steps();
    let size = format!("{}-{width}x{height}", lang.code());
    for i in 0..total {
        let lesson = app.current_lesson().ok_or("no lesson")?;
        let name = format!(
            "{size}-{:02}-{}-step{}",
            lesson.order,
            lesson.id,
            app.step + 1
        );
        let text = checked_screen(&app, width, height).map_err(|e| format!("{name}: {e}"))?;
        let chrome = lang.pick(
            format!("step {}/{}", app.step + 1, lesson.steps.len()),
            format!("第 {}/{} 节", app.step + 1, lesson.steps.len()),
        );
        assert!(
            text.contains(chrome.as_str()),
            "{name}: {chrome} missing:\n{text}"
        );
        if width >= 160 {
            assert!(text.contains(&lesson.title), "{name}: title missing");
            let key = lang.pick("L 中文", "L English");
            assert!(text.contains(key), "{name}: language key missing");
        }
        insta::assert_snapshot!(name, text);
        if i + 1 < total {
            app.update(Action::Next);
        }
        show_pendulum_run(&mut app)?;
        if app.overlay == Overlay::Quiz && app.quiz.question() == 0 {
            let lesson = app.current_lesson().ok_or("no lesson")?;
            let name = format!("{size}-{:02}-{}-quiz", lesson.order, lesson.id);
            let questions = lesson.quiz.len();
            let text = checked_screen(&app, width, height).map_err(|e| format!("{name}: {e}"))?;
            assert!(
                text.contains(lang.pick("quiz", "小测验")),
                "{name}:\n{text}"
            );
            insta::assert_snapshot!(name, text);
            for _ in 0..questions {
                app.update(Action::Next);
            }
            show_pendulum_run(&mut app)?;
        }
    }
    assert_eq!(app.position(), (total, total));
    Ok(())
}

#[test]
fn every_step_of_every_lesson_in_chinese_at_160x50() -> TestResult {
    every_step_in(Lang::Zh, 160, 50)
}

#[test]
fn every_step_of_every_lesson_at_160x50() -> TestResult {
    every_step_in(Lang::En, 160, 50)
}

#[test]
fn every_step_of_every_lesson_at_80x24() -> TestResult {
    every_step_in(Lang::En, 80, 24)
}

#[test]
fn every_step_of_every_lesson_in_chinese_at_80x24() -> TestResult {
    every_step_in(Lang::Zh, 80, 24)
}

#[test]
fn chinese_overlays_stay_aligned_at_both_sizes() -> TestResult {
    let _zh = Lang::Zh.scoped();
    let mut app = app()?;
    open(&mut app, "td-target")?;
    for (width, height) in [(160, 50), (80, 24)] {
        let size = format!("{width}x{height}");
        app.update(Action::Help);
        let help = checked_screen(&app, width, height)?;
        assert!(
            help.contains("按键（Esc 关闭）") && help.contains("切换为 English"),
            "{help}"
        );
        insta::assert_snapshot!(format!("zh-{size}-help"), help);
        app.update(Action::Back);
        app.update(Action::Lessons);
        insta::assert_snapshot!(
            format!("zh-{size}-lesson_list"),
            checked_screen(&app, width, height)?
        );
        app.update(Action::Back);
        app.update(Action::Sandbox);
        let sandbox = checked_screen(&app, width, height)?;
        assert!(sandbox.contains("沙盒"), "{sandbox}");
        insta::assert_snapshot!(format!("zh-{size}-sandbox"), sandbox);
        app.update(Action::Back);
        app.update(Action::Hint);
        let exercise = checked_screen(&app, width, height)?;
        assert!(
            exercise.contains("提示（") && exercise.contains("已完成练习"),
            "{exercise}"
        );
        insta::assert_snapshot!(format!("zh-{size}-exercise"), exercise);
        app.update(Action::Back);
    }
    let small = checked_screen(&app, 60, 20)?;
    assert!(small.contains("至少需要 80×24"), "{small}");
    Ok(())
}

#[test]
fn l_switches_the_language_live_and_keeps_the_place() -> TestResult {
    use crossterm::event::{KeyCode, KeyEvent, KeyModifiers};
    use ppo_tutor::tui::keys::{Context, map};
    assert_eq!(
        map(
            KeyEvent::new(KeyCode::Char('L'), KeyModifiers::SHIFT),
            Context::default()
        ),
        Some(Action::Language)
    );
    let quiz = Context {
        overlay_open: true,
        quiz_open: true,
        ..Context::default()
    };
    assert_eq!(
        map(KeyEvent::new(KeyCode::Char('L'), KeyModifiers::SHIFT), quiz),
        Some(Action::Language),
        "L is not typed into a quiz answer"
    );

    let _en = Lang::En.scoped();
    let mut app = app()?;
    // Only this test thread's language switches: the other tests render English meanwhile.
    app.thread_language = true;
    open(&mut app, "gae")?;
    app.update(Action::Next);
    let place = (app.lesson, app.step);
    let english_title = app.current_lesson().ok_or("no lesson")?.title.clone();
    let chinese_title = Course::embedded_in(Lang::Zh)?.lessons[app.lesson]
        .title
        .clone();
    let header = |text: &str| text.lines().next().unwrap_or_default().to_string();
    let english = screen(&app, 160, 50)?;
    assert!(english.contains(" L 中文 "), "{english}");
    assert!(header(&english).contains(&format!("{english_title} · step 2/")));

    app.update(Action::Language);
    assert_eq!(Lang::current(), Lang::Zh);
    assert_eq!((app.lesson, app.step), place, "the same lesson and step");
    let chinese = checked_screen(&app, 160, 50)?;
    assert!(
        header(&chinese).contains(&format!("{chinese_title} · 第 2/")),
        "{chinese}"
    );
    assert!(chinese.contains(" L English ") && chinese.contains("语言：中文"));

    app.update(Action::Language);
    assert_eq!(Lang::current(), Lang::En);
    assert_eq!((app.lesson, app.step), place);
    let back = screen(&app, 160, 50)?;
    assert_eq!(header(&back), header(&english), "English again");
    assert!(back.contains("language: English"));

    // Over an overlay: the quiz stays open on the same question, in the other language.
    let steps = app.current_lesson().map_or(0, |l| l.steps.len());
    for _ in app.step..steps {
        app.update(Action::Next);
    }
    app.update(Action::Next);
    assert_eq!((app.overlay, app.quiz.question()), (Overlay::Quiz, 1));
    app.update(Action::Language);
    assert_eq!((app.overlay, app.quiz.question()), (Overlay::Quiz, 1));
    let quiz = checked_screen(&app, 160, 50)?;
    assert!(quiz.contains("检验一下：第 2/"), "{quiz}");
    app.update(Action::Language);
    assert!(screen(&app, 160, 50)?.contains("Check your understanding: question 2/"));
    drop(app);
    assert_eq!(
        Lang::current(),
        Lang::En,
        "the thread's language is restored"
    );
    Ok(())
}

/// A status line about one lesson (its quiz, its hints) does not follow the
/// learner into the next.
#[test]
fn a_lesson_s_status_line_does_not_follow_into_another_lesson() -> TestResult {
    let mut app = app()?;
    open(&mut app, "gae")?;
    let hints = app
        .current_lesson()
        .and_then(|l| l.exercise.as_ref())
        .map_or(0, |e| e.hints.len());
    for _ in 0..=hints {
        app.update(Action::Hint);
    }
    assert!(
        app.status.text().contains("hints are shown"),
        "{}",
        app.status
    );
    app.update(Action::Back);
    open(&mut app, "cartpole")?;
    assert!(!app.status.text().contains("hints"), "{}", app.status);

    open_quiz(&mut app, "what-is-ppo")?;
    assert!(
        !app.status.text().is_empty(),
        "the quiz says which question is open"
    );
    let quiz_status = app.status.clone();
    app.update(Action::Back);
    open(&mut app, "cartpole")?;
    assert_ne!(app.status, quiz_status);
    assert!(!app.status.text().contains("question"), "{}", app.status);
    Ok(())
}

/// A status message belongs to the face that set it and goes when that
/// face closes; the lesson view's own messages and warnings stay.
#[test]
fn each_face_s_status_line_goes_when_it_closes() -> TestResult {
    let mut app = app()?;
    open(&mut app, "gae")?;
    app.update(Action::Hint);
    assert_eq!(app.overlay, Overlay::Exercise);
    assert!(app.status.text().contains("hint 1/"), "{}", app.status);
    app.update(Action::Back);
    assert_eq!(
        app.status.text(),
        "",
        "the hint's message closed with the panel"
    );

    open_quiz(&mut app, "what-is-ppo")?;
    assert!(app.status.text().contains("question 1/"), "{}", app.status);
    app.update(Action::Back);
    assert_eq!(
        app.status.text(),
        "",
        "the quiz's message closed with the quiz"
    );

    app.update(Action::OneEpisode);
    let said = app.status.text().to_string();
    for face in [Action::Help, Action::Lessons, Action::Sandbox] {
        app.update(face);
        app.update(Action::Back);
        assert_eq!(
            app.status.text(),
            said,
            "{face:?} keeps the lesson view's message"
        );
    }

    app.warn("the progress file was corrupt");
    let warning = app.status.text().to_string();
    assert_eq!(warning, "warning: the progress file was corrupt");
    app.update(Action::Help);
    app.update(Action::Back);
    open(&mut app, "cartpole")?;
    assert_eq!(app.status.text(), warning, "a warning stays until read");
    Ok(())
}

/// At 80×24 a quiz question's feedback (each choice's explanation)
/// scrolls, and the panel says that more follows; the keys stay on its last row.
#[test]
fn quiz_feedback_scrolls_at_80x24_and_says_more_follows() -> TestResult {
    use ppo_tutor::lesson::quiz::{Answer, QuestionKind, letter_of};
    let mut app = app()?;
    let mut scrolled = 0;
    let ids: Vec<String> = app.course.lessons.iter().map(|l| l.id.clone()).collect();
    for id in ids {
        open_quiz(&mut app, &id)?;
        let Some(QuestionKind::Choice {
            answer: Answer::Letter(answer),
            ..
        }) = app.quiz_question(0).map(|q| q.kind.clone())
        else {
            continue;
        };
        app.update(Action::Type(letter_of(answer)));
        let text = screen(&app, 80, 24)?;
        assert!(
            text.contains("Esc back to the lesson"),
            "{id}: the keys show\n{text}"
        );
        if !text.contains("more lines: ↓ scrolls") {
            continue;
        }
        scrolled += 1;
        for _ in 0..200 {
            app.update(Action::Down);
        }
        let end = screen(&app, 80, 24)?;
        assert!(end.contains("lines above: ↑ scrolls"), "{id}\n{end}");
        assert!(
            !end.contains("more lines: ↓ scrolls"),
            "{id}: ↓ reaches the end\n{end}"
        );
        let verdict = app.quiz.verdict.clone().ok_or("no verdict")?;
        let last = verdict.text.lines().last().unwrap_or_default();
        let tail: String = last
            .chars()
            .rev()
            .take(8)
            .collect::<Vec<_>>()
            .into_iter()
            .rev()
            .collect();
        assert!(
            inside_box(&end, "┌ quiz")
                .replace(' ', "")
                .contains(&tail.replace(' ', "")),
            "{id}: the feedback's last words {tail:?} show at the end\n{end}"
        );
        app.update(Action::Back);
    }
    assert!(
        scrolled > 0,
        "some feedback is longer than an 80×24 quiz panel"
    );
    Ok(())
}

/// Answering a question again shows that only the first answer counts.
#[test]
fn answering_again_says_only_the_first_answer_counts() -> TestResult {
    use ppo_tutor::lesson::quiz::letter_of;
    let mut app = app()?;
    open_quiz(&mut app, "what-is-ppo")?;
    let (answer, _) = fixed_choice(&app, 0)?;
    app.update(Action::Type(letter_of((answer + 1) % 4)));
    assert!(!screen(&app, 160, 50)?.contains("first answer counts"));
    app.update(Action::Type(letter_of(answer)));
    let text = screen(&app, 160, 50)?;
    assert!(
        text.contains("Only your first answer counts toward the score (it was not right)"),
        "{text}"
    );
    assert_eq!(app.progress.quiz.get("what-is-ppo#1"), Some(&false));
    Ok(())
}

/// The explanation says when more of it is below, and ↓ stops at its
/// end (so ↑ moves at once after holding ↓).
#[test]
fn the_explanation_says_more_follows_and_stops_at_its_end() -> TestResult {
    let mut app = app()?;
    open(&mut app, "gae")?;
    let text = screen(&app, 80, 24)?;
    assert!(text.contains("more lines: ↓ scrolls"), "{text}");
    for _ in 0..1000 {
        app.update(Action::ScrollDown);
    }
    let end = app.explanation.scroll();
    assert!(end > 0 && end < 1000, "{end}");
    let text = screen(&app, 80, 24)?;
    assert!(!text.contains("more lines: ↓ scrolls"), "{text}");
    assert!(text.contains("lines above: ↑ scrolls"), "{text}");
    app.update(Action::ScrollUp);
    assert_eq!(app.explanation.scroll(), end - 1);
    Ok(())
}

/// `r` while training: an episode the old run finished before the worker read the reset
/// (already on its way) is not shown over the fresh agent, nor is its end.
#[test]
fn r_while_training_drops_what_the_old_run_sent_after_it() -> TestResult {
    let mut app = app()?;
    let old = Session::run(PpoConfig::default(), 0, 3)?;
    app.update(Action::TrainToggle);
    app.update(Action::ResetAgent);
    let fresh = app.run.snapshot.clone();
    assert_eq!(fresh.episodes, 0, "a fresh agent shows at once");
    app.on_worker(WorkerEvent::Episode {
        run: 0,
        snapshot: Box::new(old.clone()),
    });
    app.on_worker(WorkerEvent::Finished { run: 0 });
    assert_eq!(app.run.snapshot, fresh, "the old run's episode is dropped");
    assert_eq!(app.run.train, TrainState::Paused);
    let header = screen(&app, 160, 50)?;
    assert!(header.contains("episode 0"), "{header}");
    // The new run's own episodes are shown.
    app.on_worker(WorkerEvent::Episode {
        run: app.run.id,
        snapshot: Box::new(old.clone()),
    });
    assert_eq!(app.run.snapshot, old);
    Ok(())
}

/// The worker's confirmation of a fresh agent does not overwrite what the app said when it
/// asked for it ("a Pendulum-v1 lesson: fresh agent …").
#[test]
fn the_worker_s_reset_does_not_overwrite_the_lesson_s_message() -> TestResult {
    let mut app = app()?;
    open(&mut app, "continuous-actions")?;
    assert!(
        app.status.text().contains("Pendulum-v1 lesson"),
        "{}",
        app.status
    );
    app.on_worker(WorkerEvent::Reset { seed: 0 });
    assert!(
        app.status.text().contains("Pendulum-v1 lesson"),
        "{}",
        app.status
    );
    Ok(())
}

/// At 80×24 the key bar keeps stepping, help and quit (the least
/// essential keys make room), in both languages; a warning comes first in the status line.
#[test]
fn the_key_bar_keeps_help_and_quit_at_80x24() -> TestResult {
    for (lang, help, quit) in [
        (Lang::En, "? help", "q quit"),
        (Lang::Zh, "? 帮助", "q 退出"),
    ] {
        let _lang = lang.scoped();
        let mut app = app()?;
        let text = screen(&app, 80, 24)?;
        let keys = text.lines().nth(22).ok_or("no key bar")?;
        assert!(keys.contains(help) && keys.contains(quit), "{keys}");
        assert!(keys.contains("←/→"), "{keys}");
        app.warn("a long warning about /some/long/path/.ppo-tutor-state.json");
        let text = screen(&app, 80, 24)?;
        let status = text.lines().nth(23).ok_or("no status line")?;
        assert!(status.contains("/some/long/path"), "{status}");
    }
    Ok(())
}

/// The rows of the right-hand pane titled one of `titles` on a screen from
/// [`checked_screen`]: what lies right of the text pane (`││`), from the pane's title to
/// its bottom border.
fn pane_rows(screen: &str, titles: &[&str]) -> Vec<String> {
    let mut rows = Vec::new();
    let mut inside = false;
    for line in screen.lines() {
        if titles.iter().any(|t| line.contains(&format!("┌ {t}"))) {
            inside = true;
        } else if inside {
            if line.contains('└') {
                break;
            }
            if let Some((_, right)) = line.rsplit_once("││") {
                rows.push(right.trim_end_matches(['"', '│']).to_string());
            }
        }
    }
    rows
}

/// The live-values pane's rows ([`pane_rows`]), in either language.
fn live_pane(screen: &str) -> Vec<String> {
    pane_rows(screen, &["live values", "实时数值"])
}

/// The column headers the live pane shows: its table's header row (the row that starts
/// with the step column `t`, or with a grid's first `θ=` column) split at spaces.
fn live_headers(screen: &str) -> Vec<String> {
    live_pane(screen)
        .iter()
        .map(|row| row.split_whitespace().map(String::from).collect::<Vec<_>>())
        .find(|cells| {
            cells
                .first()
                .is_some_and(|c| c == "t" || c.starts_with("θ="))
        })
        .unwrap_or_default()
}

/// At 80×24, every live column a step's text names is shown whole or
/// reached with `>` from a visible marker that says so; the policy maps label θ̇ down the
/// rows and θ across. Both languages; snapshots at offset 0 (English: the Chinese ones are
/// in the 80×24 course snapshots) and scrolled to the last column named (both).
#[test]
fn live_columns_the_text_names_fit_or_scroll_at_80x24() -> TestResult {
    let cases: [(&str, usize, &[&str]); 8] = [
        ("cartpole", 5, &["terminated", "truncated", "dones"]),
        ("episode-loop", 2, &["π(left)", "π(right)", "actions"]),
        ("episode-loop", 3, &["terminated", "truncated", "dones"]),
        (
            "episode-loop",
            4,
            &["states.x", "actions", "rewards", "next_states.x", "dones"],
        ),
        ("clipping", 1, &["ratio", "advantage", "surr1", "surr2"]),
        ("clipping", 3, &["surr1", "surr2"]),
        ("pendulum", 4, &["θ=-π", "θ=0", "θ=π"]),
        ("pendulum", 5, &["θ=-π", "θ=0", "θ=π"]),
    ];
    for (lang, marker, lang_code) in [(Lang::En, "more column", "en"), (Lang::Zh, "还有", "zh")] {
        let _lang = lang.scoped();
        let mut app = app()?;
        for (id, step, names) in cases {
            open(&mut app, id)?;
            show_pendulum_run(&mut app)?;
            for _ in 1..step {
                app.update(Action::Next);
            }
            let name = format!("live-80x24-{lang_code}-{id}-step{step}");
            let text = checked_screen(&app, 80, 24).map_err(|e| format!("{name}: {e}"))?;
            if lang == Lang::En {
                insta::assert_snapshot!(name.clone(), text);
            }
            if id == "pendulum" {
                let pane = live_pane(&text);
                for row in ["θ̇=8 ", "θ̇=0 ", "θ̇=-8 "] {
                    assert!(
                        pane.iter().any(|r| r.trim_start().starts_with(row)),
                        "{name}: no row {row:?}\n{text}"
                    );
                }
                assert!(!live_headers(&text).contains(&"t".to_string()), "{name}");
            }
            let mut scrolled = false;
            for column in names {
                let shown = |app: &App| -> Result<bool, Box<dyn std::error::Error>> {
                    let text = checked_screen(app, 80, 24)?;
                    Ok(live_headers(&text).iter().any(|h| h == column))
                };
                if shown(&app)? {
                    continue;
                }
                let text = checked_screen(&app, 80, 24)?;
                assert!(
                    live_pane(&text)
                        .iter()
                        .any(|r| r.contains(marker) && r.contains('>')),
                    "{name}: {column} is neither shown nor announced\n{text}"
                );
                for _ in 0..20 {
                    if shown(&app)? {
                        break;
                    }
                    app.update(Action::TensorRight);
                    scrolled = true;
                }
                assert!(shown(&app)?, "{name}: > never reaches {column}");
            }
            if scrolled {
                let text = checked_screen(&app, 80, 24)?;
                assert!(
                    live_pane(&text).iter().any(|r| r.contains('←')),
                    "{name}: scrolled, but nothing says columns precede\n{text}"
                );
                insta::assert_snapshot!(format!("{name}-scrolled"), text);
            }
        }
    }
    Ok(())
}

/// A live tensor's title line wider than the pane ends in a `…`, as
/// a cut code line does.
#[test]
fn cut_tensor_title_lines_show_that_they_go_on() -> TestResult {
    let mut app = app()?;
    open(&mut app, "clipping")?;
    app.update(Action::Next);
    let text = screen(&app, 80, 24)?;
    let title = text
        .lines()
        .find(|l| l.contains("ratio (29, 1) float32"))
        .ok_or("no ratio title line")?;
    assert!(title.ends_with("…│\""), "{title}");
    Ok(())
}

/// A code line wider than the code pane wraps (its rest after a dim `↪`), nothing is cut;
/// code below the pane's last row is counted there, and `]` / `[` scroll the pane.
#[test]
fn code_lines_wrap_and_the_code_pane_scrolls() -> TestResult {
    let _en = Lang::En.scoped();
    let mut app = app()?;
    open(&mut app, "td-target")?;
    let code_rows = |text: &str| pane_rows(text, &["the code that runs"]);
    let text = screen(&app, 80, 24)?;
    let rows = code_rows(&text);
    assert!(!rows.iter().any(|r| r.trim_end().ends_with('…')), "{text}");
    let last = rows.last().ok_or("no code rows")?;
    assert!(last.contains("more lines: ] scrolls"), "{text}");
    let first = rows.first().cloned().unwrap_or_default();
    let mut seen = rows.clone();
    for _ in 0..200 {
        app.update(Action::CodeDown);
        seen.extend(code_rows(&screen(&app, 80, 24)?));
    }
    let end = code_rows(&screen(&app, 80, 24)?);
    assert!(end[0].contains("lines above: [ scrolls"), "{end:#?}");
    assert!(!end.iter().any(|r| r.contains("more lines")), "{end:#?}");
    assert!(
        seen.iter().any(|r| r.contains('↪')),
        "a wrapped line continues after ↪: {seen:#?}"
    );
    // Every line of the step's code was on screen at some scroll.
    let step = app.current_step().ok_or("no step")?;
    let lesson = app.current_lesson().ok_or("no lesson")?;
    let pane = ppo_tutor::tui::ui::code_pane_text(lesson, app.step, &|_| false);
    for line in pane.lines().filter(|l| l.len() > 3 && l.len() < 30) {
        assert!(
            seen.iter().any(|r| r.contains(line.trim())),
            "{line:?} never shown ({})",
            step.title
        );
    }
    for _ in 0..200 {
        app.update(Action::CodeUp);
    }
    assert_eq!(code_rows(&screen(&app, 80, 24)?)[0], first);
    // A new step starts at the top.
    app.update(Action::CodeDown);
    app.update(Action::Next);
    assert!(!screen(&app, 80, 24)?.contains("lines above: ["));
    Ok(())
}

/// While the terminal is too small, the screen says so and keys act on nothing but `q`.
#[test]
fn keys_wait_while_the_terminal_is_too_small() -> TestResult {
    use crossterm::event::{Event as Input, KeyCode, KeyEvent, KeyModifiers};
    use ppo_tutor::tui::{Event, handle};
    let _en = Lang::En.scoped();
    let mut app = app()?;
    let key = |c: char| {
        Event::Input(Input::Key(KeyEvent::new(
            KeyCode::Char(c),
            KeyModifiers::NONE,
        )))
    };
    handle(&mut app, Event::Input(Input::Resize(60, 20)));
    assert!(app.too_small);
    let text = screen(&app, 60, 20)?;
    assert!(text.contains("needs at least 80×24"), "{text}");
    let before = (app.lesson, app.step, app.overlay);
    for c in ['n', 'l', 's', '?', 't', 'r'] {
        handle(&mut app, key(c));
    }
    assert_eq!((app.lesson, app.step, app.overlay), before);
    assert!(app.run.outbox.is_empty(), "{:?}", app.run.outbox);
    handle(&mut app, Event::Input(Input::Resize(80, 24)));
    handle(&mut app, key('n'));
    assert_eq!(app.step, before.1 + 1, "keys act again once it fits");
    handle(&mut app, Event::Input(Input::Resize(60, 20)));
    handle(&mut app, key('q'));
    assert!(app.quit, "q still quits");
    Ok(())
}

/// The status line says the latest message first and whole, at 80×24 and at 160×50 (on a
/// second row when it needs one): "all 500 episodes done: r resets the agent, s opens the
/// sandbox" is not cut after "done".
#[test]
fn the_latest_message_is_read_whole_at_both_sizes() -> TestResult {
    for lang in [Lang::En, Lang::Zh] {
        let _lang = lang.scoped();
        let mut app = app()?;
        open(&mut app, "losses")?;
        app.run.train = TrainState::Finished;
        app.update(Action::TrainToggle);
        let message = app.status.text().to_string();
        assert!(!message.is_empty());
        for (width, height) in [(80, 24), (160, 50)] {
            let text = screen(&app, width, height)?;
            let footer: Vec<&str> = text.lines().rev().take(3).collect();
            let joined: String = footer
                .iter()
                .rev()
                .map(|l| l.trim_matches('"').trim())
                .collect::<Vec<_>>()
                .join("");
            let squeezed: String = message.split_whitespace().collect();
            let on_screen: String = joined.split_whitespace().collect();
            assert!(
                on_screen.contains(&squeezed),
                "{width}x{height}: {message:?} not whole in\n{text}"
            );
        }
    }
    Ok(())
}

/// `d` opens a step's details blocks one at a time and only on that step: a block to read
/// after a prediction stays folded when one was opened elsewhere.
#[test]
fn d_opens_one_block_of_one_step() -> TestResult {
    let _en = Lang::En.scoped();
    let mut app = app()?;
    open(&mut app, "cartpole")?;
    while !app
        .current_step()
        .is_some_and(|s| ppo_tutor::lesson::details::has_details(&s.body))
    {
        app.update(Action::Next);
    }
    app.update(Action::Details);
    assert!(screen(&app, 140, 45)?.contains("explicit Euler"));
    open(&mut app, "trust-region")?;
    while !app
        .current_step()
        .is_some_and(|s| s.body.contains("open after you have predicted"))
    {
        app.update(Action::Next);
        assert!(app.overlay != Overlay::Quiz, "no such step");
    }
    assert_eq!(app.explanation.opened(&app.ctx()), 0);
    let mut text = String::new();
    for _ in 0..100 {
        text.push_str(&screen(&app, 160, 50)?);
        app.update(Action::ScrollDown);
    }
    assert!(
        text.contains("▸ Details: What five seeds showed (open after you have predicted)"),
        "the prediction's answer stays folded:\n{text}"
    );
    // Coming back to the first step, its block is still open.
    open(&mut app, "cartpole")?;
    while !app
        .current_step()
        .is_some_and(|s| ppo_tutor::lesson::details::has_details(&s.body))
    {
        app.update(Action::Next);
    }
    assert!(screen(&app, 140, 45)?.contains("explicit Euler"));
    Ok(())
}

/// A question that asks for a number of the run hides the live values behind it until it
/// is answered (lesson 7's last question asks δ_0, which row 0 of td_delta shows).
#[test]
fn an_open_prediction_hides_the_live_values() -> TestResult {
    use ppo_tutor::lesson::quiz::QuestionKind;
    let _en = Lang::En.scoped();
    let mut app = app()?;
    open_quiz(&mut app, "td-target")?;
    let count = app.current_lesson().map_or(0, |l| l.quiz.len());
    let mut found = false;
    for i in 0..count {
        let Some(q) = app.quiz_question(i).cloned() else {
            continue;
        };
        if let QuestionKind::Predict { .. } = q.kind {
            found = true;
            let text = screen(&app, 160, 50)?;
            assert!(app.live_hidden(), "question {}", i + 1);
            assert!(
                text.contains("hidden while the quiz question is open"),
                "{text}"
            );
            assert!(!text.contains("td_delta ("), "{text}");
            for c in "0.5".chars() {
                app.update(Action::Type(c));
            }
            app.update(Action::Enter);
            assert!(!app.live_hidden(), "answered: the values come back");
            assert!(!screen(&app, 160, 50)?.contains("hidden while the quiz"));
        }
        app.update(Action::Next);
    }
    assert!(found, "lesson 7 has a prediction");
    Ok(())
}

/// A letter that is not one of the choices is said to be so, in the app's words (not the
/// notebook's "put your choice in place of").
#[test]
fn a_letter_past_the_choices_says_which_letters_answer() -> TestResult {
    use ppo_tutor::lesson::quiz::QuestionKind;
    let _en = Lang::En.scoped();
    let mut app = app()?;
    for lesson in app.course.lessons.clone() {
        for (i, q) in lesson.quiz.iter().enumerate() {
            let QuestionKind::Choice { choices, .. } = &q.kind else {
                continue;
            };
            if choices.len() >= 4 {
                continue;
            }
            open_quiz(&mut app, &lesson.id)?;
            for _ in 0..i {
                app.update(Action::Next);
            }
            app.update(Action::Type('d'));
            let said = app.status.text().to_string();
            assert!(
                said.contains("not one of the choices: answer with a–c"),
                "{said}"
            );
            assert!(!said.contains("in place of"), "{said}");
            assert!(!app.quiz.answered());
            return Ok(());
        }
    }
    Err("no question with three choices".into())
}

/// After a sandbox change the header says the live agent runs the learner's settings, and
/// the status line names what differs from the lessons'.
#[test]
fn the_app_says_when_the_agent_runs_other_settings() -> TestResult {
    let _en = Lang::En.scoped();
    let mut app = app()?;
    assert!(!screen(&app, 160, 50)?.contains("your settings"));
    app.update(Action::Sandbox);
    app.sandbox.selected = "eps";
    app.update(Action::Increase);
    app.update(Action::Enter);
    let said = app.status.text().to_string();
    assert!(
        said.contains("not the lessons' settings: eps 0.25 (0.2)"),
        "{said}"
    );
    assert!(screen(&app, 160, 50)?.contains("your settings"));
    app.update(Action::Sandbox);
    app.sandbox.selected = "eps";
    app.update(Action::Decrease);
    app.update(Action::Enter);
    assert!(app.status.text().contains("with the lessons' settings"));
    assert!(!screen(&app, 160, 50)?.contains("your settings"));
    Ok(())
}

/// `x` on a step without an experiment names the lessons that have one, from the course.
#[test]
fn x_without_an_experiment_names_the_lessons_with_one() -> TestResult {
    let _en = Lang::En.scoped();
    let mut app = app()?;
    app.update(Action::RunLab);
    let said = app.status.text().to_string();
    let with: Vec<String> = app
        .course
        .lessons
        .iter()
        .filter(|l| l.steps.iter().any(|s| s.lab.is_some()))
        .map(|l| l.order.to_string())
        .collect();
    assert!(with.len() >= 4, "{with:?}");
    assert!(
        said.contains(&format!("lessons {} have them", with.join(", "))),
        "{said}"
    );
    Ok(())
}

/// PgDn/PgUp move the live tables a page, Home/End to their first and last rows.
#[test]
fn page_keys_and_home_end_scroll_the_live_tables() -> TestResult {
    let _en = Lang::En.scoped();
    let mut app = App::new(Course::embedded()?, Progress::default(), None);
    app.show(Session::run(PpoConfig::default(), 0, 30)?);
    open(&mut app, "training")?;
    let rows = |app: &App| -> Result<Vec<String>, Box<dyn std::error::Error>> {
        Ok(live_pane(&screen(app, 80, 24)?))
    };
    let first = rows(&app)?;
    assert!(
        first
            .iter()
            .any(|r| r.split_whitespace().next() == Some("1")),
        "{first:#?}"
    );
    app.update(Action::TensorLast);
    let last = rows(&app)?;
    assert!(
        last.iter()
            .any(|r| r.split_whitespace().next() == Some("30")),
        "{last:#?}"
    );
    assert!(last.iter().any(|r| r.contains("of 30")), "{last:#?}");
    app.update(Action::TensorFirst);
    assert_eq!(rows(&app)?, first);
    app.update(Action::TensorPageDown);
    let paged = rows(&app)?;
    assert_ne!(paged, first);
    assert!(
        !paged
            .iter()
            .any(|r| r.split_whitespace().next() == Some("1")),
        "{paged:#?}"
    );
    app.update(Action::TensorPageUp);
    assert_eq!(rows(&app)?, first);
    Ok(())
}

/// Over a trained curve (it runs along the top right, where ratatui
/// drew its legend) the plot's legend has a row of its own, with no data on it, at both
/// sizes and in both languages.
#[test]
fn the_plot_legend_stays_whole_over_a_trained_curve() -> TestResult {
    for (lang, names) in [
        (Lang::En, ["returns", "moving average (9)"]),
        (Lang::Zh, ["回报", "移动平均（9）"]),
    ] {
        let _lang = lang.scoped();
        let mut app = app()?;
        open(&mut app, "training")?;
        app.update(Action::Next);
        // 300 episodes: a climb, then the cap of 500 with a few falls back.
        app.run.snapshot.returns = (0..300_u32)
            .map(|i| match i {
                0..80 => f64::from(10 + 6 * i),
                _ if i % 23 == 0 => 180.0,
                _ => 500.0,
            })
            .collect();
        app.run.snapshot.moving_average =
            ppo_tutor::ppo::moving_average(&app.run.snapshot.returns, 9)?;
        app.run.snapshot.episodes = 300;
        for (width, height) in [(80, 24), (160, 50)] {
            let text = screen(&app, width, height)?;
            let row = text
                .lines()
                .find(|l| names.iter().all(|n| l.contains(n)))
                .ok_or_else(|| format!("no legend row:\n{text}"))?;
            assert!(
                !row.chars().any(|c| ('\u{2800}'..='\u{28FF}').contains(&c)
                    || matches!(c, '▀' | '▄' | '█')),
                "data on the legend's row:\n{text}"
            );
            insta::assert_snapshot!(
                format!("{}-{width}x{height}-trained-plot", lang.code()),
                text
            );
        }
    }
    Ok(())
}

/// `<` and `>` scroll the live tables by a column, stop at the first
/// and the last, and a new step starts at the first.
#[test]
fn angle_brackets_scroll_the_live_columns() -> TestResult {
    use crossterm::event::{KeyCode, KeyEvent, KeyModifiers};
    use ppo_tutor::tui::keys::{Context, map};
    let key = |c| {
        map(
            KeyEvent::new(KeyCode::Char(c), KeyModifiers::NONE),
            Context::default(),
        )
    };
    assert_eq!(key('>'), Some(Action::TensorRight));
    assert_eq!(key('<'), Some(Action::TensorLeft));
    let help: Vec<_> = ppo_tutor::tui::keys::help();
    assert!(help.iter().any(|(k, _)| k.contains("< / >")), "{help:?}");

    let mut app = app()?;
    open(&mut app, "episode-loop")?;
    app.update(Action::TensorLeft);
    assert_eq!(app.tensor_hscroll, 0, "< at the first column stays");
    app.update(Action::Next); // obs, probs, actions: 7 columns
    for _ in 0..20 {
        app.update(Action::TensorRight);
    }
    assert_eq!(app.tensor_hscroll, 6, "> stops at the last column");
    let text = screen(&app, 80, 24)?;
    assert_eq!(live_headers(&text), ["t", "actions"], "{text}");
    app.update(Action::TensorLeft);
    assert_eq!(app.tensor_hscroll, 5);
    app.update(Action::Next);
    assert_eq!(
        app.tensor_hscroll, 0,
        "a new step starts at the first column"
    );
    Ok(())
}

/// Every step that shows a per-epoch value (the losses, approx_kl, clip_frac, the ratios'
/// extremes, the entropy) shows its first epoch as row 1 and, after End, its last, at
/// 80×24 and 160×50 in both languages: lesson 12's "in the first epoch … the actor loss
/// equals minus the mean of the advantage column" and "the ratios start at exactly 1", and
/// lesson 13's "approx_kl is 0 in the first epoch" ask for those rows.
#[test]
fn every_step_showing_epochs_shows_the_first_and_the_last() -> TestResult {
    use ppo_tutor::lesson::Index;
    for lang in [Lang::En, Lang::Zh] {
        let _lang = lang.scoped();
        let corner = lang.pick("epoch", "轮");
        let mut app = app()?;
        let total = app.course.total_steps();
        let mut checked = 0;
        for i in 0..total {
            show_pendulum_run(&mut app)?;
            let step = app.current_step().ok_or("no step")?.clone();
            let epochs = step
                .show
                .iter()
                .filter_map(|n| app.run.snapshot.tensor(n))
                .filter(|t| t.index == Index::Epoch)
                .map(|t| t.values.len())
                .max();
            if let Some(epochs) = epochs {
                let lesson = app.current_lesson().ok_or("no lesson")?;
                let name = format!("{} step {}", lesson.id, app.step + 1);
                for (width, height) in [(80, 24), (160, 50)] {
                    let row_of = |text: &str, e: usize| {
                        live_pane(text)
                            .iter()
                            .any(|r| r.split_whitespace().next() == Some(e.to_string().as_str()))
                    };
                    let text = screen(&app, width, height)?;
                    let pane = live_pane(&text);
                    assert!(
                        pane.iter().any(|r| r.trim_start().starts_with(corner)),
                        "{name} {width}x{height}: no epoch table\n{text}"
                    );
                    assert!(
                        row_of(&text, 1),
                        "{name} {width}x{height}: no epoch 1\n{text}"
                    );
                    app.update(Action::TensorLast);
                    let text = screen(&app, width, height)?;
                    assert!(
                        row_of(&text, epochs),
                        "{name} {width}x{height}: End shows no epoch {epochs}\n{text}"
                    );
                    app.update(Action::TensorFirst);
                }
                checked += 1;
            }
            if i + 1 < total {
                app.update(Action::Next);
            }
            if app.overlay == Overlay::Quiz {
                let questions = app.current_lesson().map_or(0, |l| l.quiz.len());
                for _ in 0..questions {
                    app.update(Action::Next);
                }
            }
        }
        assert!(checked >= 8, "{lang:?}: only {checked} steps show epochs");
    }
    Ok(())
}

/// A question seen again shows the latest answer to it: a fixed choice with its verdict
/// and explanations, a prediction as a line (its verdict was about another run's numbers),
/// kept in the progress as text.
#[test]
fn a_question_seen_again_shows_the_earlier_answer() -> TestResult {
    use ppo_tutor::lesson::quiz::{QuestionKind, letter_of};
    let _en = Lang::En.scoped();
    let mut app = app()?;
    open_quiz(&mut app, "what-is-ppo")?;
    let (answer, choices) = fixed_choice(&app, 0)?;
    let wrong = (answer + 1) % choices.len();
    app.update(Action::Type(letter_of(wrong)));
    assert_eq!(
        app.progress.answer("what-is-ppo", 1),
        Some(choices[wrong].as_str())
    );
    app.update(Action::Back);
    open_quiz(&mut app, "what-is-ppo")?;
    let text = screen(&app, 160, 50)?;
    assert!(
        text.contains(&format!("✗ Not {})", letter_of(wrong))),
        "{text}"
    );
    assert!(text.contains("(it was not right)"), "{text}");
    // A prediction: the number typed, as a line.
    open_quiz(&mut app, "td-target")?;
    let count = app.current_lesson().map_or(0, |l| l.quiz.len());
    for i in 0..count {
        if matches!(
            app.quiz_question(i).map(|q| &q.kind),
            Some(QuestionKind::Predict { .. })
        ) {
            for c in "0.25".chars() {
                app.update(Action::Type(c));
            }
            app.update(Action::Enter);
            app.update(Action::Back);
            open_quiz(&mut app, "td-target")?;
            for _ in 0..i {
                app.update(Action::Next);
            }
            let text = screen(&app, 160, 50)?;
            assert!(text.contains("Your answer last time: 0.25"), "{text}");
            assert!(!app.quiz.answered(), "a new prediction can be typed");
            return Ok(());
        }
        app.update(Action::Next);
    }
    Err("lesson 7 has a prediction".into())
}

/// While the candle exercise's first build runs, the panel and the status line say what
/// cargo is compiling (the grading runs on its own thread: the screen is never stuck on a
/// fixed line), and the line goes when the grading ends.
#[test]
fn a_grading_s_progress_shows_while_it_builds() -> TestResult {
    use ppo_tutor::grade::GradeProgress;
    let _en = Lang::En.scoped();
    let mut app = app()?;
    open(&mut app, "losses")?;
    app.update(Action::Grade);
    assert!(app.exercise.grading && app.exercise.request.is_some());
    app.on_grade_progress(GradeProgress::Compiling {
        krate: "candle-core".into(),
        done: 37,
        total: 120,
        first_time: true,
    });
    let text = screen(&app, 160, 50)?;
    assert!(
        text.contains("candle-core") && text.contains("37/120"),
        "{text}"
    );
    assert!(app.status.text().contains("37/120"), "{}", app.status);
    app.on_graded(Vec::<ppo_tutor::tui::app::Graded>::new());
    assert!(app.exercise.progress.is_none());
    assert!(!screen(&app, 160, 50)?.contains("37/120"));
    Ok(())
}

/// The return plot's moving average follows the run's length: the seed's 9 episodes for
/// CartPole's 500, more for Pendulum's 2000 (39), said in the legend; its title names the
/// algorithm that trains.
#[test]
fn the_plot_s_window_and_title_follow_the_run() -> TestResult {
    let _en = Lang::En.scoped();
    let mut app = app()?;
    open(&mut app, "training")?;
    app.update(Action::Next);
    app.run.snapshot.returns = (0..30_u32).map(|i| f64::from(10 + 5 * i)).collect();
    app.run.snapshot.moving_average = ppo_tutor::ppo::moving_average(&app.run.snapshot.returns, 9)?;
    let text = screen(&app, 160, 50)?;
    assert!(
        text.contains("moving average (9)") && text.contains("PPO on CartPole-v1"),
        "{text}"
    );
    open(&mut app, "pendulum")?;
    let step = app
        .current_lesson()
        .and_then(|l| {
            l.steps
                .iter()
                .position(|s| s.show.iter().any(|v| v == "plot"))
        })
        .ok_or("no plot step in lesson 18")?;
    for _ in 0..step {
        app.update(Action::Next);
    }
    app.run.snapshot.returns = (0..300_u32).map(|i| -1500.0 + 4.0 * f64::from(i)).collect();
    app.run.snapshot.episodes = 300;
    let text = screen(&app, 160, 50)?;
    assert!(text.contains("moving average (39)"), "{text}");
    Ok(())
}
