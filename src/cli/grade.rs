//! `ppo-tutor grade [EXERCISE] [--file PATH]` and `ppo-tutor reset EXERCISE`: the graded
//! exercises from the command line, like rustlings.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Duration;

use anyhow::Context as _;
use clap::Args;

use crate::grade::{self, GradeError, GradeOptions, GradeProgress, Report};
use crate::i18n::t;
use crate::lesson::Progress;
use crate::tr;

/// `--time-limit`, shared by `grade` and `watch`.
#[derive(Debug, Args)]
pub struct TimeLimit {
    /// Seconds the learner's code may run on all cases of one exercise (at least 1).
    #[arg(long, default_value_t = 10, value_name = "SECS",
          value_parser = super::args::parse_count, allow_hyphen_values = true)]
    pub time_limit: usize,
}

impl TimeLimit {
    /// The grading options with this limit.
    fn options(&self) -> GradeOptions {
        GradeOptions {
            time_limit: Duration::from_secs(u64::try_from(self.time_limit).unwrap_or(u64::MAX)),
            ..GradeOptions::default()
        }
    }
}

/// Arguments of `ppo-tutor grade`.
#[derive(Debug, Args)]
#[command(
    after_help = "The compiled programs are cached in $PPO_TUTOR_GRADE_CACHE, by default \
    ppo-tutor-grade in the system's temporary folder (/tmp/ppo-tutor-grade on Linux): candle's \
    build for ppo_losses (about 380 MB, compiled once, about 2 minutes on two cores) and the 4 \
    most recently used builds of each exercise (about 0.5 MB each, 5 MB for ppo_losses). \
    Deleting the folder is safe: it is rebuilt as needed."
)]
pub struct GradeArgs {
    /// The exercise (its function name, e.g. compute_advantage); all exercises when omitted.
    pub exercise: Option<String>,
    /// Grade this file instead of the starter's path (lessons/NN-slug/exercise.rs, or
    /// exercise_candle.rs for ppo_losses).
    #[arg(long, value_name = "PATH")]
    pub file: Option<PathBuf>,
    /// How long the learner's code may run.
    #[command(flatten)]
    pub limit: TimeLimit,
}

/// Arguments of `ppo-tutor watch`.
#[derive(Debug, Args)]
pub struct WatchArgs {
    /// The exercise to start with; by default the first one in course order that has not
    /// passed yet.
    pub exercise: Option<String>,
    /// How long the learner's code may run.
    #[command(flatten)]
    pub limit: TimeLimit,
}

/// Arguments of `ppo-tutor init`.
#[derive(Debug, Args)]
pub struct InitArgs {
    /// The folder to write the exercises in (created if needed); the current folder by
    /// default. Run `grade`, `watch` and the tutor from there.
    pub dir: Option<PathBuf>,
}

/// Arguments of `ppo-tutor reset`.
#[derive(Debug, Args)]
pub struct ResetArgs {
    /// The exercise whose starter to restore: its function only when the lesson's file holds
    /// other exercises, else the whole file; a changed file is first kept as FILE.bak.
    pub exercise: String,
}

fn usage(message: &str) -> ExitCode {
    eprintln!("{}{message}{}", super::error_prefix(), super::see_help());
    ExitCode::from(super::EXIT_USAGE)
}

/// Grades one exercise (details) or all of them (a score table). Exit code 0 exactly when
/// every check of every graded exercise passes, 1 otherwise, 2 for a usage error.
///
/// # Errors
/// Grading cannot happen at all (no rustc, unwritable cache).
pub fn run(args: &GradeArgs) -> anyhow::Result<ExitCode> {
    let opts = args.limit.options();
    let Some(name) = &args.exercise else {
        if args.file.is_some() {
            return Ok(usage(t(
                "--file needs an exercise name: ppo-tutor grade NAME --file PATH",
                "--file 需要练习名：ppo-tutor grade <练习> --file <路径>",
            )));
        }
        return grade_all(&opts);
    };
    let report = match grade_shown(name, args.file.as_deref(), &opts) {
        Err(e @ GradeError::UnknownExercise { .. }) => return Ok(usage(&e.to_string())),
        Err(e @ GradeError::Read { given, .. }) => {
            let other = if given {
                String::new()
            } else {
                tr!(
                    "\nto grade another file: ppo-tutor grade {name} --file PATH",
                    "\n要给另一个文件评分：ppo-tutor grade {name} --file <路径>"
                )
            };
            eprintln!("{}{e}{other}", super::error_prefix());
            return Ok(ExitCode::FAILURE);
        }
        other => other?,
    };
    write!(std::io::stdout(), "{}", report.render())?;
    if report.passed() {
        record_pass(&report);
        if args.file.is_none()
            && let Ok(exercise) = grade::find(name)
        {
            let path = exercise.solution_path();
            let mut out = std::io::stdout();
            if Path::new(&path).is_file() {
                writeln!(
                    out,
                    "  {}",
                    tr!("The reference solution: {path}", "参考答案：{path}")
                )?;
            } else if let Some(code) = grade::solution(name) {
                // Outside the course folder (after `ppo-tutor init`) the file is not there:
                // the binary carries every reference solution.
                writeln!(
                    out,
                    "  {}\n\n{code}",
                    t("The reference solution:", "参考答案：")
                )?;
            }
        }
        Ok(ExitCode::SUCCESS)
    } else {
        Ok(ExitCode::FAILURE)
    }
}

