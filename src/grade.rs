//! Graded exercises: the learner writes PPO's pieces in plain Rust and the tutor grades them.
//!
//! Each exercise is one function of the seed's update (`td_target`, `compute_advantage`,
//! `actor_loss`, ...) with a starter at `lessons/<lesson>/exercise.rs` (`todo!()` and TODO
//! comments) and a reference solution at `lessons/<lesson>/solution.rs`. Grading:
//!
//! 1. [`harness`] compiles the learner's file with `rustc -O` inside a generated program
//!    (cached by content hash) that calls the function through its exact signature;
//! 2. [`cases`] supplies the inputs: seeded random batches, the recorded PyTorch episodes,
//!    and edge cases (a single step, every step done, ratios outside 1 ± ε, ...);
//! 3. every result is compared with the reference's within a tolerance; for the first
//!    failure of each check the [`Report`] keeps the input, expected and actual results;
//! 4. the learner's wrong outputs are compared with the [`catalog`]'s known mistakes (GAE
//!    run forwards, a missing `(1 - done)`, max instead of min, ...) to pick the hint.
//!
//! One exercise, [`ppo_losses`], is on candle tensors instead: built with cargo against
//! candle, graded on losses and gradients, then plugged into the agent to train CartPole.
//!
//! Panics are caught per case and reported with their message; a run past the time limit
//! is killed and reported as never returning. The grader itself returns errors, never
//! panics.
//!
//! ```
//! use ppo_tutor::grade::catalog;
//!
//! let spec = catalog::find("td_target").ok_or("no td_target")?;
//! assert_eq!(
//!     spec.signature(),
//!     "pub fn td_target(rewards: &[f32], next_values: &[f32], dones: &[bool], gamma: f32) -> Vec<f32>"
//! );
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

pub mod cases;
pub mod catalog;
pub mod harness;
pub mod in_process;
pub mod ppo_losses;
pub mod report;
pub mod solutions;
pub mod value;

use std::path::{Path, PathBuf};
use std::time::Duration;

pub use catalog::{Args, CheckCases, Mistake, Spec};
pub use report::{CheckReport, CheckStatus, Failure, Problem, Report};

use value::Output;

/// Why grading could not happen at all (a learner's bad file is a [`Report`], not this).
#[derive(Debug, thiserror::Error)]
pub enum GradeError {
    /// No exercise has this name.
    #[error("unknown exercise '{name}': the exercises are {known}")]
    UnknownExercise {
        /// The name given.
        name: String,
        /// The valid names, comma-separated.
        known: String,
    },
    /// The learner's file cannot be read.
    #[error(
        "cannot read {file}: {reason} (run `ppo-tutor reset {exercise}` to restore the starter, or pass --file PATH)"
    )]
    Read {
        /// The file.
        file: PathBuf,
        /// The exercise.
        exercise: String,
        /// The I/O error.
        reason: String,
    },
    /// `rustc` could not be started.
    #[error(
        "cannot run the Rust compiler '{rustc}': {reason}; install Rust (https://rustup.rs) or set RUSTC to rustc's path"
    )]
    NoRustc {
        /// The program tried.
        rustc: PathBuf,
        /// The I/O error.
        reason: String,
    },
    /// The cache folder cannot be written.
    #[error(
        "cannot write the grading cache {dir}: {reason} (set PPO_TUTOR_GRADE_CACHE to a writable folder)"
    )]
    Cache {
        /// The folder.
        dir: PathBuf,
        /// The I/O error.
        reason: String,
    },
    /// `cargo` could not be started (the candle exercise is built with cargo).
    #[error(
        "cannot run cargo '{cargo}': {reason}; the candle exercise is built with cargo: install Rust (https://rustup.rs) or set CARGO to cargo's path"
    )]
    NoCargo {
        /// The program tried.
        cargo: PathBuf,
        /// The I/O error.
        reason: String,
    },
    /// cargo failed for a reason other than the learner's code.
    #[error(
        "cargo could not build the candle grader in {dir}:\n{message}\n(the first build fetches and compiles candle: it needs the crates.io registry or cargo's download cache; delete {dir} to start over)"
    )]
    Cargo {
        /// The project folder.
        dir: PathBuf,
        /// cargo's last lines of output.
        message: String,
    },
    /// The embedded PyTorch fixture could not be replayed (a broken build).
    #[error(
        "the embedded PyTorch fixture cannot be replayed: {0} (a bug in this build of ppo-tutor)"
    )]
    Fixture(String),
    /// The compiled harness could not be started.
    #[error("cannot run the compiled grader {binary}: {reason}")]
    Run {
        /// The harness.
        binary: PathBuf,
        /// The I/O error.
        reason: String,
    },
    /// Writing a starter back failed.
    #[error("cannot write {file}: {reason}")]
    Write {
        /// The file.
        file: PathBuf,
        /// The I/O error.
        reason: String,
    },
}

