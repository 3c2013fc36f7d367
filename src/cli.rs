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
pub mod pendulum;
pub mod play;
pub mod replay;
pub mod train;
pub mod trust_region;

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
            let line = match Lang::current() {
                Lang::En => usage_error_line(&err.render().to_string()),
                Lang::Zh => usage_error_zh(err),
            };
            eprintln!("{line}{}", see_help());
            ExitCode::from(EXIT_USAGE)
        }
    }
}

/// A clap usage error as one Chinese line, built from its kind and context (what clap
/// renders is English): `错误：` and one sentence per kind, quoting the argument and value.
fn usage_error_zh(err: &clap::Error) -> String {
    use clap::error::{ContextKind, ContextValue, ErrorKind};
    let get = |kind: ContextKind| -> Option<String> {
        match err.get(kind)? {
            ContextValue::String(s) => Some(s.clone()),
            ContextValue::Strings(v) => Some(v.join("、")),
            ContextValue::StyledStr(s) => Some(s.to_string()),
            ContextValue::StyledStrs(v) => Some(
                v.iter()
                    .map(ToString::to_string)
                    .collect::<Vec<_>>()
                    .join("、"),
            ),
            ContextValue::Number(n) => Some(n.to_string()),
            ContextValue::Bool(b) => Some(b.to_string()),
            ContextValue::None => None,
            _ => None,
        }
    };
    let quoted = |list: String| -> String {
        list.split('、')
            .map(|item| format!("'{item}'"))
            .collect::<Vec<_>>()
            .join("、")
    };
    let arg = get(ContextKind::InvalidArg).unwrap_or_default();
    let value = get(ContextKind::InvalidValue);
    let suggest = |kind: ContextKind| -> String {
        get(kind)
            .map(|s| format!("；你是不是想用 {}？", quoted(s)))
            .unwrap_or_default()
    };
    let sentence = match err.kind() {
        // A flag clap does not know, or a value no argument takes.
        ErrorKind::UnknownArgument if arg.starts_with('-') => {
            format!("不认识的参数 '{arg}'{}", suggest(ContextKind::SuggestedArg))
        }
        ErrorKind::UnknownArgument => format!("多余的参数 '{arg}'"),
        ErrorKind::InvalidSubcommand => format!(
            "不认识的子命令 '{}'{}",
            get(ContextKind::InvalidSubcommand).unwrap_or_default(),
            suggest(ContextKind::SuggestedSubcommand)
        ),
        ErrorKind::InvalidValue => match value.as_deref() {
            None | Some("") => format!("'{arg}' 需要一个值，但没有给出"),
            Some(value) => {
                let valid = get(ContextKind::ValidValue)
                    .map(|v| format!("；可选值：{}", quoted(v)))
                    .unwrap_or_default();
                format!(
                    "'{value}' 不是 '{arg}' 的有效值{valid}{}",
                    suggest(ContextKind::SuggestedValue)
                )
            }
        },
        ErrorKind::ValueValidation => {
            let value = value.unwrap_or_default();
            // Our own parsers explain in Chinese (or in both languages, then the Chinese
            // half); a number parser of the standard library in English, which
            // `errors::parse_reason` says in Chinese; any other reason in English is left out.
            let source = std::error::Error::source(err);
            let why = source
                .and_then(errors::parse_reason)
                .or_else(|| {
                    source
                        .map(ToString::to_string)
                        .map(|m| match m.split_once(" / ") {
                            Some((_, zh)) if has_chinese(zh) => zh.to_string(),
                            _ => m,
                        })
                        .filter(|m| has_chinese(m))
                })
                .map(|m| format!("：{m}"))
                .unwrap_or_default();
            format!("'{arg}' 的值 '{value}' 无效{why}")
        }
        ErrorKind::MissingRequiredArgument => format!("缺少必需的参数：{}", quoted(arg)),
        ErrorKind::MissingSubcommand => {
            let valid = get(ContextKind::ValidSubcommand)
                .map(|v| format!("：{}", quoted(v)))
                .unwrap_or_default();
            format!(
                "'{}' 需要一个子命令{valid}",
                get(ContextKind::InvalidSubcommand).unwrap_or_default()
            )
        }
        ErrorKind::ArgumentConflict => match get(ContextKind::PriorArg) {
            Some(prior) if prior != arg => {
                format!("'{arg}' 不能与 {} 同时使用", quoted(prior))
            }
            _ => format!("'{arg}' 不能重复使用"),
        },
        ErrorKind::TooManyValues => format!(
            "'{arg}' 不需要更多的值，却多给了 '{}'",
            value.unwrap_or_default()
        ),
        ErrorKind::TooFewValues => format!(
            "'{arg}' 至少需要 {} 个值，只给了 {} 个",
            get(ContextKind::MinValues).unwrap_or_default(),
            get(ContextKind::ActualNumValues).unwrap_or_default()
        ),
        ErrorKind::WrongNumberOfValues => format!(
            "'{arg}' 需要 {} 个值，给了 {} 个",
            get(ContextKind::ExpectedNumValues).unwrap_or_default(),
            get(ContextKind::ActualNumValues).unwrap_or_default()
        ),
        ErrorKind::NoEquals => format!("'{arg}' 的值要用等号连着写，如 '{arg}=…'"),
        ErrorKind::InvalidUtf8 => "参数不是有效的 UTF-8 文本".to_string(),
        _ if arg.is_empty() => "命令行参数有误".to_string(),
        _ => format!("命令行参数 '{arg}' 有误"),
    };
    format!("{}{sentence}", error_prefix())
}

