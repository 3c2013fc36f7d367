//! The `ppo-tutor` command line: argument definitions (clap) and dispatch.
//!
//! `src/main.rs` only calls [`main_with_args`]; every subcommand lives in its own
//! module under `cli/` and returns an [`anyhow::Result`] so errors reach the user
//! with context, never as a panic.

use std::ffi::OsString;
use std::process::ExitCode;

use clap::{Parser, Subcommand};

pub mod args;
pub mod cartpole;
pub mod dev;
pub mod grade;
pub mod lab;
pub mod lessons;
pub mod pendulum;
pub mod play;
pub mod replay;
pub mod train;

/// Learn Proximal Policy Optimization by running it: a terminal tutor over a native
/// CartPole-v1 and a candle PPO identical to the seed's PyTorch code.
#[derive(Debug, Parser)]
#[command(name = "ppo-tutor", version, about, long_about = None)]
pub struct Cli {
    /// What to do; with none, the tutor starts.
    #[command(subcommand)]
    pub command: Option<Command>,
}

/// The subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Run the native CartPole: reset with a seed, apply actions, print the trajectory.
    Cartpole(cartpole::CartpoleArgs),
    /// Run the native Pendulum-v1: reset with a seed, apply torques, print the trajectory.
    Pendulum(pendulum::PendulumArgs),
    /// List the lessons, one `id<TAB>title` per line, in order.
    Lessons,
    /// Print one lesson step (or all steps) as plain text with its live values.
    Show(lessons::ShowArgs),
    /// Train the seed's PPO on CartPole-v1 (or the book's PPOContinuous with --env Pendulum-v1):
    /// progress bars, a summary and the return curve.
    Train(train::TrainArgs),
    /// Run a clip-lab experiment: one knob changed, every setting over several seeds.
    Lab(lab::LabArgs),
    /// Watch a saved agent (`train --save`) balance the pole or swing up the pendulum.
    Play(play::PlayArgs),
    /// Re-run recorded PyTorch updates (ppo_update_pytorch.json, or its continuous twin) and
    /// print ours.
    Replay(replay::ReplayArgs),
    /// Grade your solution of an exercise (or all): checks, first failing input, hints.
    Grade(grade::GradeArgs),
    /// Regrade an exercise every time you save its file, then go on to the next one.
    Watch(grade::WatchArgs),
    /// Restore an exercise's starter file (lessons/NN-slug/exercise.rs).
    Reset(grade::ResetArgs),
    /// Developer commands that regenerate the course's content (`dev notebooks`).
    #[command(hide = true)]
    Dev(dev::DevArgs),
}

/// One progress bar over many runs' episodes (`train --seeds`, `lab`), labelled `prefix`;
/// `None` when `quiet` or stderr is not a terminal.
pub(crate) fn episodes_bar(
    quiet: bool,
    total: usize,
    prefix: &'static str,
) -> Option<indicatif::ProgressBar> {
    use std::io::IsTerminal;
    if quiet || !std::io::stderr().is_terminal() {
        return None;
    }
    let style = indicatif::ProgressStyle::with_template(
        "{prefix}: {percent:>3}%|{bar:30}| {pos}/{len} episodes [{elapsed}<{eta}]",
    )
    .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar());
    Some(
        indicatif::ProgressBar::new(total as u64)
            .with_style(style.progress_chars("█▉▊▋▌▍▎▏ "))
            .with_prefix(prefix),
    )
}

/// Exit code for bad command-line input (as clap uses).
pub const EXIT_USAGE: u8 = 2;

/// Parses `args` and runs the command; the binary's whole `main`.
pub fn main_with_args<I, T>(args: I) -> ExitCode
where
    I: IntoIterator<Item = T>,
    T: Into<OsString> + Clone,
{
    let cli = match Cli::try_parse_from(args) {
        Ok(cli) => cli,
        Err(err) => return report_clap_error(&err),
    };
    match run(cli) {
        Ok(code) => code,
        // The reader went away (`ppo-tutor cartpole ... | head`): nothing left to say.
        Err(err) if is_broken_pipe(&err) => ExitCode::SUCCESS,
        Err(err) => {
            eprintln!("error: {err:#}");
            ExitCode::FAILURE
        }
    }
}

