//! `ppo-tutor grade [EXERCISE] [--file PATH]` and `ppo-tutor reset EXERCISE`: the graded
//! exercises from the command line, like rustlings.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Duration;

use clap::Args;

use crate::grade::{self, GradeError, GradeOptions, Report};
use crate::i18n::t;
use crate::lesson::Progress;
use crate::tr;

/// Arguments of `ppo-tutor grade`.
#[derive(Debug, Args)]
pub struct GradeArgs {
    /// The exercise (its function name, e.g. td_target); all exercises when omitted.
    pub exercise: Option<String>,
    /// Grade this file instead of the starter's path (lessons/NN-slug/exercise.rs, or
    /// exercise_candle.rs for ppo_losses).
    #[arg(long, value_name = "PATH")]
    pub file: Option<PathBuf>,
    /// Seconds the learner's code may run on all cases of one exercise.
    #[arg(long, default_value_t = 10, value_name = "SECS")]
    pub time_limit: u64,
}

/// Arguments of `ppo-tutor watch`.
#[derive(Debug, Args)]
pub struct WatchArgs {
    /// The exercise to start with; by default the first one in course order that has not
    /// passed yet.
    pub exercise: Option<String>,
    /// Seconds the learner's code may run on all cases of one exercise.
    #[arg(long, default_value_t = 10, value_name = "SECS")]
    pub time_limit: u64,
}

/// Arguments of `ppo-tutor reset`.
#[derive(Debug, Args)]
pub struct ResetArgs {
    /// The exercise whose starter file to restore (the whole file is rewritten).
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
    let opts = GradeOptions {
        time_limit: Duration::from_secs(args.time_limit.max(1)),
        ..GradeOptions::default()
    };
    let Some(name) = &args.exercise else {
        if args.file.is_some() {
            return Ok(usage(t(
                "--file needs an exercise name: ppo-tutor grade NAME --file PATH",
                "--file 需要练习名：ppo-tutor grade NAME --file PATH",
            )));
        }
        return grade_all(&opts);
    };
    note_first_build(name, &opts);
    let report = match grade::grade(name, args.file.as_deref(), &opts) {
        Err(e @ GradeError::UnknownExercise { .. }) => return Ok(usage(&e.to_string())),
        Err(e @ GradeError::Read { .. }) => {
            eprintln!("{}{e}", super::error_prefix());
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
            writeln!(
                std::io::stdout(),
                "  {}",
                tr!("The reference solution: {path}", "参考答案：{path}")
            )?;
        }
        Ok(ExitCode::SUCCESS)
    } else {
        Ok(ExitCode::FAILURE)
    }
}

/// Says so before a grading whose first build is slow (minutes, with no other output).
fn note_first_build(name: &str, opts: &GradeOptions) {
    if let Some(note) = grade::find(name)
        .ok()
        .and_then(|e| e.first_build_note(&opts.cache_dir))
    {
        eprintln!("{note}");
    }
}

fn grade_all(opts: &GradeOptions) -> anyhow::Result<ExitCode> {
    let mut out = std::io::stdout();
    writeln!(
        out,
        "{} {} {}",
        super::pad(t("exercise", "练习"), 22),
        super::pad(t("file", "文件"), 38),
        t("result", "结果")
    )?;
    let mut passed = 0;
    let exercises = grade::exercises();
    for exercise in exercises {
        let (name, path) = (exercise.name(), exercise.starter_path());
        note_first_build(name, opts);
        let result = match grade::grade(name, None, opts) {
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
        writeln!(out, "{name:<22} {path:<38} {result}")?;
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
        let path = path.display();
        eprintln!(
            "{}",
            tr!(
                "warning: could not record the pass in {path}: {e}",
                "警告：无法把通过记录写入 {path}：{e}"
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
        Ok(path) => {
            let path = path.display();
            writeln!(
                std::io::stdout(),
                "{}",
                tr!("restored the starter {path}", "已恢复初始文件 {path}")
            )?;
            Ok(ExitCode::SUCCESS)
        }
    }
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
    let opts = GradeOptions {
        time_limit: Duration::from_secs(args.time_limit.max(1)),
        ..GradeOptions::default()
    };
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
                        "所有练习都已通过。仍想监视某个练习，可用 `ppo-tutor watch NAME`。"
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
        if !path.exists() {
            let shown = path.display();
            eprintln!(
                "{}{}",
                super::error_prefix(),
                tr!(
                    "{shown} is missing: `ppo-tutor reset {name}` writes the starter there \
                     (run ppo-tutor from the course folder)",
                    "找不到 {shown}：`ppo-tutor reset {name}` 会在那里写入初始文件\
                     （请在课程文件夹中运行 ppo-tutor）"
                )
            );
            return Ok(ExitCode::FAILURE);
        }
        let sender = tx.clone();
        let _watcher = grade::watch::SaveWatcher::new(std::slice::from_ref(&path), move |_| {
            let _ = sender.send(());
        })?;
        loop {
            if clear && !keep_screen {
                print!("\x1b[2J\x1b[H");
            }
            keep_screen = false;
            note_first_build(name, &opts);
            let passed = match grade::grade(name, None, &opts) {
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
