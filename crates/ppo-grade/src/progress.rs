//! What a grading is doing while it runs, for a face to show: the build of the learner's
//! program (the candle exercise's first build compiles candle, about two minutes on two
//! cores), cargo's progress through it, then the checks.
//!
//! A face passes a callback to [`crate::grade_with_progress`] (or
//! [`crate::Exercise::grade_source_with_progress`]); it is called on the grading thread,
//! in order, and only when something changed. A face on another thread sends each
//! [`GradeProgress`] over its channel:
//!
//! ```no_run
//! let (tx, rx) = std::sync::mpsc::channel();
//! std::thread::spawn(move || {
//!     let opts = ppo_grade::GradeOptions::default();
//!     let report = ppo_grade::grade_with_progress("ppo_losses", None, &opts, &mut |p| {
//!         let _ = tx.send(p.clone());
//!     });
//!     drop(report);
//! });
//! for progress in rx {
//!     println!("{progress}"); // building candle (first time, ~2 min): Compiling gemm (37/120)
//! }
//! ```

use std::path::PathBuf;

use crate::i18n::Text;
use crate::text;

/// One step of a grading, as it happens.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum GradeProgress {
    /// The learner's program is being built. `first_time`: this build compiles candle for
    /// the candle exercise (minutes, once per grading cache), in `dir`.
    Building {
        /// Whether this build compiles candle.
        first_time: bool,
        /// The folder being built in.
        dir: PathBuf,
    },
    /// cargo compiles `krate` (`done` of `total` build steps finished; `total` is 0 until
    /// cargo has counted them).
    Compiling {
        /// The crate, as cargo names it (`candle-core`).
        krate: String,
        /// Build steps finished.
        done: usize,
        /// Build steps in all (0: not known yet).
        total: usize,
        /// Whether this build compiles candle (see [`GradeProgress::Building`]).
        first_time: bool,
    },
    /// cargo waits for another build of the same project to finish (two gradings at once:
    /// the tutor and the command line).
    Waiting,
    /// The learner's program answers the cases.
    Checking,
}

impl GradeProgress {
    /// One line saying so, in both languages (shown later, in the language of the moment).
    #[must_use]
    pub fn text(&self) -> Text {
        match self {
            Self::Building {
                first_time: true,
                dir,
            } => {
                let dir = dir.display();
                text!(
                    "building candle for the grader in {dir} (the first time only: about 2 \
                     minutes on two cores)…",
                    "正在 {dir} 里为评分器构建 candle（只有第一次需要：双核约 2 分钟）……"
                )
            }
            Self::Building { .. } => Text::new("building your code…", "正在编译你的代码……"),
            Self::Compiling {
                krate,
                done,
                total,
                first_time,
            } => {
                let (en, zh) = if *total == 0 {
                    (String::new(), String::new())
                } else {
                    (format!(" ({done}/{total})"), format!("（{done}/{total}）"))
                };
                if *first_time {
                    Text::owned(
                        format!("building candle (first time, ~2 min): Compiling {krate}{en}"),
                        format!("正在构建 candle（第一次，约 2 分钟）：编译 {krate}{zh}"),
                    )
                } else {
                    Text::owned(
                        format!("building: Compiling {krate}{en}"),
                        format!("正在构建：编译 {krate}{zh}"),
                    )
                }
            }
            Self::Waiting => Text::new(
                "waiting for another grading's build of the same exercise (cargo's lock)…",
                "正在等待同一练习的另一次评分构建完成（cargo 的锁）……",
            ),
            Self::Checking => Text::new("running the checks…", "正在运行各项检查……"),
        }
    }
}

impl std::fmt::Display for GradeProgress {
    /// The line in the current language.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        self.text().fmt(f)
    }
}
