//! The terminal app: the tutorial step by step, with live tensors and live plots.
//!
//! - [`app`]: what the faces share (course, live run, progress, status line) and the routing
//!   of every key to the open face; [`components`]: the faces (help, lesson list, sandbox,
//!   exercise panel, quiz, explanation, clip lab), each owning its state, keys and drawing;
//!   [`keys`]: key map; [`ui`]: the lesson view's drawing; [`theme`]: styles (`NO_COLOR`
//!   aware); [`widgets`]: plot, cart-pole, clip chart, tensors.
//! - [`worker`]: the engine's live training session on its own thread, talking to the UI
//!   over channels.
//!
//! The loop waits on one channel of [`Event`]s fed by an input thread, a ticker and the
//! worker, so the UI never blocks on training.

pub mod app;
pub mod components;
pub mod keys;
pub mod run;
pub mod theme;
pub mod ui;
pub mod widgets;
pub mod worker;

use std::io::IsTerminal;
use std::sync::mpsc::{self, Sender};
use std::time::Duration;

use anyhow::Context;
use crossterm::event::{self, DisableMouseCapture, EnableMouseCapture, MouseEventKind};

use crate::lesson::{Course, Progress};
use crate::ppo::lab::{self, Experiment};
use crate::watch::SaveWatcher;
use app::App;
use keys::Action;
use widgets::lab::LabState;
use worker::{Command, WorkerEvent};

/// What the event loop reacts to.
#[derive(Debug)]
pub enum Event {
    /// A key, mouse or resize event from the terminal.
    Input(event::Event),
    /// Animation tick.
    Tick,
    /// A message from the training worker.
    Worker(WorkerEvent),
    /// A grading started with `g` finished.
    Graded(Vec<app::Graded>),
    /// A grading under way did something new (built, compiled a crate, checked).
    GradeProgress(crate::grade::GradeProgress),
    /// A clip-lab experiment started with `x` progressed or ended.
    Lab(Experiment, LabState),
    /// The open lesson's exercise file was saved.
    Saved,
    /// The trust-region probe of the batch after this many episodes finished.
    Probe(
        usize,
        Result<Box<crate::ppo::trust_region::TrustRegionProbe>, String>,
    ),
    /// The process was asked to end (SIGTERM, SIGHUP, SIGINT from outside): the app saves
    /// the progress and restores the terminal, as `q` does.
    Signal(i32),
}

/// Frames per second of the cart-pole animation.
const TICK: Duration = Duration::from_millis(50);

/// Runs the tutor in the terminal until the learner quits (success) or a signal ends it
/// (128 + the signal's number, as a shell reports it). Unless the language was chosen
/// for this run (`chosen`: `--lang` or `PPO_TUTOR_LANG`), the one last chosen in the app
/// with `L` (kept in the progress file) is used.
///
/// # Errors
/// No terminal attached, the lessons cannot be loaded, terminal I/O fails, or the progress
/// could not be saved when leaving (the error says where and why).
pub fn run(chosen: bool) -> anyhow::Result<std::process::ExitCode> {
    if !std::io::stdout().is_terminal() || !std::io::stdin().is_terminal() {
        anyhow::bail!(crate::tr!(
            "ppo-tutor needs an interactive terminal; without one, use `ppo-tutor lessons` and `ppo-tutor show <id> [--step N]`",
            "ppo-tutor 需要交互式终端；没有终端时，请用 `ppo-tutor lessons` 和 `ppo-tutor show <课> [--step <节>]`"
        ));
    }
    let path = Progress::default_path();
    let (progress, warning) = Progress::load(&path);
    if !chosen && let Some(lang) = progress.language() {
        lang.set_current();
    }
    let course = Course::embedded().context(crate::i18n::t(
        "loading the embedded lessons",
        "加载内置课程",
    ))?;
    let mut app = App::new(course, progress, Some(path));
    if let Some(w) = warning {
        app.warn(&w);
    }
    let (tx, rx) = mpsc::channel::<Event>();
    let (cmd_tx, cmd_rx) = mpsc::channel::<Command>();
    let (worker_tx, worker_rx) = mpsc::channel::<WorkerEvent>();
    let worker = worker::spawn(app.run_config(), app.run.seed, cmd_rx, worker_tx);
    forward(worker_rx, tx.clone());
    spawn_input(tx.clone());
    spawn_ticker(tx.clone());
    let theme = theme::Theme::from_env();
    spawn_signals(tx.clone());
    let mut terminal = ratatui::init();
    let _ = crossterm::execute!(std::io::stdout(), EnableMouseCapture);
    // Start with one episode so every live value has something to show.
    let _ = cmd_tx.send(Command::OneEpisode);
    let result = event_loop(&mut terminal, &mut app, theme, &rx, (&cmd_tx, &tx));
    let _ = crossterm::execute!(std::io::stdout(), DisableMouseCapture);
    ratatui::restore();
    let _ = cmd_tx.send(Command::Quit);
    let _ = worker.join();
    // Once more, with the run's end recorded; an error now is the last word, on stderr.
    if let Err(said) = app.save_progress() {
        result?;
        anyhow::bail!(said);
    }
    result?;
    Ok(app.signal.map_or(std::process::ExitCode::SUCCESS, |sig| {
        std::process::ExitCode::from(u8::try_from(128 + sig).unwrap_or(1))
    }))
}

