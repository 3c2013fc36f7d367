//! Learners' lesson folders from an older numbering of the course, moved to the current one.
//!
//! A course folder written by `ppo-tutor init` (or a clone) holds the learner's exercise files
//! under `lessons/NN-slug/`. When the course gains a lesson, the lessons after it change
//! number (lesson 10 `trust-region` moved `10-clipping` to `11-clipping`, and so on), and the
//! tutor would look for the learner's work in a folder that does not exist. [`move_renumbered`]
//! renames each such folder to its current name, once, before anything reads the files: the
//! slug, not the number, says which lesson a folder is.
//!
//! Nothing is overwritten: a folder is moved only when the current name is free and exactly
//! one folder carries the slug under another number.
//!
//! ```
//! let root = std::env::temp_dir().join(format!("ppo-renumber-doc-{}", std::process::id()));
//! std::fs::create_dir_all(root.join("lessons/10-clipping"))?;
//! std::fs::write(root.join("lessons/10-clipping/exercise.rs"), "// my work")?;
//! let moved = ppo_grade::renumber::move_renumbered(&root);
//! assert_eq!(moved.len(), 1);
//! assert!(root.join("lessons/11-clipping/exercise.rs").exists());
//! std::fs::remove_dir_all(&root)?;
//! # Ok::<(), std::io::Error>(())
//! ```

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

/// What happened to one folder.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Moved {
    /// `from` was renamed to `to`.
    Renamed {
        /// The folder as it was, e.g. `lessons/10-clipping`.
        from: PathBuf,
        /// Its current name, e.g. `lessons/11-clipping`.
        to: PathBuf,
    },
    /// `from` should have been renamed to `to` but the rename failed (the message says why).
    Failed {
        /// The folder as it is.
        from: PathBuf,
        /// Its current name.
        to: PathBuf,
        /// The operating system's error.
        error: String,
    },
}

impl Moved {
    /// One line for the learner, in the current language.
    #[must_use]
    pub fn message(&self) -> String {
        match self {
            Self::Renamed { from, to } => {
                let (from, to) = (from.display(), to.display());
                crate::tr!(
                    "moved {from} to {to} (the course's lessons were renumbered)",
                    "已把 {from} 移到 {to}（课程的各课重新编了号）"
                )
            }
            Self::Failed { from, to, error } => {
                let (from, to) = (from.display(), to.display());
                crate::tr!(
                    "could not move {from} to {to} ({error}): move it by hand, your work is in it",
                    "无法把 {from} 移到 {to}（{error}）：请手动移动，你的代码在里面"
                )
            }
        }
    }
}

/// Renames every `lessons/MM-slug` folder under `root` whose lesson is now numbered `NN`
/// (the lesson folders the exercises live in) to `lessons/NN-slug`. Returns what was moved
/// or failed to move; an empty list when every folder already has its current name or there
/// is no `lessons` folder at all.
#[must_use]
pub fn move_renumbered(root: &Path) -> Vec<Moved> {
    let current: BTreeSet<&str> = crate::exercises().iter().map(|e| e.meta().lesson).collect();
    let lessons = root.join("lessons");
    let Ok(entries) = std::fs::read_dir(&lessons) else {
        return Vec::new();
    };
    let present: Vec<String> = entries
        .filter_map(Result::ok)
        .filter(|e| e.path().is_dir())
        .filter_map(|e| e.file_name().to_str().map(str::to_owned))
        .collect();
    let mut out = Vec::new();
    for folder in current {
        let Some((_, slug)) = split(folder) else {
            continue;
        };
        let to = lessons.join(folder);
        if to.exists() {
            continue;
        }
        let old: Vec<&String> = present
            .iter()
            .filter(|p| p.as_str() != folder && split(p).is_some_and(|(_, s)| s == slug))
            .collect();
        let [old] = old[..] else {
            continue;
        };
        let from = lessons.join(old);
        out.push(match std::fs::rename(&from, &to) {
            Ok(()) => Moved::Renamed { from, to },
            Err(e) => Moved::Failed {
                from,
                to,
                error: e.to_string(),
            },
        });
    }
    out
}