/// Whether `err` comes from writing to a closed pipe.
fn is_broken_pipe(err: &anyhow::Error) -> bool {
    err.chain().any(|cause| {
        cause
            .downcast_ref::<std::io::Error>()
            .is_some_and(|io| io.kind() == std::io::ErrorKind::BrokenPipe)
    })
}

/// Prints help and version as clap does; usage errors as one line, exit code 2.
fn report_clap_error(err: &clap::Error) -> ExitCode {
    use clap::error::ErrorKind;
    match err.kind() {
        ErrorKind::DisplayHelp
        | ErrorKind::DisplayVersion
        | ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand => {
            let _ = err.print();
            ExitCode::SUCCESS
        }
        _ => {
            let rendered = err.render().to_string();
            let line = rendered
                .lines()
                .find(|l| !l.trim().is_empty())
                .unwrap_or("error: invalid arguments");
            eprintln!("{line} (see --help)");
            ExitCode::from(EXIT_USAGE)
        }
    }
}

/// Re-runs this `ppo-tutor` process with `RAYON_NUM_THREADS=1` when it is unset.
///
/// Without the variable, candle asks the OS for the number of physical cores (by reading
/// `/proc/cpuinfo`) on every matrix product: ~30 µs each, ~50% of the time of the seed's
/// default run with 4x128 networks (measured 7.2 s vs 3.4 s for 500 episodes). Setting the
/// variable in-process needs `unsafe` (`std::env::set_var`, edition 2024), which this crate
/// forbids; re-running the binary costs a millisecond. A value set by the user is kept.
/// Returns `None` to go on in this process (variable set, or not the `ppo-tutor` binary,
/// as when a test calls [`run`] in-process).
fn rerun_with_one_candle_thread() -> Option<anyhow::Result<ExitCode>> {
    if std::env::var_os("RAYON_NUM_THREADS").is_some() {
        return None;
    }
    let exe = std::env::current_exe().ok()?;
    if exe.file_stem().and_then(|s| s.to_str()) != Some("ppo-tutor") {
        return None;
    }
    let status = std::process::Command::new(&exe)
        .args(std::env::args_os().skip(1))
        .env("RAYON_NUM_THREADS", "1")
        .status();
    Some(match status {
        Ok(status) => Ok(status
            .code()
            .and_then(|c| u8::try_from(c).ok())
            .map_or(ExitCode::FAILURE, ExitCode::from)),
        Err(e) => Err(anyhow::Error::new(e).context(format!("re-running {}", exe.display()))),
    })
}

/// Runs a parsed command line.
///
/// # Errors
/// Whatever the subcommand reports (bad files, invalid settings, I/O).
pub fn run(cli: Cli) -> anyhow::Result<ExitCode> {
    // Training, showing live values and grading run candle: one candle thread is faster.
    // (`dev notebooks` re-runs itself with one thread among its other settings.)
    let uses_candle = !matches!(
        cli.command,
        Some(
            Command::Cartpole(_)
                | Command::Pendulum(_)
                | Command::Lessons
                | Command::Reset(_)
                | Command::Dev(_)
        )
    );
    if uses_candle && let Some(done) = rerun_with_one_candle_thread() {
        return done;
    }
    match cli.command {
        Some(Command::Cartpole(args)) => cartpole::run(&args),
        Some(Command::Pendulum(args)) => pendulum::run(&args),
        Some(Command::Lessons) => lessons::list(),
        Some(Command::Show(args)) => lessons::show(&args),
        Some(Command::Train(args)) => train::run(&args),
        Some(Command::Lab(args)) => lab::run(&args),
        Some(Command::Play(args)) => play::run(&args),
        Some(Command::Replay(args)) => replay::run(&args),
        Some(Command::Grade(args)) => grade::run(&args),
        Some(Command::Watch(args)) => grade::watch(&args),
        Some(Command::Reset(args)) => grade::reset(&args),
        Some(Command::Dev(args)) => dev::run(&args),
        None => {
            crate::tui::run()?;
            Ok(ExitCode::SUCCESS)
        }
    }
}
