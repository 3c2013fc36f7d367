//! Building the learner's file into a program, with one content-hashed cache.
//!
//! The learner's file is declared as a module `learner` of a small generated program
//! ([`Source`]: a `main.rs` that takes the exercise's function through a pointer of its
//! exact type, plus any support files) and built by its exercise's [`Backend`]:
//!
//! - [`Backend::Rustc`]: plain Rust, `rustc -O` into `<cache>/<name>-<key>/` (about
//!   0.5 MB: the program is built without debug information);
//! - [`Backend::Cargo`]: code that uses candle, one binary target `l<key>` of a cargo
//!   project `<cache>/<name>/` ([`cargo`]): candle's build in it, about 380 MB, is made
//!   once and kept; each learner program is about 5 MB.
//!
//! Both name a build by [`key`], a hash of every source that goes into it, so grading an
//! unchanged file again skips the build, and distinct files never overwrite each other.
//! The cache is bounded: each build that is made deletes the exercise's builds beyond the
//! [`KEEP`] most recently used, so grading version after version of a file does not fill
//! the disk. The cache is `$PPO_TUTOR_GRADE_CACHE`, by default `ppo-tutor-grade` in the
//! system's temporary folder ([`crate::GradeOptions`]).

pub mod cargo;
mod rustc;

use std::hash::{Hash, Hasher};
use std::path::{Path, PathBuf};

use super::error::GradeError;
use super::progress::GradeProgress;
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

/// The serving loop every learner program shares ([`crate::harness`]), as text: a file
/// `harness.rs` beside the program's `main.rs`.
pub const HARNESS: &str = include_str!("harness.rs");

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

/// What to build: exercise `name`'s program `source` around `learner`, the learner's text.
#[derive(Debug, Clone, Copy)]
pub struct Request<'a> {
    /// The exercise (its function's name).
    pub name: &'a str,
    /// How its programs are built.
    pub backend: Backend,
    /// The program around the learner's file.
    pub source: &'a Source,
    /// What a mismatch message asks for.
    pub signature: &'a str,
    /// The learner's file, as text.
    pub learner: &'a str,
    /// The learner's file as messages name it.
    pub display: &'a str,
    /// The grading cache.
    pub cache: &'a Path,
}

/// Builds (or finds in the cache) `request`'s program, telling `progress` what it does
/// ([`GradeProgress::Building`] when a build starts, then cargo's steps for the candle
/// backend). Each build that is made deletes all but the [`KEEP`] newest of the
/// exercise's builds.
///
/// # Errors
/// [`GradeError::Cache`] if the cache cannot be written; [`GradeError::NoRustc`] or
/// [`GradeError::NoCargo`] if the compiler cannot be started; [`GradeError::Cargo`] if
/// cargo fails for a reason other than the learner's code.
pub fn build(
    request: &Request<'_>,
    progress: &mut dyn FnMut(&GradeProgress),
) -> Result<Build, GradeError> {
    let (name, signature, display) = (request.name, request.signature, request.display);
    let failed = |stderr: &str, main: &str, program: &Program, compiler: &str| Build::Failed {
        summary: summarize(name, signature, stderr, main, display, compiler),
        compiler: program.rename(stderr, display),
    };
    let (source, learner, cache) = (request.source, request.learner, request.cache);
    match request.backend {
        Backend::Rustc => rustc::build(name, source, learner, cache, progress, failed),
        Backend::Cargo => cargo::build(name, source, learner, cache, progress, failed),
    }
}

/// How many builds of each exercise the cache keeps: the most recently used ones (a
/// grading that finds its build marks it used). Several, not one, so gradings of two
/// versions at once (the tutor and the command line) do not delete each other's program.
pub const KEEP: usize = 4;

/// The file whose time says when a build was last used.
const USED: &str = "used";

/// Marks the build in folder `dir` as used now.
fn mark_used(dir: &Path) {
    let _ = std::fs::write(dir.join(USED), b"");
}

/// When the build in folder `dir` was last used (its folder's time if never marked).
fn last_used(dir: &Path) -> Option<std::time::SystemTime> {
    std::fs::metadata(dir.join(USED))
        .or_else(|_| std::fs::metadata(dir))
        .and_then(|m| m.modified())
        .ok()
}

/// The builds in `parent` that `is_build` accepts by name, other than `current`, least
/// recently used first, beyond the [`KEEP`] - 1 most recent: the ones to delete.
fn excess(parent: &Path, current: &str, is_build: impl Fn(&str) -> bool) -> Vec<String> {
    let Ok(entries) = std::fs::read_dir(parent) else {
        return Vec::new();
    };
    let mut builds: Vec<(Option<std::time::SystemTime>, String)> = entries
        .filter_map(Result::ok)
        .filter_map(|e| {
            let name = e.file_name().to_string_lossy().into_owned();
            (name != current && is_build(&name)).then(|| (last_used(&e.path()), name))
        })
        .collect();
    builds.sort();
    let excess = (builds.len() + 1).saturating_sub(KEEP);
    builds.into_iter().take(excess).map(|(_, n)| n).collect()
}

/// Whether `text` is a cache key as [`key`] writes it.
fn is_key(text: &str) -> bool {
    text.len() == 16 && text.bytes().all(|b| b.is_ascii_hexdigit())
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