/// How to grade.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct GradeOptions {
    /// The longest a learner's program may run on all cases of one exercise.
    pub time_limit: Duration,
    /// Where compiled harnesses are kept.
    pub cache_dir: PathBuf,
}

impl Default for GradeOptions {
    /// 10 s; the cache in `$PPO_TUTOR_GRADE_CACHE` or the system's temporary folder.
    fn default() -> Self {
        let cache_dir = std::env::var_os("PPO_TUTOR_GRADE_CACHE").map_or_else(
            || std::env::temp_dir().join("ppo-tutor-grade"),
            PathBuf::from,
        );
        Self {
            time_limit: Duration::from_secs(10),
            cache_dir,
        }
    }
}

/// Every exercise name, in course order (`ppo_losses`, on candle tensors, follows the
/// plain exercises of its lesson).
#[must_use]
pub fn exercise_names() -> Vec<&'static str> {
    let mut names: Vec<(&str, &str)> = catalog::SPECS.iter().map(|s| (s.lesson, s.name)).collect();
    let after = names
        .iter()
        .rposition(|(lesson, _)| *lesson <= ppo_losses::LESSON)
        .map_or(0, |i| i + 1);
    names.insert(after, (ppo_losses::LESSON, ppo_losses::NAME));
    names.into_iter().map(|(_, name)| name).collect()
}

/// Where an exercise's files are: its lesson folder, starter and reference solution.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Files {
    /// The lesson folder under `lessons/`, e.g. `07-td-target`.
    pub lesson: &'static str,
    /// The starter's file name in it (`exercise.rs`).
    pub starter: &'static str,
    /// The reference solution's file name in it (`solution.rs`).
    pub solution: &'static str,
}

impl Files {
    /// The starter's path relative to the course root.
    #[must_use]
    pub fn starter_path(&self) -> String {
        format!("lessons/{}/{}", self.lesson, self.starter)
    }

    /// The reference solution's path relative to the course root.
    #[must_use]
    pub fn solution_path(&self) -> String {
        format!("lessons/{}/{}", self.lesson, self.solution)
    }
}

/// The files of exercise `name`, or [`GradeError::UnknownExercise`].
///
/// # Errors
/// [`GradeError::UnknownExercise`] listing the valid names.
pub fn files(name: &str) -> Result<Files, GradeError> {
    if name == ppo_losses::NAME {
        return Ok(Files {
            lesson: ppo_losses::LESSON,
            starter: ppo_losses::STARTER,
            solution: ppo_losses::SOLUTION,
        });
    }
    spec(name).map(|s| Files {
        lesson: s.lesson,
        starter: "exercise.rs",
        solution: "solution.rs",
    })
}

/// The exercise `name`, or [`GradeError::UnknownExercise`].
///
/// # Errors
/// [`GradeError::UnknownExercise`] listing the valid names.
pub fn spec(name: &str) -> Result<&'static Spec, GradeError> {
    catalog::find(name).ok_or_else(|| GradeError::UnknownExercise {
        name: name.to_string(),
        known: exercise_names().join(", "),
    })
}

/// The embedded starter of `name`'s lesson: its path relative to the course root and text.
#[must_use]
pub fn starter(name: &str) -> Option<(String, &'static str)> {
    let files = files(name).ok()?;
    let text =
        crate::lesson::loader::embedded_file(&format!("{}/{}", files.lesson, files.starter))?;
    Some((files.starter_path(), text))
}

/// The embedded reference solution of `name`'s lesson (shown after a pass).
#[must_use]
pub fn solution(name: &str) -> Option<&'static str> {
    let files = files(name).ok()?;
    crate::lesson::loader::embedded_file(&format!("{}/{}", files.lesson, files.solution))
}

