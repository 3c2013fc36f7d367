//! Graded exercises: the learner writes PPO's pieces in Rust and the tutor grades them.
//!
//! Every exercise is one function that applies an idea of its lesson (`n_step_target`,
//! `compute_advantage`, `kl_early_stop`, ...) with a starter in its lesson folder (`todo!()` and TODO comments) and
//! a reference solution beside it. The exercises are listed once, in course order, in the
//! [`exercises()`] registry; every face (the terminal app, `ppo-tutor grade`/`reset`, the
//! notebooks, the tests) iterates it and none names a particular exercise.
//!
//! ```text
//! grade.rs            the registry's API: find, grade, reset (options go down)
//!   exercises/<name>  one module per exercise: signature, reference, cases, mistakes
//!   exercise.rs       the trait the faces see (files, signature, grade_source)
//!   spec.rs           the typed trait each exercise implements
//!   pipeline.rs       the one pipeline: not started?, build, ask, judge, follow up
//!   not_started.rs    a function still the starter's todo!(), seen before any build
//!   progress.rs       what a grading is doing, for a face to show (cargo's steps)
//!   plain.rs          plain-Rust exercises (rustc), a `Spec` from a table of fields
//!   build.rs          one content-hashed build cache; backends rustc and cargo (candle)
//!   learner.rs        answers from the learner's program or an in-process function
//!   harness.rs        the serving loop inside every learner program (marked answers)
//!   judge.rs          first failing case per check, diagnosis against the catalogue
//!   prose.rs          hints from lessons/NN-slug/exercise.toml   (reports come up)
//! ```
//!
//! Grading a file: a function still the starter's `todo!()` is reported as not started
//! at once; otherwise its backend builds it inside a generated program (cached by content
//! hash, a few builds per exercise kept); the program is asked every case (seeded random inputs, the recorded PyTorch
//! episodes, edge cases); the judge compares each answer with the reference's within a
//! tolerance, keeps the first failure of each check with its input, expected and actual
//! results, and names the likely mistake from the exercise's catalogue of typical wrong
//! variants (GAE run forwards, a sum across an episode's end, min instead of max, ...), whose hint
//! comes from the lesson's `exercise.toml`. Panics are caught per case and reported with
//! their message; a run past the time limit is killed (with every process it started) and
//! reported as never returning. What the learner's code prints is shown beside its case, a
//! few lines of it. The grader itself returns errors, never panics.
//!
//! ```
//! let exercise = ppo_grade::find("reverse_kl")?;
//! assert_eq!(
//!     exercise.signature(),
//!     "pub fn reverse_kl(old_log_probs: &[f32], log_probs: &[f32]) -> f32"
//! );
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

// The engine's modules, as `crate::ppo`, `crate::lesson`, ... inside this crate.
pub(crate) use ppo_engine::{env, i18n, lesson, ppo, text, tr};

pub mod build;
pub mod error;
pub mod exercise;
pub mod exercises;
pub mod fixture;
pub mod harness;
pub mod hints;
pub mod in_process;
pub mod judge;
pub mod learner;
pub mod not_started;
pub mod notebook;
pub mod pipeline;
pub mod plain;
pub mod progress;
pub mod prose;
pub mod renumber;
pub mod report;
pub mod reset;
pub mod solutions;
pub mod spec;
pub mod value;

use std::path::{Path, PathBuf};

pub use build::Backend;
pub use error::{GradeError, GradeOptions};
pub use exercise::{Exercise, Meta};
pub use progress::GradeProgress;
pub use report::{CheckReport, CheckStatus, Failure, Problem, Report};

/// Every exercise, in course order.
#[must_use]
pub fn exercises() -> &'static [&'static dyn Exercise] {
    exercises::ALL
}

/// Every exercise name, in course order.
#[must_use]
pub fn exercise_names() -> Vec<&'static str> {
    exercises::ALL.iter().map(|e| e.name()).collect()
}

/// The exercise `name`.
///
/// # Errors
/// [`GradeError::UnknownExercise`] listing the valid names.
pub fn find(name: &str) -> Result<&'static dyn Exercise, GradeError> {
    exercises::ALL
        .iter()
        .copied()
        .find(|e| e.name() == name)
        .ok_or_else(|| GradeError::UnknownExercise {
            name: name.to_string(),
            known: exercise_names().join(", "),
        })
}

/// The embedded starter of `name`: its path relative to the course root, and its text.
#[must_use]
pub fn starter(name: &str) -> Option<(String, &'static str)> {
    let exercise = find(name).ok()?;
    Some((exercise.starter_path(), exercise.starter()?))
}

/// The embedded reference solution of `name` (shown after a pass).
#[must_use]
pub fn solution(name: &str) -> Option<&'static str> {
    find(name).ok()?.solution()
}

/// Writes `name`'s starter back under `root` (only its function when other exercises share
/// the file, a changed file kept as `.bak` first); says what it did.
///
/// # Errors
/// [`GradeError::UnknownExercise`], or [`GradeError::Write`] if the file cannot be written.
pub fn reset(name: &str, root: &Path) -> Result<reset::Restored, GradeError> {
    find(name)?.reset(root)
}

/// Grades exercise `name` in `file` (default: its starter path under the current folder).
///
/// # Errors
/// A [`GradeError`] when grading cannot happen (unknown exercise, unreadable file, no
/// compiler); a file that does not compile, panics or loops is a failing [`Report`].
pub fn grade(name: &str, file: Option<&Path>, opts: &GradeOptions) -> Result<Report, GradeError> {
    grade_with_progress(name, file, opts, &mut |_| {})
}

/// [`grade`], saying what it is doing as it goes: `progress` is called on this thread with
/// each [`GradeProgress`] (the build, cargo's steps when candle is compiled, the checks).
///
/// # Errors
/// As [`grade`].
pub fn grade_with_progress(
    name: &str,
    file: Option<&Path>,
    opts: &GradeOptions,
    progress: &mut dyn FnMut(&GradeProgress),
) -> Result<Report, GradeError> {
    let exercise = find(name)?;
    let path = file.map_or_else(|| PathBuf::from(exercise.starter_path()), Path::to_path_buf);
    let source = std::fs::read_to_string(&path).map_err(|e| GradeError::Read {
        file: path.clone(),
        exercise: name.to_string(),
        given: file.is_some(),
        missing: e.kind() == std::io::ErrorKind::NotFound,
        reason: crate::error::reason(&e),
    })?;
    exercise.grade_source_with_progress(&source, &path.display().to_string(), opts, progress)
}
