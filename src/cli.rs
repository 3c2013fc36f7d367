//! The `ppo-tutor` command line: argument definitions (clap) and dispatch.
//!
//! `src/main.rs` only calls [`main_with_args`]; every subcommand lives in its own
//! module under `cli/` and returns an [`anyhow::Result`] so errors reach the user
//! with context, never as a panic.

use std::ffi::OsString;
use std::process::ExitCode;

use clap::{Parser, Subcommand};

use crate::i18n::{Lang, t};

pub mod args;
pub mod cartpole;
pub mod dev;
pub mod errors;
pub mod grade;
pub mod help_zh;
pub mod interrupt;
pub mod lab;
pub mod lessons;
mod one_thread;
pub mod pendulum;
pub mod play;
pub mod replay;
pub mod train;
pub mod trust_region;
mod usage;

use one_thread::rerun_with_one_candle_thread;
use usage::report_clap_error;

/// Learn Proximal Policy Optimization by running it: a terminal tutor over a native
/// CartPole-v1 and a candle PPO identical to the seed's PyTorch code.
#[derive(Debug, Parser)]
#[command(
    name = "ppo-tutor",
    version,
    about,
    long_about = None,
    after_help = "Language / 语言: `--lang en` or `--lang zh` (on any command), else \
PPO_TUTOR_LANG=en|zh, else the locale (LC_ALL, LC_MESSAGES, LANG: zh_CN.UTF-8 and other zh* \
give Chinese); English otherwise.\n\
界面语言：任何命令都可加 `--lang zh` 或 `--lang en`；否则看 PPO_TUTOR_LANG=zh|en；再否则跟随系统语言\
（LC_ALL、LC_MESSAGES、LANG 以 zh 开头即为中文）。"
)]
pub struct Cli {
    /// The language of everything printed for people: en or zh (default: PPO_TUTOR_LANG,
    /// else the locale: LC_ALL, LC_MESSAGES, LANG starting with zh give Chinese).
    #[arg(long, global = true, value_name = "LANG", value_parser = parse_lang)]
    pub lang: Option<Lang>,
    /// What to do; with none, the tutor starts.
    #[command(subcommand)]
    pub command: Option<Command>,
}

/// Parses `--lang`: exactly `en` or `zh`.
fn parse_lang(s: &str) -> Result<Lang, String> {
    // clap names the flag and the value itself: only the fix, in both languages (the
    // language is what is wrong).
    s.parse::<Lang>()
        .map_err(|_| "expected en or zh / 应为 en 或 zh".to_string())
}

/// The subcommands.
// One value per process, parsed once: `train`'s many flags make it the largest variant,
// and boxing it would buy nothing.
#[allow(clippy::large_enum_variant)]
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
    /// Measure how far PPO's surrogate can be trusted: steps of growing length along the
    /// latest batch's gradient, each with the KL, the predicted and the true change in return.
    TrustRegion(trust_region::TrustRegionArgs),
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
    /// Write every exercise's starter into a folder, to do the exercises outside the clone.
    Init(grade::InitArgs),
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
    let style = indicatif::ProgressStyle::with_template(t(
        "{prefix}: {percent:>3}%|{bar:30}| {pos}/{len} episodes [{elapsed}<{eta}]",
        "{prefix}：{percent:>3}%|{bar:30}| {pos}/{len} 个回合 [{elapsed}<{eta}]",
    ))
    .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar());
    Some(
        indicatif::ProgressBar::new(total as u64)
            .with_style(style.progress_chars("█▉▊▋▌▍▎▏ "))
            .with_prefix(prefix),
    )
}

pub use crate::i18n::{pad_left, pad_right as pad, width};

/// ` (see --help)` in the current language, after a usage error.
#[must_use]
pub fn see_help() -> &'static str {
    t(" (see --help)", "（见 --help）")
}

/// Exit code for bad command-line input (as clap uses).
pub const EXIT_USAGE: u8 = 2;

/// Parses `args` and runs the command; the binary's whole `main`.
pub fn main_with_args<I, T>(args: I) -> ExitCode
where
    I: IntoIterator<Item = T>,
    T: Into<OsString> + Clone,
{
    let args: Vec<OsString> = args.into_iter().map(Into::into).collect();
    // Usage errors are reported before the language is settled: guess it from the raw
    // arguments and the environment, so even they speak it.
    guess_lang(&args).set_current();
    let cli = match parse(&args) {
        Ok(cli) => cli,
        Err(err) => return report_clap_error(&err),
    };
    let lang = match cli.lang {
        Some(lang) => lang,
        None => match Lang::detect() {
            Ok(lang) => lang,
            Err(err) => {
                eprintln!("error: {err}");
                return ExitCode::from(EXIT_USAGE);
            }
        },
    };
    lang.set_current();
    match run(cli) {
        Ok(code) => code,
        // The reader went away (`ppo-tutor cartpole ... | head`): nothing left to say.
        Err(err) if is_broken_pipe(&err) => ExitCode::SUCCESS,
        Err(err) => {
            eprintln!("{}{}", error_prefix(), errors::render(&err));
            ExitCode::FAILURE
        }
    }
}