/// Writes `name`'s starter back to `root/lessons/<lesson>/exercise.rs`; returns the path.
///
/// # Errors
/// [`GradeError::UnknownExercise`], or [`GradeError::Write`] if the file cannot be written.
pub fn reset(name: &str, root: &Path) -> Result<PathBuf, GradeError> {
    let files = files(name)?;
    let (rel, text) = starter(name).ok_or_else(|| GradeError::Write {
        file: PathBuf::from(files.starter_path()),
        reason: "no starter is embedded for this exercise".into(),
    })?;
    let path = root.join(rel);
    let write_err = |e: std::io::Error| GradeError::Write {
        file: path.clone(),
        reason: e.to_string(),
    };
    if let Some(dir) = path.parent() {
        std::fs::create_dir_all(dir).map_err(write_err)?;
    }
    std::fs::write(&path, text).map_err(write_err)?;
    Ok(path)
}

/// Grades exercise `name` in `file` (default: its starter path under the current folder).
///
/// # Errors
/// A [`GradeError`] when grading cannot happen (unknown exercise, unreadable file, no
/// rustc); a file that does not compile, panics or loops is a failing [`Report`].
pub fn grade(name: &str, file: Option<&Path>, opts: &GradeOptions) -> Result<Report, GradeError> {
    let files = files(name)?;
    let path = file.map_or_else(|| PathBuf::from(files.starter_path()), Path::to_path_buf);
    let source = std::fs::read_to_string(&path).map_err(|e| GradeError::Read {
        file: path.clone(),
        exercise: name.to_string(),
        reason: e.to_string(),
    })?;
    let display = path.display().to_string();
    if name == ppo_losses::NAME {
        return ppo_losses::grade_source(&source, &display, opts);
    }
    grade_source(spec(name)?, &source, &display, opts)
}

/// Grades `source` (the text of a learner's file, shown as `display`) against `spec`.
///
/// # Errors
/// [`GradeError::NoRustc`], [`GradeError::Cache`] or [`GradeError::Run`].
pub fn grade_source(
    spec: &Spec,
    source: &str,
    display: &str,
    opts: &GradeOptions,
) -> Result<Report, GradeError> {
    let checks = (spec.checks)();
    let mut report = Report {
        exercise: spec.name.to_string(),
        file: display.to_string(),
        compile_error: None,
        checks: Vec::new(),
        mistake: None,
    };
    let binary = match harness::build(spec, source, display, &opts.cache_dir)? {
        harness::Build::Ready(binary) => binary,
        harness::Build::Failed { summary, compiler } => {
            report.compile_error = Some((summary, compiler));
            report.checks = checks
                .iter()
                .map(|c| CheckReport {
                    name: c.name.clone(),
                    cases: c.cases.len(),
                    status: CheckStatus::NotRun("the file does not compile".into()),
                })
                .collect();
            return Ok(report);
        }
    };
    let mut input = String::new();
    for case in checks.iter().flat_map(|c| &c.cases) {
        let fields: Vec<String> = case.iter().map(value::Arg::encode).collect();
        input.push_str(&fields.join(" "));
        input.push('\n');
    }
    let run = harness::run(&binary, input, opts.time_limit)?;
    let answers = answers(spec, &checks, &run, display, opts.time_limit);
    (report.mistake, report.checks) = judge(spec, &checks, &answers);
    Ok(report)
}

/// The verdict on a learner's answers, one per case of `checks` in order: the known
/// mistake they match (if any) and one report line per check, its first failure carrying
/// the hint for that mistake.
fn judge(
    spec: &Spec,
    checks: &[CheckCases],
    answers: &[Answer],
) -> (Option<String>, Vec<CheckReport>) {
    let diagnosis = diagnose(spec, checks, answers);
    let hint = diagnosis.map_or(spec.hint, |m| m.hint);
    let mut lines = Vec::with_capacity(checks.len());
    let mut k = 0;
    for check in checks {
        let end = (k + check.cases.len()).min(answers.len());
        let status = check_status(spec, check, &answers[k.min(end)..end], hint);
        k = end;
        lines.push(CheckReport {
            name: check.name.clone(),
            cases: check.cases.len(),
            status,
        });
    }
    (diagnosis.map(|m| m.id.to_string()), lines)
}

/// What the learner's function did on one case.
#[derive(Debug, Clone, PartialEq)]
enum Answer {
    Value(Output),
    Panicked(String),
    TimedOut(u64),
    Crashed(String),
    NotRun,
}

