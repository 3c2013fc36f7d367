//! Why grading could not happen at all, and how to grade: the leaf every part of the
//! grader shares.

use std::path::PathBuf;
use std::time::Duration;

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
    /// The embedded course content is broken (a bug in this build of ppo-tutor).
    #[error("the embedded course content is broken: {0} (a bug in this build of ppo-tutor)")]
    Content(String),
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
