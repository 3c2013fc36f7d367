//! Building the learner's file into a program, with one content-hashed cache.
//!
//! The learner's file is declared as a module `learner` of a small generated program
//! ([`Source`]: a `main.rs` that takes the exercise's function through a pointer of its
//! exact type, plus any support files) and built by its exercise's [`Backend`]:
//!
//! - [`Backend::Rustc`]: plain Rust, `rustc -O` into `<cache>/<name>-<key>/`;
//! - [`Backend::Cargo`]: code that uses candle, one binary target `l<key>` of a cargo
//!   project `<cache>/<name>/` ([`cargo`]).
//!
//! Both name a build by [`key`], a hash of every source that goes into it, so grading an
//! unchanged file again skips the build, and distinct files never overwrite each other.

pub mod cargo;
mod rustc;

use std::hash::{Hash, Hasher};
use std::path::{Path, PathBuf};

use super::error::GradeError;
use crate::i18n::Text;

/// How an exercise's program is built.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Backend {
    /// Plain Rust: `rustc` alone, a second or two.
    Rustc,
    /// Rust against candle: a cargo project in the cache; the first build compiles candle
    /// (minutes), later ones seconds.
    Cargo,
}

/// The program around the learner's file (which becomes `learner.rs`).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Source {
    /// `main.rs`: declares `mod learner;` and serves the function on stdin/stdout.
    pub main: String,
    /// Further files beside it, `(file name, text)`.
    pub files: Vec<(&'static str, &'static str)>,
}

/// The outcome of building a learner's program.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Build {
    /// The program.
    Ready(Program),
    /// The learner's file does not compile: a one-line summary and the compiler's errors
    /// (paths are the learner's).
    Failed {
        /// What went wrong, in one sentence.
        summary: Text,
        /// The compiler's output.
        compiler: String,
    },
}

/// A built learner program and the path its messages use for the learner's file.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Program {
    /// The executable.
    pub binary: PathBuf,
    /// The learner's file as the compiler names it (`learner.rs`, or
    /// `src/bin/l<key>/learner.rs` in the cargo project).
    pub learner_path: String,
}

impl Program {
    /// `text` with the program's name for the learner's file replaced by `display`.
    #[must_use]
    pub fn rename(&self, text: &str, display: &str) -> String {
        text.replace(&format!("{}:", self.learner_path), &format!("{display}:"))
    }
}

/// The cache key of a build from `parts` (and this version of ppo-tutor).
#[must_use]
pub fn key(parts: &[&str]) -> String {
    let mut h = std::hash::DefaultHasher::new();
    env!("CARGO_PKG_VERSION").hash(&mut h);
    for p in parts {
        p.hash(&mut h);
    }
    format!("{:016x}", h.finish())
}

/// Builds (or finds in `cache`) exercise `name`'s program `source` around `learner`, the learner's text
/// (`display` is its path in messages); `signature` is what a mismatch message asks for.
///
/// # Errors
/// [`GradeError::Cache`] if the cache cannot be written; [`GradeError::NoRustc`] or
/// [`GradeError::NoCargo`] if the compiler cannot be started; [`GradeError::Cargo`] if
/// cargo fails for a reason other than the learner's code.
pub fn build(
    name: &str,
    backend: Backend,
    source: &Source,
    signature: &str,
    learner: &str,
    display: &str,
    cache: &Path,
) -> Result<Build, GradeError> {
    let failed = |stderr: &str, main: &str, program: &Program, compiler: &str| Build::Failed {
        summary: summarize(name, signature, stderr, main, display, compiler),
        compiler: program.rename(stderr, display),
    };
    match backend {
        Backend::Rustc => rustc::build(name, source, learner, cache, failed),
        Backend::Cargo => cargo::build(name, source, learner, cache, failed),
    }
}

/// A sentence before a build that is slow the first time, `None` when it is quick.
#[must_use]
pub fn first_build_note(name: &str, backend: Backend, cache: &Path) -> Option<String> {
    (backend == Backend::Cargo && cargo::first_build_pending(name, cache)).then(|| {
        let dir = cargo::project_dir(name, cache);
        let dir = dir.display();
        crate::tr!(
            "Compiling candle for the candle exercise's grader in {dir} (the first time only: \
             a few minutes)…",
            "正在 {dir} 里为 candle 练习的评分器编译 candle（只有第一次需要，约几分钟）……"
        )
    })
}

/// One sentence for a failed build: the learner's own errors, or a missing, private or
/// mistyped function (errors in `main`, where the function is taken).
fn summarize(
    name: &str,
    signature: &str,
    stderr: &str,
    main: &str,
    display: &str,
    compiler: &str,
) -> Text {
    if !stderr.contains(&format!("--> {main}")) {
        return crate::text!(
            "{display} does not compile ({compiler}'s errors below)",
            "{display} 编译不通过（{compiler} 的报错见下）"
        );
    }
    if stderr.contains("E0425") || stderr.contains(&format!("cannot find function `{name}`")) {
        crate::text!(
            "{display} has no function `{name}`: write `{signature}`",
            "{display} 里没有函数 `{name}`：请写出 `{signature}`"
        )
    } else if stderr.contains("E0603") {
        crate::text!(
            "`{name}` in {display} is private: declare it `{signature}`",
            "{display} 里的 `{name}` 是私有的：请声明为 `{signature}`"
        )
    } else {
        crate::text!(
            "`{name}` in {display} does not have the exercise's signature: `{signature}`",
            "{display} 里的 `{name}` 与练习要求的签名不符：应为 `{signature}`"
        )
    }
}