/// One [`Answer`] per case, in order, from the harness's output.
fn answers(
    spec: &Spec,
    checks: &[CheckCases],
    run: &harness::Run,
    display: &str,
    limit: Duration,
) -> Vec<Answer> {
    let total: usize = checks.iter().map(|c| c.cases.len()).sum();
    let mut out: Vec<Answer> = run
        .lines
        .iter()
        .take(total)
        .map(|line| {
            if let Some(payload) = line.strip_prefix("ok") {
                spec.output.parse(payload).map_or_else(
                    || Answer::Crashed(format!("unreadable result '{payload}'")),
                    Answer::Value,
                )
            } else if let Some(message) = line.strip_prefix("panic ") {
                Answer::Panicked(harness::rename_learner(message, display))
            } else {
                Answer::Crashed(format!("unexpected output '{line}'"))
            }
        })
        .collect();
    if out.len() < total {
        // The case after the last answer is the one that hung or killed the program.
        out.push(match run.status {
            None => Answer::TimedOut(limit.as_secs().max(1)),
            Some(status) => {
                let stderr = harness::rename_learner(run.stderr.trim(), display);
                let last = stderr.lines().last().unwrap_or("no message");
                Answer::Crashed(format!("the program stopped ({status}): {last}"))
            }
        });
        out.resize(total, Answer::NotRun);
    }
    out
}

/// The known mistake that best explains the learner's answers: among the variants that
/// reproduce at least one wrong answer, the one agreeing with the learner on the most cases
/// (wrong and right ones alike, so a variant that is only wrong where the learner is wrong
/// beats one that happens to coincide on a single input).
fn diagnose(spec: &Spec, checks: &[CheckCases], answers: &[Answer]) -> Option<&'static Mistake> {
    let answered: Vec<(&Vec<value::Arg>, &Output, bool)> = checks
        .iter()
        .flat_map(|c| &c.cases)
        .zip(answers)
        .filter_map(|(case, answer)| match answer {
            Answer::Value(got) => {
                let right = got.matches(&(spec.reference)(Args(case)), spec.tolerance);
                Some((case, got, right))
            }
            _ => None,
        })
        .collect();
    let mut best: Option<(&'static Mistake, usize)> = None;
    for mistake in spec.mistakes {
        let agrees: Vec<bool> = answered
            .iter()
            .map(|(case, got, _)| got.matches(&(mistake.answer)(Args(case)), spec.tolerance))
            .collect();
        let explains_a_failure = answered
            .iter()
            .zip(&agrees)
            .any(|((_, _, right), a)| !right && *a);
        let score = agrees.iter().filter(|a| **a).count();
        if explains_a_failure && best.is_none_or(|(_, b)| score > b) {
            best = Some((mistake, score));
        }
    }
    best.map(|(m, _)| m)
}

fn check_status(spec: &Spec, check: &CheckCases, answers: &[Answer], hint: &str) -> CheckStatus {
    for (case, answer) in check.cases.iter().zip(answers) {
        let expected = (spec.reference)(Args(case));
        let (problem, got, detail, hint) = match answer {
            Answer::Value(got) => match got.differs(&expected, spec.tolerance) {
                None => continue,
                Some(detail) => (Problem::Wrong, got.show(), detail, hint.to_string()),
            },
            Answer::Panicked(m) => (
                Problem::Panicked(m.clone()),
                String::new(),
                String::new(),
                panic_hint(m),
            ),
            Answer::TimedOut(s) => (
                Problem::TimedOut(*s),
                String::new(),
                String::new(),
                "Check that every loop ends: a loop whose counter never moves, or a \
                 `while` whose condition stays true, never returns."
                    .to_string(),
            ),
            Answer::Crashed(m) => (
                Problem::Crashed(m.clone()),
                String::new(),
                String::new(),
                "The program died on this input: unbounded recursion (stack overflow) or \
                 std::process::exit are the usual causes."
                    .to_string(),
            ),
            Answer::NotRun => {
                return CheckStatus::NotRun("an earlier case stopped the program".into());
            }
        };
        let input = spec
            .params
            .iter()
            .zip(case)
            .map(|((name, _), arg)| ((*name).to_string(), arg.show()))
            .collect();
        return CheckStatus::Failed(Box::new(Failure {
            problem,
            input,
            expected: expected.show(),
            got,
            detail,
            hint,
        }));
    }
    CheckStatus::Passed
}

pub(crate) fn panic_hint(message: &str) -> String {
    let hint = if message.contains("not yet implemented") {
        "The starter's todo!() is still there: replace it with your implementation."
    } else if message.contains("out of bounds") || message.contains("range end index") {
        "An index went past the end of a slice: check the loop bounds (a single step, or the \
         first and last positions, are the usual suspects)."
    } else if message.contains("overflow") {
        "An integer went out of range, often a usize going below 0 (like i - 1 at i = 0): \
         check the bounds of your loops."
    } else {
        "Your function panicked on this input: run it by hand on the input above."
    };
    hint.to_string()
}