/// Grades `name` (in `file`, else its starter) showing the grading's progress on stderr:
/// a sentence when candle is about to be compiled (minutes, the first time only), then
/// cargo's steps, as a line redrawn on a terminal, a line per crate otherwise.
fn grade_shown(name: &str, file: Option<&Path>, opts: &GradeOptions) -> Result<Report, GradeError> {
    let mut shown = Shown::new();
    let report = grade::grade_with_progress(name, file, opts, &mut |p| shown.show(p));
    shown.finish();
    report
}

/// A grading's progress on stderr.
struct Shown {
    bar: Option<indicatif::ProgressBar>,
    terminal: bool,
    /// The crate last printed (on a terminal the line is redrawn instead).
    krate: String,
}

impl Shown {
    fn new() -> Self {
        use std::io::IsTerminal;
        Self {
            bar: None,
            terminal: std::io::stderr().is_terminal(),
            krate: String::new(),
        }
    }

    fn show(&mut self, progress: &GradeProgress) {
        match progress {
            GradeProgress::Building {
                first_time: true, ..
            }
            | GradeProgress::Waiting => self.say(&progress.to_string()),
            GradeProgress::Compiling {
                krate, first_time, ..
            } => {
                if self.terminal {
                    let bar = self.bar.get_or_insert_with(|| {
                        let style = indicatif::ProgressStyle::with_template("{spinner} {msg}")
                            .unwrap_or_else(|_| indicatif::ProgressStyle::default_spinner());
                        let bar = indicatif::ProgressBar::new_spinner().with_style(style);
                        bar.enable_steady_tick(Duration::from_millis(120));
                        bar
                    });
                    bar.set_message(progress.to_string());
                } else if *first_time && *krate != self.krate {
                    eprintln!("{progress}");
                    self.krate.clone_from(krate);
                }
            }
            // The line redrawn on a terminal moves on; elsewhere nothing is said.
            GradeProgress::Checking => {
                if let Some(bar) = &self.bar {
                    bar.set_message(progress.to_string());
                }
            }
            GradeProgress::Building { .. } => {}
        }
    }

    /// A line that stays, above the redrawn one.
    fn say(&self, line: &str) {
        match &self.bar {
            Some(bar) => bar.println(line),
            None => eprintln!("{line}"),
        }
    }

    fn finish(self) {
        if let Some(bar) = self.bar {
            bar.finish_and_clear();
        }
    }
}

/// The score table: one row per exercise, its columns as wide as their widest cell in
/// terminal columns (a Chinese character takes two).
fn grade_all(opts: &GradeOptions) -> anyhow::Result<ExitCode> {
    let mut out = std::io::stdout();
    let exercises = grade::exercises();
    let (exercise_head, file_head) = (t("exercise", "练习"), t("file", "文件"));
    let widest = |head: &str, cells: &mut dyn Iterator<Item = String>| {
        cells
            .map(|c| super::width(&c))
            .chain([super::width(head)])
            .max()
            .unwrap_or(0)
    };
    let names = widest(
        exercise_head,
        &mut exercises.iter().map(|e| e.name().to_string()),
    );
    let files = widest(file_head, &mut exercises.iter().map(|e| e.starter_path()));
    writeln!(
        out,
        "{}  {}  {}",
        super::pad(exercise_head, names),
        super::pad(file_head, files),
        t("result", "结果")
    )?;
    let mut passed = 0;
    for exercise in exercises {
        let (name, path) = (exercise.name(), exercise.starter_path());
        let result = match grade_shown(name, None, opts) {
            Ok(report) => {
                if report.passed() {
                    passed += 1;
                    record_pass(&report);
                }
                report.summary()
            }
            Err(GradeError::Read { .. }) => tr!(
                "missing: ppo-tutor reset {name}",
                "文件不存在：ppo-tutor reset {name}"
            ),
            Err(GradeError::NoCargo { .. } | GradeError::Cargo { .. }) => tr!(
                "not graded, cargo failed: ppo-tutor grade {name} says why",
                "未评分，cargo 出错：ppo-tutor grade {name} 会说明原因"
            ),
            Err(e) => return Err(e.into()),
        };
        writeln!(
            out,
            "{}  {}  {result}",
            super::pad(name, names),
            super::pad(&path, files)
        )?;
    }
    let total = exercises.len();
    writeln!(
        out,
        "{}",
        tr!(
            "score: {passed}/{total} exercises pass",
            "得分：{passed}/{total} 个练习通过"
        )
    )?;
    writeln!(
        out,
        "{}",
        t(
            "details: ppo-tutor grade <exercise>",
            "详情：ppo-tutor grade <练习名>"
        )
    )?;
    Ok(if passed == exercises.len() {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    })
}