/// Turns SIGTERM, SIGHUP and SIGINT into [`Event::Signal`]: the loop then leaves as on `q`,
/// restoring the terminal (a default SIGTERM would leave it in the alternate screen with
/// the cursor hidden).
#[cfg(unix)]
fn spawn_signals(tx: Sender<Event>) {
    use signal_hook::consts::{SIGHUP, SIGINT, SIGTERM};
    let Ok(mut signals) = signal_hook::iterator::Signals::new([SIGTERM, SIGHUP, SIGINT]) else {
        return;
    };
    std::thread::spawn(move || {
        for signal in signals.forever() {
            if tx.send(Event::Signal(signal)).is_err() {
                return;
            }
        }
    });
}

#[cfg(not(unix))]
fn spawn_signals(_tx: Sender<Event>) {}

fn event_loop(
    terminal: &mut ratatui::DefaultTerminal,
    app: &mut App,
    theme: theme::Theme,
    rx: &mpsc::Receiver<Event>,
    (cmd_tx, tx): (&Sender<Command>, &Sender<Event>),
) -> anyhow::Result<()> {
    let mut watcher: Option<SaveWatcher> = None;
    // The lesson whose exercise files `watcher` was set up for (once per lesson opened, not
    // on every event).
    let mut watched_lesson = None;
    loop {
        if watched_lesson != Some(app.lesson) {
            watched_lesson = Some(app.lesson);
            watch_exercise_files(app, &mut watcher, tx);
        }
        if let Ok(size) = terminal.size() {
            app.resize(size.width, size.height);
        }
        terminal.draw(|f| f.render_widget(&ui::View { app, theme }, f.area()))?;
        let Ok(event) = rx.recv() else { return Ok(()) };
        handle(app, event);
        // Drain whatever else is queued before redrawing.
        while let Ok(event) = rx.try_recv() {
            handle(app, event);
        }
        for command in app.run.outbox.drain(..) {
            let _ = cmd_tx.send(command);
        }
        if let Some(names) = app.exercise.request.take() {
            spawn_grader(names, tx.clone());
        }
        if let Some((experiment, base)) = app.lab.request.take() {
            spawn_lab(experiment, base, tx.clone());
        }
        if let Some(episodes) = app.wants_probe() {
            spawn_probe(app, episodes, tx.clone());
        }
        if app.quit {
            return Ok(());
        }
    }
}

/// Applies one event to the app.
pub fn handle(app: &mut App, event: Event) {
    match event {
        Event::Tick => app.tick(),
        Event::Worker(w) => app.on_worker(w),
        Event::Graded(graded) => app.on_graded(graded),
        Event::GradeProgress(progress) => app.on_grade_progress(progress),
        Event::Lab(experiment, state) => app.on_lab(experiment, state),
        Event::Saved => app.on_saved(),
        Event::Probe(episodes, result) => app.on_probe(episodes, result),
        Event::Signal(signal) => app.on_signal(signal),
        Event::Input(event::Event::Resize(width, height)) => app.resize(width, height),
        Event::Input(event::Event::Key(key)) => {
            let context = keys::Context {
                overlay_open: app.overlay != app::Overlay::None
                    && app.overlay != app::Overlay::Help,
                sandbox_open: app.overlay == app::Overlay::Sandbox,
                quiz_open: app.overlay == app::Overlay::Quiz,
                prediction_open: app.overlay == app::Overlay::None && app.asking_prediction(),
            };
            // While the screen only says it is too small, keys would act unseen: only
            // quitting does.
            if let Some(action) = keys::map(key, context)
                && (!app.too_small || action == Action::Quit)
            {
                app.update(action);
            }
        }
        Event::Input(event::Event::Mouse(_)) if app.too_small => {}
        Event::Input(event::Event::Mouse(m)) => match m.kind {
            MouseEventKind::ScrollDown => app.update(Action::ScrollDown),
            MouseEventKind::ScrollUp => app.update(Action::ScrollUp),
            _ => {}
        },
        Event::Input(_) => {}
    }
}