/// Parses the command line in the current language: in Chinese against the command whose
/// help, headings and usage [`help_zh::localise`] translated (the same ids and parsers, so
/// the same [`Cli`]); in English exactly as clap derive does.
fn parse(args: &[OsString]) -> Result<Cli, clap::Error> {
    use clap::{CommandFactory as _, FromArgMatches as _};
    match Lang::current() {
        Lang::En => Cli::try_parse_from(args),
        Lang::Zh => {
            let mut cmd = help_zh::localise(Cli::command());
            let mut matches = cmd.try_get_matches_from_mut(args)?;
            Cli::from_arg_matches_mut(&mut matches).map_err(|e| e.format(&mut cmd))
        }
    }
}

/// The language before the command line is parsed: a well-formed `--lang en|zh` among
/// `args`, else what the environment says, else English (a bad value is reported later).
fn guess_lang(args: &[OsString]) -> Lang {
    let mut flag = None;
    let mut iter = args.iter().skip(1).filter_map(|a| a.to_str());
    while let Some(arg) = iter.next() {
        if arg == "--" {
            break;
        }
        let value = match arg.strip_prefix("--lang") {
            Some("") => iter.next(),
            Some(rest) => rest.strip_prefix('='),
            None => None,
        };
        if let Some(lang) = value.and_then(|v| v.parse::<Lang>().ok()) {
            flag = Some(lang);
        }
    }
    flag.or_else(|| Lang::detect().ok()).unwrap_or_default()
}

/// `error: ` in the current language, before an error's sentence.
#[must_use]
pub fn error_prefix() -> &'static str {
    t("error: ", "错误：")
}

/// Whether `err` comes from writing to a closed pipe.
fn is_broken_pipe(err: &anyhow::Error) -> bool {
    err.chain().any(|cause| {
        cause
            .downcast_ref::<std::io::Error>()
            .is_some_and(|io| io.kind() == std::io::ErrorKind::BrokenPipe)
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
                | Command::Init(_)
                | Command::Dev(_)
        )
    );
    if uses_candle && let Some(done) = rerun_with_one_candle_thread() {
        return done;
    }
    move_renumbered_lessons(&cli.command);
    match cli.command {
        Some(Command::Cartpole(args)) => cartpole::run(&args),
        Some(Command::Pendulum(args)) => pendulum::run(&args),
        Some(Command::Lessons) => lessons::list(),
        Some(Command::Show(args)) => lessons::show(&args),
        Some(Command::Train(args)) => train::run(&args),
        Some(Command::Lab(args)) => lab::run(&args),
        Some(Command::TrustRegion(args)) => trust_region::run(&args),
        Some(Command::Play(args)) => play::run(&args),
        Some(Command::Replay(args)) => replay::run(&args),
        Some(Command::Grade(args)) => grade::run(&args),
        Some(Command::Watch(args)) => grade::watch(&args),
        Some(Command::Reset(args)) => grade::reset(&args),
        Some(Command::Init(args)) => grade::init(&args),
        Some(Command::Dev(args)) => dev::run(&args),
        // The language was chosen for this run, or the app takes the one last chosen in it.
        None => crate::tui::run(
            cli.lang.is_some() || std::env::var_os("PPO_TUTOR_LANG").is_some_and(|v| !v.is_empty()),
        ),
    }
}