/// Adds a passed exercise to the progress file (a failure to save is only a warning).
fn record_pass(report: &Report) {
    let path = Progress::default_path();
    let (mut progress, _) = Progress::load(&path);
    if progress.exercises_done.insert(report.exercise.clone())
        && let Err(e) = progress.save(&path)
    {
        // The error names the file, the cause and the fix.
        eprintln!(
            "{}",
            tr!(
                "warning: the pass is not recorded: {e}",
                "警告：没能记下这次通过：{e}"
            )
        );
    }
}

/// Restores an exercise's starter file under the current folder.
///
/// # Errors
/// The file cannot be written.
pub fn reset(args: &ResetArgs) -> anyhow::Result<ExitCode> {
    match grade::reset(&args.exercise, Path::new(".")) {
        Err(e @ GradeError::UnknownExercise { .. }) => Ok(usage(&e.to_string())),
        Err(e) => Err(e.into()),
        Ok(done) => {
            let (name, path) = (&args.exercise, done.path.display());
            let mut out = std::io::stdout();
            let line = if done.only_function {
                tr!(
                    "restored {name}'s starter in {path} (the file's other exercises are kept)",
                    "已在 {path} 中恢复 {name} 的初始代码（文件里的其他练习保持不变）"
                )
            } else {
                tr!("restored the starter {path}", "已恢复初始文件 {path}")
            };
            writeln!(out, "{line}")?;
            if let Some(backup) = &done.backup {
                let backup = backup.display();
                writeln!(
                    out,
                    "{}",
                    tr!(
                        "your previous version is in {backup}",
                        "你之前的版本保存在 {backup}"
                    )
                )?;
            }
            Ok(ExitCode::SUCCESS)
        }
    }
}

/// Writes every exercise's starter under `dir` (default: the current folder), keeping any
/// file already there, so the exercises can be done outside the course's clone.
///
/// # Errors
/// The folder cannot be created or a file cannot be written.
pub fn init(args: &InitArgs) -> anyhow::Result<ExitCode> {
    let dir = args.dir.clone().unwrap_or_else(|| PathBuf::from("."));
    if dir.exists() && !dir.is_dir() {
        let shown = dir.display();
        return Ok(usage(&tr!(
            "{shown} is not a folder: give a folder to write the exercises in",
            "{shown} 不是文件夹：请给出存放练习的文件夹"
        )));
    }
    let mut out = std::io::stdout();
    let (mut written, mut kept) = (0, 0);
    let mut seen = std::collections::BTreeSet::new();
    for exercise in grade::exercises() {
        let rel = exercise.starter_path();
        if !seen.insert(rel.clone()) {
            continue;
        }
        let path = dir.join(&rel);
        let shown = path.display();
        if path.exists() {
            kept += 1;
            writeln!(out, "{}", tr!("kept     {shown}", "保留     {shown}"))?;
            continue;
        }
        let text = exercise.starter().ok_or_else(|| {
            anyhow::anyhow!(tr!(
                "no starter is embedded for {rel}",
                "{rel} 没有内置的初始文件"
            ))
        })?;
        if let Some(parent) = path.parent() {
            std::fs::create_dir_all(parent)
                .with_context(|| tr!("creating {}", "创建 {}", parent.display()))?;
        }
        std::fs::write(&path, text).with_context(|| tr!("writing {shown}", "写入 {shown}"))?;
        written += 1;
        writeln!(out, "{}", tr!("wrote    {shown}", "写入     {shown}"))?;
    }
    let shown = dir.display();
    writeln!(
        out,
        "{}",
        tr!(
            "{written} starters written, {kept} kept. In {shown}: `ppo-tutor watch` grades on \
             every save, `ppo-tutor grade` shows the score.",
            "写入 {written} 个初始文件，保留 {kept} 个。在 {shown} 中：`ppo-tutor watch` 每次保存都会\
             评分，`ppo-tutor grade` 显示得分。"
        )
    )?;
    Ok(ExitCode::SUCCESS)
}

/// The first exercise at or after `from` in course order that has not passed yet.
fn next_pending(from: usize, progress: &Progress) -> Option<usize> {
    let all = grade::exercises();
    (from..all.len()).find(|&i| !progress.exercises_done.contains(all[i].name()))
}