/// `07-td-target` as `("07", "td-target")`; `None` without a two-digit prefix.
fn split(folder: &str) -> Option<(&str, &str)> {
    let (number, slug) = folder.split_once('-')?;
    (number.len() == 2 && number.bytes().all(|b| b.is_ascii_digit()) && !slug.is_empty())
        .then_some((number, slug))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn course() -> tempfile::TempDir {
        tempfile::tempdir().unwrap_or_else(|e| panic!("temp dir: {e}"))
    }

    fn write(root: &Path, rel: &str, text: &str) {
        let path = root.join(rel);
        if let Some(parent) = path.parent() {
            std::fs::create_dir_all(parent).unwrap_or_else(|e| panic!("{e}"));
        }
        std::fs::write(path, text).unwrap_or_else(|e| panic!("{e}"));
    }

    #[test]
    fn old_numbers_move_to_the_current_ones_with_the_work_inside() {
        let dir = course();
        let root = dir.path();
        // The folder names of the numbering before lesson 10 (trust-region) was added.
        write(root, "lessons/10-clipping/exercise.rs", "// mine: clipping");
        write(
            root,
            "lessons/11-losses/exercise_candle.rs",
            "// mine: candle",
        );
        write(
            root,
            "lessons/16-continuous-actions/exercise.rs",
            "// mine: gaussian",
        );
        write(root, "lessons/09-ratio/exercise.rs", "// unchanged");
        let moved = move_renumbered(root);
        let names: Vec<String> = moved.iter().map(Moved::message).collect();
        assert_eq!(moved.len(), 3, "{names:?}");
        assert!(moved.iter().all(|m| matches!(m, Moved::Renamed { .. })));
        let read = |rel: &str| std::fs::read_to_string(root.join(rel)).ok();
        assert_eq!(
            read("lessons/11-clipping/exercise.rs").as_deref(),
            Some("// mine: clipping")
        );
        assert_eq!(
            read("lessons/12-losses/exercise_candle.rs").as_deref(),
            Some("// mine: candle")
        );
        assert_eq!(
            read("lessons/17-continuous-actions/exercise.rs").as_deref(),
            Some("// mine: gaussian")
        );
        assert_eq!(
            read("lessons/09-ratio/exercise.rs").as_deref(),
            Some("// unchanged")
        );
        assert!(!root.join("lessons/10-clipping").exists());
        // A second run finds nothing left to move.
        assert!(move_renumbered(root).is_empty());
    }

    #[test]
    fn nothing_is_overwritten_or_guessed() {
        let dir = course();
        let root = dir.path();
        // The current folder exists: the old one stays where it is.
        write(root, "lessons/11-clipping/exercise.rs", "// current");
        write(root, "lessons/10-clipping/exercise.rs", "// old");
        // Two candidates for one lesson: ambiguous, left alone.
        write(root, "lessons/11-losses/exercise.rs", "// a");
        write(root, "lessons/13-losses/exercise.rs", "// b");
        assert!(move_renumbered(root).is_empty());
        assert!(root.join("lessons/10-clipping/exercise.rs").exists());
        assert!(root.join("lessons/11-losses/exercise.rs").exists());
        // No lessons folder at all: nothing to do.
        let empty = course();
        assert!(move_renumbered(empty.path()).is_empty());
    }

    #[test]
    fn folder_names_split_on_their_two_digit_number() {
        assert_eq!(split("07-td-target"), Some(("07", "td-target")));
        assert_eq!(split("7-td-target"), None);
        assert_eq!(split("ab-cd"), None);
        assert_eq!(split("07-"), None);
        assert_eq!(split("glossary.toml"), None);
    }
}