/// Whether `text` holds a Chinese character.
fn has_chinese(text: &str) -> bool {
    text.chars().any(|c| ('\u{4e00}'..='\u{9fff}').contains(&c))
}

/// A clap error as one line: its first line, and for a missing argument the arguments it
/// lists on the lines below (`error: the following required arguments were not provided:
/// <EXERCISE>`), which the first line alone would leave out.
fn usage_error_line(rendered: &str) -> String {
    let mut lines = rendered.lines().skip_while(|l| l.trim().is_empty());
    let Some(first) = lines.next() else {
        return "error: invalid arguments".to_string();
    };
    let listed: Vec<&str> = lines
        .take_while(|l| l.starts_with(' ') && !l.trim().is_empty())
        .map(str::trim)
        .collect();
    if listed.is_empty() {
        first.to_string()
    } else {
        format!("{first} {}", listed.join(", "))
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
    let mut command = std::process::Command::new(&exe);
    command
        .args(std::env::args_os().skip(1))
        .env("RAYON_NUM_THREADS", "1");
    Some(rerun(command, &exe))
}

/// Runs `command`, this program again with one candle thread. On Unix it replaces this
/// process (the same PID, so a signal meant for `ppo-tutor` reaches it, and nothing is left
/// running when it is killed: a child used to outlive a SIGTERM); `exec` returns only when
/// it fails.
#[cfg(unix)]
fn rerun(mut command: std::process::Command, exe: &std::path::Path) -> anyhow::Result<ExitCode> {
    use std::os::unix::process::CommandExt as _;
    let e = command.exec();
    Err(anyhow::Error::new(e).context(format!("re-running {}", exe.display())))
}

/// Runs `command`, this program again with one candle thread, and exits with its code.
/// Ctrl-C reaches both processes: this one ignores it, so that the child's answer
/// ([`interrupt`]) and exit code are what the user sees.
#[cfg(not(unix))]
fn rerun(mut command: std::process::Command, exe: &std::path::Path) -> anyhow::Result<ExitCode> {
    interrupt::ignore_in_parent();
    match command.status() {
        Ok(status) => Ok(status
            .code()
            .and_then(|c| u8::try_from(c).ok())
            .map_or(ExitCode::FAILURE, ExitCode::from)),
        Err(e) => Err(anyhow::Error::new(e).context(format!("re-running {}", exe.display()))),
    }
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
            let text = usage_error_zh(&err);
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