/// Grades an exercise every time its file is saved (debounced), and when it passes moves
/// on to the next exercise that has not passed, until every one has. Ctrl-C stops.
///
/// # Errors
/// Grading cannot happen at all (no rustc), or the exercise's folder cannot be watched.
pub fn watch(args: &WatchArgs) -> anyhow::Result<ExitCode> {
    use std::io::IsTerminal;
    let opts = args.limit.options();
    let all = grade::exercises();
    let (progress, _) = Progress::load(&Progress::default_path());
    let start = match &args.exercise {
        Some(name) => match all.iter().position(|e| e.name() == name) {
            Some(i) => i,
            None => {
                let known = grade::exercise_names().join(", ");
                return Ok(usage(&tr!(
                    "no exercise '{name}'; the exercises are: {known}",
                    "没有名为 '{name}' 的练习；现有的练习：{known}"
                )));
            }
        },
        None => match next_pending(0, &progress) {
            Some(i) => i,
            None => {
                println!(
                    "{}",
                    t(
                        "Every exercise passes already: `ppo-tutor watch NAME` watches one anyway.",
                        "所有练习都已通过。仍想监视某个练习，可用 `ppo-tutor watch <练习>`。"
                    )
                );
                return Ok(ExitCode::SUCCESS);
            }
        },
    };
    let clear = std::io::stdout().is_terminal();
    let (tx, rx) = std::sync::mpsc::channel();
    let mut current = start;
    // After a pass, the next exercise is graded at once, below the pass (not cleared).
    let mut keep_screen = false;
    loop {
        let exercise = all[current];
        let (name, path) = (exercise.name(), PathBuf::from(exercise.starter_path()));
        // Without a name, exercises whose file is missing are skipped (said once each).
        if !path.exists()
            && args.exercise.is_none()
            && let Some(next) = (current + 1..all.len()).find(|&i| {
                !progress.exercises_done.contains(all[i].name())
                    && Path::new(&all[i].starter_path()).exists()
            })
        {
            let shown = path.display();
            eprintln!(
                "{}",
                tr!(
                    "skipping {name}: {shown} is missing (`ppo-tutor reset {name}` writes it)",
                    "跳过 {name}：找不到 {shown}（`ppo-tutor reset {name}` 会写入它）"
                )
            );
            current = next;
            continue;
        }
        if !path.exists() {
            let shown = path.display();
            eprintln!(
                "{}{}",
                super::error_prefix(),
                tr!(
                    "{shown} is missing: `ppo-tutor reset {name}` writes the starter there, \
                     `ppo-tutor init` every starter (exercises live under the current folder)",
                    "找不到 {shown}：`ppo-tutor reset {name}` 会在那里写入初始文件，\
                     `ppo-tutor init` 会写入全部初始文件（练习文件位于当前文件夹下）"
                )
            );
            return Ok(ExitCode::FAILURE);
        }
        let sender = tx.clone();
        let _watcher = crate::watch::SaveWatcher::new(std::slice::from_ref(&path), move |_| {
            let _ = sender.send(());
        })?;
        loop {
            if clear && !keep_screen {
                print!("\x1b[2J\x1b[H");
            }
            keep_screen = false;
            let passed = match grade_shown(name, None, &opts) {
                Ok(report) => {
                    print!("{}", report.render());
                    report.passed().then_some(report)
                }
                Err(e) => {
                    println!("{}{e}", super::error_prefix());
                    None
                }
            };
            if let Some(report) = passed {
                record_pass(&report);
                let (progress, _) = Progress::load(&Progress::default_path());
                match next_pending(current + 1, &progress).or_else(|| next_pending(0, &progress)) {
                    Some(next) => {
                        let (next_name, next_path) = (all[next].name(), all[next].starter_path());
                        println!(
                            "\n{}\n",
                            tr!(
                                "✓ {name} passes. Next: {next_name} in {next_path}",
                                "✓ {name} 通过了。下一个：{next_path} 中的 {next_name}"
                            )
                        );
                        current = next;
                    }
                    None => {
                        println!(
                            "\n{}",
                            tr!(
                                "✓ {name} passes, and so does every other exercise. Well done.",
                                "✓ {name} 通过了，其他练习也全部通过。干得漂亮！"
                            )
                        );
                        return Ok(ExitCode::SUCCESS);
                    }
                }
                keep_screen = true;
                break;
            }
            let shown = path.display();
            println!(
                "\n{}",
                tr!(
                    "Watching {shown} for saves: edit and save to regrade (Ctrl-C stops).",
                    "正在监视 {shown}：修改并保存后会重新评分（按 Ctrl-C 停止）。"
                )
            );
            std::io::stdout().flush()?;
            if rx.recv().is_err() {
                return Ok(ExitCode::FAILURE);
            }
            // Saves that came in while grading are covered by the grading that follows.
            while rx.try_recv().is_ok() {}
        }
    }
}