/// Keeps `watcher` on the open lesson's exercise files (those that exist under the current
/// folder), so that a save regrades them; a folder that cannot be watched is said in the
/// status line.
fn watch_exercise_files(app: &mut App, watcher: &mut Option<SaveWatcher>, tx: &Sender<Event>) {
    let files: Vec<std::path::PathBuf> = app
        .exercise_files()
        .into_iter()
        .filter(|f| f.exists())
        .filter_map(|f| std::path::absolute(f).ok())
        .collect();
    if watcher
        .as_ref()
        .map_or(files.is_empty(), |w| w.files() == files.as_slice())
    {
        return;
    }
    *watcher = None;
    if files.is_empty() {
        return;
    }
    let sender = tx.clone();
    match SaveWatcher::new(&files, move |_| {
        let _ = sender.send(Event::Saved);
    }) {
        Ok(w) => *watcher = Some(w),
        Err(e) => {
            app.warn(&crate::tr!("{e}; g still grades", "{e}；按 g 仍可评分"));
        }
    }
}

/// Measures the trust-region probe of the latest batch on a background thread (a second or
/// so), so that training and the UI never wait on it.
fn spawn_probe(app: &mut App, episodes: usize, tx: Sender<Event>) {
    let snapshot = app.run.snapshot.clone();
    let config = app.run.cartpole();
    app.probe = app::Probe::Measuring(episodes);
    std::thread::spawn(move || {
        let settings = crate::ppo::trust_region::ProbeSettings::default();
        let result = crate::ppo::trust_region::probe_snapshot(&snapshot, &config, &settings)
            .map(Box::new)
            .map_err(|e| e.to_string());
        let _ = tx.send(Event::Probe(episodes, result));
    });
}

/// Runs a clip-lab experiment on a background thread (its runs on every core), sending its
/// progress about a hundred times and then its result.
fn spawn_lab(experiment: Experiment, base: crate::ppo::PpoConfig, tx: Sender<Event>) {
    std::thread::spawn(move || {
        let threads = std::thread::available_parallelism().map_or(1, usize::from);
        let result = lab::run(
            experiment,
            &base,
            &app::LAB_SEEDS,
            threads,
            |done, total| {
                if done % (total / 100).max(1) == 0 {
                    let _ = tx.send(Event::Lab(experiment, LabState::Running { done, total }));
                }
            },
        );
        let state = match result {
            Ok(r) => LabState::Done(Box::new(r)),
            Err(e) => LabState::Failed(e.to_string()),
        };
        let _ = tx.send(Event::Lab(experiment, state));
    });
}

/// Grades `names` on a background thread (compiling can take seconds, and the candle
/// exercise's first build minutes), sending what the grading does as it goes (the panel
/// shows cargo's progress) and then the result.
fn spawn_grader(names: Vec<String>, tx: Sender<Event>) {
    std::thread::spawn(move || {
        let options = crate::grade::GradeOptions::default();
        let graded = names
            .into_iter()
            .map(|name| {
                let progress = tx.clone();
                let result = crate::grade::grade_with_progress(&name, None, &options, &mut |p| {
                    let _ = progress.send(Event::GradeProgress(p.clone()));
                })
                .map_err(|e| e.to_string());
                app::Graded { name, result }
            })
            .collect();
        let _ = tx.send(Event::Graded(graded));
    });
}

fn forward(rx: mpsc::Receiver<WorkerEvent>, tx: Sender<Event>) {
    std::thread::spawn(move || {
        for e in rx {
            if tx.send(Event::Worker(e)).is_err() {
                return;
            }
        }
    });
}

fn spawn_input(tx: Sender<Event>) {
    std::thread::spawn(move || {
        while let Ok(e) = event::read() {
            if tx.send(Event::Input(e)).is_err() {
                return;
            }
        }
    });
}

fn spawn_ticker(tx: Sender<Event>) {
    std::thread::spawn(move || {
        while tx.send(Event::Tick).is_ok() {
            std::thread::sleep(TICK);
        }
    });
}