/// Before a command that reads or writes the learner's exercise files (the app, `show`,
/// `grade`, `watch`, `reset`, `init`), moves lesson folders of an older numbering of the
/// course to their current names and says so on stderr (see [`ppo_grade::renumber`]).
fn move_renumbered_lessons(command: &Option<Command>) {
    let root = match command {
        None
        | Some(Command::Show(_) | Command::Grade(_) | Command::Watch(_) | Command::Reset(_)) => {
            std::path::PathBuf::from(".")
        }
        Some(Command::Init(args)) => args.dir.clone().unwrap_or_else(|| ".".into()),
        _ => return,
    };
    for moved in ppo_grade::renumber::move_renumbered(&root) {
        eprintln!("{}", moved.message());
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn args(list: &[&str]) -> Vec<OsString> {
        list.iter().map(OsString::from).collect()
    }

    #[test]
    fn the_language_is_guessed_from_a_well_formed_flag_anywhere() {
        for (given, want) in [
            (&["ppo-tutor", "--lang", "zh", "lessons"][..], Lang::Zh),
            (&["ppo-tutor", "lessons", "--lang=zh"][..], Lang::Zh),
            (
                &["ppo-tutor", "--lang", "zh", "grade", "--lang", "en"][..],
                Lang::En,
            ),
        ] {
            assert_eq!(guess_lang(&args(given)), want, "{given:?}");
        }
    }

    #[test]
    fn the_flag_parses_on_every_subcommand() {
        for line in [
            &["ppo-tutor", "--lang", "zh", "lessons"][..],
            &["ppo-tutor", "lessons", "--lang", "zh"][..],
            &["ppo-tutor", "grade", "compute_advantage", "--lang=zh"][..],
            &["ppo-tutor", "--lang", "zh"][..],
        ] {
            let cli = Cli::try_parse_from(line);
            assert!(
                cli.as_ref().is_ok_and(|c| c.lang == Some(Lang::Zh)),
                "{line:?}: {cli:?}"
            );
        }
        let bad = Cli::try_parse_from(["ppo-tutor", "--lang", "fr", "lessons"]);
        let message = bad.err().map(|e| e.to_string()).unwrap_or_default();
        assert!(message.contains("expected en or zh"), "{message}");
    }

    /// Each kind of usage error reads as one Chinese sentence that quotes what was wrong,
    /// with no English word outside flags, values and identifiers.
    #[test]
    fn usage_errors_read_in_chinese() {
        use clap::CommandFactory as _;
        let mut english = Cli::command();
        english.build();
        let mut allowed = std::collections::BTreeSet::new();
        help_zh::identifiers(&english, &mut allowed);
        for (line, kind, says) in [
            (
                &["train", "--foo"][..],
                "UnknownArgument",
                "不认识的参数 '--foo'",
            ),
            (&["train", "--epsx", "3"][..], "UnknownArgument", "'--eps'"),
            (
                &["lessons", "extra"][..],
                "UnknownArgument",
                "多余的参数 'extra'",
            ),
            (
                &["trian"][..],
                "InvalidSubcommand",
                "不认识的子命令 'trian'",
            ),
            (&["show"][..], "MissingRequiredArgument", "缺少必需的参数"),
            (&["play"][..], "MissingRequiredArgument", "'--load <文件>'"),
            (
                &["cartpole", "--policy", "lea"][..],
                "InvalidValue",
                "'lea' 不是 '--policy <策略>' 的有效值；可选值：'random'、'lean'",
            ),
            (&["train", "--episodes"][..], "InvalidValue", "需要一个值"),
            (
                &["cartpole", "--seed", "abc"][..],
                "ValueValidation",
                "'--seed <种子>' 的值 'abc' 无效：应为",
            ),
            (
                &["--lang", "fr", "lessons"][..],
                "ValueValidation",
                "应为 en 或 zh",
            ),
            (
                &["show", "td-target", "--step", "x"][..],
                "ValueValidation",
                "'x' 无效：应为不小于 1 的整数",
            ),
            (
                &["train", "--eps", "abc"][..],
                "ValueValidation",
                "'abc' 无效：不是数",
            ),
            (
                &["train", "--seeds", "0-2", "--seed", "3"][..],
                "ArgumentConflict",
                "不能与 '--seed <种子>' 同时使用",
            ),
            (
                &["cartpole", "--json", "--json"][..],
                "ArgumentConflict",
                "不能重复使用",
            ),
        ] {
            let _zh = Lang::Zh.scoped();
            let mut cmd = help_zh::localise(Cli::command());
            let mut args = vec!["ppo-tutor"];
            args.extend_from_slice(line);
            let Err(err) = cmd.try_get_matches_from_mut(&args) else {
                panic!("{line:?} parsed");
            };
            assert_eq!(format!("{:?}", err.kind()), kind, "{line:?}");
            let text = usage::usage_error_zh(&err);
            assert!(
                text.starts_with("错误：") && text.contains(says) && !text.contains('\n'),
                "{line:?}: {text}"
            );
            // What the user typed is quoted as typed.
            let mut quoted = text.clone();
            for typed in line {
                quoted = quoted.replace(&format!("'{typed}'"), "");
            }
            let words = help_zh::english_words(&quoted, &allowed);
            assert!(words.is_empty(), "{line:?}: English {words:?} in {text}");
        }
    }
}
