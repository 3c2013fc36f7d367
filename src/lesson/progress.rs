//! Where the learner is and what is done, saved atomically between runs.
//!
//! The state file is small JSON (`.ppo-tutor-state.json` in the working directory, or
//! the path in `PPO_TUTOR_STATE`). It is written to a temporary file and renamed, so a
//! crash never leaves half a file; a corrupt file yields a warning and a fresh start.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

/// The default state file name (in the working directory).
pub const STATE_FILE: &str = ".ppo-tutor-state.json";

/// The learner's progress.
#[derive(Debug, Clone, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(default)]
pub struct Progress {
    /// The lesson open last.
    pub lesson: String,
    /// The step open last in that lesson (0-based).
    pub step: usize,
    /// Lessons whose every step has been seen.
    pub lessons_done: BTreeSet<String>,
    /// Exercises graded as passing.
    pub exercises_done: BTreeSet<String>,
    /// Quiz questions answered, by `lesson#number` (e.g. `gae#2`): whether the first answer
    /// was right.
    pub quiz: BTreeMap<String, bool>,
}

impl Progress {
    /// The key of question `number` (from 1) of lesson `lesson` in [`Self::quiz`].
    #[must_use]
    pub fn quiz_key(lesson: &str, number: usize) -> String {
        format!("{lesson}#{number}")
    }

    /// Records the first answer to a question (later ones do not change it).
    pub fn record_quiz(&mut self, lesson: &str, number: usize, right: bool) {
        self.quiz
            .entry(Self::quiz_key(lesson, number))
            .or_insert(right);
    }

    /// `(answered, right)` over every question recorded.
    #[must_use]
    pub fn quiz_score(&self) -> (usize, usize) {
        (self.quiz.len(), self.quiz.values().filter(|r| **r).count())
    }
}

impl Progress {
    /// The state file to use: `PPO_TUTOR_STATE` if set, else [`STATE_FILE`].
    #[must_use]
    pub fn default_path() -> PathBuf {
        std::env::var_os("PPO_TUTOR_STATE").map_or_else(|| PathBuf::from(STATE_FILE), PathBuf::from)
    }

    /// Loads progress from `path`. A missing file is a fresh start; a corrupt one is a fresh
    /// start plus a warning naming the file.
    #[must_use]
    pub fn load(path: &Path) -> (Self, Option<String>) {
        match std::fs::read_to_string(path) {
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => (Self::default(), None),
            Err(e) => (
                Self::default(),
                Some(format!(
                    "could not read {}: {e}; starting fresh",
                    path.display()
                )),
            ),
            Ok(text) => match serde_json::from_str(&text) {
                Ok(p) => (p, None),
                Err(e) => (
                    Self::default(),
                    Some(format!(
                        "{} is not a valid progress file ({e}); starting fresh (it will be overwritten)",
                        path.display()
                    )),
                ),
            },
        }
    }

    /// Saves to `path` atomically (write a sibling temporary file, then rename).
    ///
    /// # Errors
    /// The directory is not writable.
    pub fn save(&self, path: &Path) -> std::io::Result<()> {
        let json = serde_json::to_string_pretty(self).map_err(std::io::Error::other)?;
        let mut tmp = path.as_os_str().to_owned();
        tmp.push(".tmp");
        let tmp = PathBuf::from(tmp);
        std::fs::write(&tmp, json)?;
        std::fs::rename(&tmp, path)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn round_trip_and_corrupt_file() -> Result<(), Box<dyn std::error::Error>> {
        let dir = tempfile::tempdir()?;
        let path = dir.path().join("state.json");
        let (fresh, warning) = Progress::load(&path);
        assert_eq!(fresh, Progress::default());
        assert!(warning.is_none());
        let mut p = Progress {
            lesson: "gae".into(),
            step: 2,
            ..Progress::default()
        };
        p.lessons_done.insert("networks".into());
        p.record_quiz("gae", 2, false);
        p.record_quiz("gae", 2, true);
        p.record_quiz("gae", 3, true);
        assert_eq!(
            p.quiz_score(),
            (2, 1),
            "a second answer does not change the first"
        );
        p.save(&path)?;
        assert_eq!(Progress::load(&path).0, p);
        std::fs::write(&path, "{not json")?;
        let (after, warning) = Progress::load(&path);
        assert_eq!(after, Progress::default());
        assert!(warning.is_some_and(|w| w.contains("state.json")));
        Ok(())
    }
}
