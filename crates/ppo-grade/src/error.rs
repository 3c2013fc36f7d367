//! Why grading could not happen at all, and how to grade: the leaf every part of the
//! grader shares.

use std::path::PathBuf;
use std::time::Duration;

use crate::i18n::Text;
use crate::tr;

/// Why grading could not happen at all (a learner's bad file is a [`Report`](crate::Report), not this).
#[derive(Debug)]
pub enum GradeError {
    /// No exercise has this name.
    UnknownExercise {
        /// The name given.
        name: String,
        /// The valid names, comma-separated.
        known: String,
    },
    /// The learner's file cannot be read.
    Read {
        /// The file.
        file: PathBuf,
        /// The exercise.
        exercise: String,
        /// Whether the caller gave the file (else it is the exercise's starter path).
        given: bool,
        /// Whether the file does not exist.
        missing: bool,
        /// The I/O error, in both languages.
        reason: Text,
    },
    /// `rustc` could not be started.
    NoRustc {
        /// The program tried.
        rustc: PathBuf,
        /// The I/O error, in both languages.
        reason: Text,
    },
    /// The cache folder cannot be written.
    Cache {
        /// The folder.
        dir: PathBuf,
        /// The I/O error, in both languages.
        reason: Text,
    },
    /// `cargo` could not be started (the candle exercise is built with cargo).
    NoCargo {
        /// The program tried.
        cargo: PathBuf,
        /// The I/O error, in both languages.
        reason: Text,
    },
    /// cargo failed for a reason other than the learner's code.
    Cargo {
        /// The project folder.
        dir: PathBuf,
        /// cargo's last lines of output.
        message: String,
    },
    /// The embedded course content is broken (a bug in this build of ppo-tutor).
    Content(String),
    /// The embedded PyTorch fixture could not be replayed (a broken build).
    Fixture(String),
    /// The compiled harness could not be started.
    Run {
        /// The harness.
        binary: PathBuf,
        /// The I/O error, in both languages.
        reason: Text,
    },
    /// Writing a starter back failed.
    Write {
        /// The file.
        file: PathBuf,
        /// The I/O error, in both languages.
        reason: Text,
    },
}

impl std::error::Error for GradeError {}

/// A lower layer's error (`io`, `serde_json`, …) as a [`GradeError`]'s `reason`: its
/// message in both languages ([`ppo_engine::causes::message`]).
pub(crate) fn reason(e: &(dyn std::error::Error + 'static)) -> Text {
    Text::in_each(|| ppo_engine::causes::message(e))
}

impl std::fmt::Display for GradeError {
    /// The message in the current language (flags, paths and commands as they are).
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let text = match self {
            Self::UnknownExercise { name, known } => tr!(
                "unknown exercise '{name}': the exercises are {known}",
                "没有名为 '{name}' 的练习；现有的练习：{known}"
            ),
            Self::Read {
                file,
                exercise,
                given,
                missing,
                reason,
            } => {
                let file = file.display();
                match (given, missing) {
                    (true, true) => tr!(
                        "{file} does not exist: check the path",
                        "{file} 不存在：请检查路径"
                    ),
                    (true, false) => tr!(
                        "cannot read {file}: {reason} (check the path)",
                        "无法读取 {file}：{reason}（请检查路径）"
                    ),
                    (false, _) => tr!(
                        "cannot read {file}: {reason} (run `ppo-tutor reset {exercise}` to restore the starter)",
                        "无法读取 {file}：{reason}（运行 `ppo-tutor reset {exercise}` 恢复初始文件）"
                    ),
                }
            }
            Self::NoRustc { rustc, reason } => {
                let rustc = rustc.display();
                tr!(
                    "cannot run the Rust compiler '{rustc}': {reason}; install Rust (https://rustup.rs) or set RUSTC to rustc's path",
                    "无法运行 Rust 编译器 '{rustc}'：{reason}。请安装 Rust（https://rustup.rs），或把 RUSTC 设为 rustc 的路径"
                )
            }
            Self::Cache { dir, reason } => {
                let dir = dir.display();
                tr!(
                    "cannot write the grading cache {dir}: {reason} (set PPO_TUTOR_GRADE_CACHE to a writable folder)",
                    "无法写入评分缓存 {dir}：{reason}（请把 PPO_TUTOR_GRADE_CACHE 设为可写的文件夹）"
                )
            }
            Self::NoCargo { cargo, reason } => {
                let cargo = cargo.display();
                tr!(
                    "cannot run cargo '{cargo}': {reason}; the candle exercise is built with cargo: install Rust (https://rustup.rs) or set CARGO to cargo's path",
                    "无法运行 cargo '{cargo}'：{reason}。candle 练习要用 cargo 构建：请安装 Rust（https://rustup.rs），或把 CARGO 设为 cargo 的路径"
                )
            }
            Self::Cargo { dir, message } => {
                let dir = dir.display();
                tr!(
                    "cargo could not build the candle grader in {dir}:\n{message}\n(the first build fetches and compiles candle: it needs the crates.io registry or cargo's download cache; delete {dir} to start over)",
                    "cargo 无法在 {dir} 中构建 candle 评分器：\n{message}\n（第一次构建要下载并编译 candle，需要能访问 crates.io 或有 cargo 的下载缓存；删除 {dir} 即可重新开始）"
                )
            }
            Self::Content(why) => tr!(
                "the embedded course content is broken: {why} (a bug in this build of ppo-tutor)",
                "内置的课程内容有误：{why}（这是本版 ppo-tutor 的 bug）"
            ),
            Self::Fixture(why) => tr!(
                "the embedded PyTorch fixture cannot be replayed: {why} (a bug in this build of ppo-tutor)",
                "内置的 PyTorch 录制数据无法回放：{why}（这是本版 ppo-tutor 的 bug）"
            ),
            Self::Run { binary, reason } => {
                let binary = binary.display();
                tr!(
                    "cannot run the compiled grader {binary}: {reason}",
                    "无法运行编译好的评分器 {binary}：{reason}"
                )
            }
            Self::Write { file, reason } => {
                let file = file.display();
                tr!("cannot write {file}: {reason}", "无法写入 {file}：{reason}")
            }
        };
        f.write_str(&text)
    }
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
