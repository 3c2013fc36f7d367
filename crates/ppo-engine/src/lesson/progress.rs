//! Where the learner is and what is done, saved atomically between runs.
//!
//! The state file is small JSON (`.ppo-tutor-state.json` in the working directory, or
//! the path in `PPO_TUTOR_STATE`). It is written to a temporary file and renamed, so a
//! crash never leaves half a file; a corrupt file yields a warning and a fresh start.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use super::Course;

/// The default state file name (in the working directory).
pub const STATE_FILE: &str = ".ppo-tutor-state.json";

/// The numbering of quiz questions that [`Progress::quiz`] keys follow now. A progress file
/// written before a numbering existed (with no `quiz_numbering`) is 0, and loading it moves
/// its answers by [`RENUMBERED`]; one written before numbering 2 forgets its answers to the
/// questions in [`REPLACED`], and one written before numbering 3 those in [`REPLACED_3`].
pub const QUIZ_NUMBERING: u32 = 3;

/// A quiz question by lesson id and number (from 1), as in [`Progress::quiz_key`].
pub type QuestionAt = (&'static str, usize);

/// How questions moved from numbering 0 to 1 (issue 25, section 2): `(lesson, number)` before,
/// then after. Lesson 1's questions 2 (the clip at r = 1.35) and 3 (GAE with λ = 0) went to
/// the lessons that teach them, as clipping's question 1 and gae's question 2, and the
/// questions from there on in those quizzes are one number later; lesson 1's question 4 is
/// now 3, after a new question 2 that no saved answer belongs to.
pub const RENUMBERED: &[(QuestionAt, QuestionAt)] = &[
    (("what-is-ppo", 2), ("clipping", 1)),
    (("what-is-ppo", 3), ("gae", 2)),
    (("what-is-ppo", 4), ("what-is-ppo", 3)),
    (("gae", 2), ("gae", 3)),
    (("gae", 3), ("gae", 4)),
    (("gae", 4), ("gae", 5)),
    (("clipping", 1), ("clipping", 2)),
    (("clipping", 2), ("clipping", 3)),
    (("clipping", 3), ("clipping", 4)),
    (("clipping", 4), ("clipping", 5)),
];

/// Questions replaced in place at numbering 2 (issue 27, section 3): the fixed-fact
/// predictions that asked again what another lesson asks ("every ratio is 1 in epoch 1",
/// one done per batch) or that a question depending on the run now asks better. An answer
/// saved before belongs to the old question, and is forgotten.
pub const REPLACED: &[QuestionAt] = &[
    ("what-is-ppo", 3),
    ("policy-gradient", 4),
    ("gae", 5),
    ("ratio", 2),
    ("clipping", 5),
    ("losses", 1),
    ("beyond-the-seed", 3),
    ("continuous-actions", 3),
    ("pendulum", 2),
];

/// Questions replaced in place at numbering 3 (issue 27, section 5): the hyper-parameter
/// recap's questions on the critic's rate and on epochs and ε, now questions on that
/// lesson's own one-knob experiments, and the training lesson's questions on the smoothed
/// curve's first value and on centred windows, now questions on what seeds show. An answer
/// saved before belongs to the old question, and is forgotten.
pub const REPLACED_3: &[QuestionAt] = &[
    ("training", 2),
    ("training", 3),
    ("hyperparameters", 3),
    ("hyperparameters", 4),
];

/// The learner's progress.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
#[serde(default)]
pub struct Progress {
    /// The lesson open last.
    pub lesson: String,
    /// The step open last in that lesson (0-based).
    pub step: usize,
    /// Lessons done: every step seen and, when the lesson has a quiz, every question
    /// answered (skipping the quiz does not count).
    pub lessons_done: BTreeSet<String>,
    /// Exercises graded as passing.
    pub exercises_done: BTreeSet<String>,
    /// Quiz questions answered, by `lesson#number` (e.g. `gae#2`): whether the first answer
    /// was right.
    pub quiz: BTreeMap<String, bool>,
    /// The numbering [`Self::quiz`] follows: [`QUIZ_NUMBERING`], or 0 in a file written
    /// before it existed.
    #[serde(default)]
    pub quiz_numbering: u32,
}

impl Default for Progress {
    fn default() -> Self {
        Self {
            lesson: String::new(),
            step: 0,
            lessons_done: BTreeSet::new(),
            exercises_done: BTreeSet::new(),
            quiz: BTreeMap::new(),
            quiz_numbering: QUIZ_NUMBERING,
        }
    }
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

    /// Moves answers saved under an older numbering of the questions to the current one
    /// ([`RENUMBERED`]), so that an answer stays with its question, and forgets those whose
    /// question was replaced since ([`REPLACED`]).
    pub fn renumber_quiz(&mut self) {
        if self.quiz_numbering >= QUIZ_NUMBERING {
            return;
        }
        if self.quiz_numbering < 1 {
            let old = std::mem::take(&mut self.quiz);
            for (key, right) in old {
                let moved = RENUMBERED.iter().find_map(|((id, n), (to, m))| {
                    (key == Self::quiz_key(id, *n)).then(|| Self::quiz_key(to, *m))
                });
                self.quiz.entry(moved.unwrap_or(key)).or_insert(right);
            }
        }
        let replaced: Vec<&QuestionAt> = if self.quiz_numbering < 2 {
            REPLACED.iter().chain(REPLACED_3).collect()
        } else {
            REPLACED_3.iter().collect()
        };
        self.quiz.retain(|key, _| {
            !replaced
                .iter()
                .any(|(id, n)| *key == Self::quiz_key(id, *n))
        });
        self.quiz_numbering = QUIZ_NUMBERING;
    }

    /// `(answered, right)` over every question recorded.
    #[must_use]
    pub fn quiz_score(&self) -> (usize, usize) {
        (self.quiz.len(), self.quiz.values().filter(|r| **r).count())
    }
}

/// Where a file's previous text is kept: its name with `.bak` added (a corrupt progress
/// file here, an exercise file before `reset` in `grade::reset`).
#[must_use]
pub fn backup_path(path: &Path) -> PathBuf {
    let mut name = path.as_os_str().to_owned();
    name.push(".bak");
    PathBuf::from(name)
}

impl Progress {
    /// The state file to use: `PPO_TUTOR_STATE` if set, else [`STATE_FILE`].
    #[must_use]
    pub fn default_path() -> PathBuf {
        std::env::var_os("PPO_TUTOR_STATE").map_or_else(|| PathBuf::from(STATE_FILE), PathBuf::from)
    }

    /// Loads progress from `path`. A missing file is a fresh start; an unreadable or
    /// corrupt one is a fresh start plus a one-line warning naming the file, and a corrupt
    /// one is first copied to `<path>.bak` (the next save would overwrite it). Answers saved
    /// under an older numbering of the questions move to the current one
    /// ([`Self::renumber_quiz`]).
    #[must_use]
    pub fn load(path: &Path) -> (Self, Option<String>) {
        let file = path.display();
        match std::fs::read_to_string(path) {
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => (Self::default(), None),
            Err(e) => (
                Self::default(),
                Some(crate::tr!(
                    "could not read {file} ({}); starting fresh",
                    "无法读取 {file}（{}）；从头开始",
                    crate::causes::message(&e)
                )),
            ),
            Ok(text) => match serde_json::from_str::<Self>(&text) {
                Ok(mut p) => {
                    p.renumber_quiz();
                    (p, None)
                }
                Err(e) => {
                    let backup = backup_path(path);
                    let kept = std::fs::write(&backup, &text).is_ok();
                    let backup = backup.display();
                    let (line, column) = (e.line(), e.column());
                    let warning = if kept {
                        crate::tr!(
                            "{file} is not valid progress (line {line}, column {column}); kept as {backup}, starting fresh",
                            "{file} 不是有效的进度文件（第 {line} 行第 {column} 列）；已另存为 {backup}，从头开始"
                        )
                    } else {
                        crate::tr!(
                            "{file} is not valid progress (line {line}, column {column}) and could not be kept; starting fresh",
                            "{file} 不是有效的进度文件（第 {line} 行第 {column} 列），也无法另存；从头开始"
                        )
                    };
                    (Self::default(), Some(warning))
                }
            },
        }
    }

    /// Forgets what the course does not know (issue 25, bug 8): lessons, quiz questions
    /// and, given `exercises` (their names), exercises that are not in it, and a saved
    /// position in a lesson that no longer exists (the first lesson opens at its first
    /// step, not at the old step number). A step past the lesson's end becomes its last.
    /// Returns how many entries were dropped.
    pub fn retain_known(&mut self, course: &Course, exercises: Option<&[&str]>) -> usize {
        let before = self.lessons_done.len() + self.quiz.len() + self.exercises_done.len();
        self.lessons_done.retain(|id| course.index_of(id).is_some());
        self.quiz.retain(|key, _| {
            key.rsplit_once('#').is_some_and(|(id, n)| {
                let questions = course
                    .index_of(id)
                    .map_or(0, |i| course.lessons[i].quiz.len());
                n.parse::<usize>()
                    .is_ok_and(|n| (1..=questions).contains(&n))
            })
        });
        if let Some(known) = exercises {
            self.exercises_done.retain(|e| known.contains(&e.as_str()));
        }
        match course.index_of(&self.lesson) {
            Some(i) => {
                let steps = course.lessons[i].steps.len();
                self.step = self.step.min(steps.saturating_sub(1));
            }
            None => {
                self.lesson = String::new();
                self.step = 0;
            }
        }
        before - (self.lessons_done.len() + self.quiz.len() + self.exercises_done.len())
    }

    /// Whether every question of lesson `id` (with `questions` questions) has an answer.
    #[must_use]
    pub fn quiz_answered(&self, id: &str, questions: usize) -> bool {
        (1..=questions).all(|n| self.quiz.contains_key(&Self::quiz_key(id, n)))
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
        let warning = warning.ok_or("no warning")?;
        assert!(warning.contains("state.json"), "{warning}");
        // Kept before anything overwrites it, and the warning says where, in one short line.
        let backup = dir.path().join("state.json.bak");
        assert_eq!(std::fs::read_to_string(&backup)?, "{not json");
        assert!(warning.contains("state.json.bak"), "{warning}");
        assert!(!warning.contains('\n'));
        Ok(())
    }

    #[test]
    fn answers_saved_before_a_renumbering_follow_their_questions()
    -> Result<(), Box<dyn std::error::Error>> {
        let dir = tempfile::tempdir()?;
        let path = dir.path().join("state.json");
        // Written before issue 25 moved lesson 1's questions 2 and 3 (no quiz_numbering), and
        // so before issue 27 replaced lesson 1's question 3 and gae's question 5.
        std::fs::write(
            &path,
            r#"{"quiz":{"what-is-ppo#1":true,"what-is-ppo#2":false,"what-is-ppo#3":true,
                "what-is-ppo#4":true,"gae#1":true,"gae#2":true,"gae#4":false,"clipping#1":true}}"#,
        )?;
        let (p, warning) = Progress::load(&path);
        assert!(warning.is_none(), "{warning:?}");
        assert_eq!(p.quiz_numbering, QUIZ_NUMBERING);
        let moved = [
            ("what-is-ppo#1", true),
            ("clipping#1", false),
            ("gae#2", true),
            ("gae#1", true),
            ("gae#3", true),
            ("clipping#2", true),
        ];
        let moved: BTreeMap<String, bool> = moved.map(|(k, r)| (k.to_string(), r)).into();
        assert_eq!(p.quiz, moved);
        // Each answer is now under the number of the question it answered.
        let course = Course::embedded_in(crate::i18n::Lang::En)?;
        let prompt = |id: &str, n: usize| {
            course
                .get(id)
                .and_then(|l| l.quiz.get(n - 1))
                .map(|q| q.prompt.clone())
                .unwrap_or_default()
        };
        for (id, n, says) in [
            ("clipping", 1, "r_t is 1.35"),
            ("clipping", 2, "grown to 1.5"),
            ("gae", 2, "λ = 0"),
            ("gae", 3, "λ = 1"),
        ] {
            assert!(prompt(id, n).contains(says), "{id}#{n}: {}", prompt(id, n));
        }
        // Saved, it is in the new numbering and is not moved again; a fresh start is too.
        p.save(&path)?;
        assert_eq!(Progress::load(&path).0, p);
        let fresh = Progress::default();
        fresh.save(&path)?;
        assert_eq!(Progress::load(&path).0.quiz_numbering, QUIZ_NUMBERING);
        Ok(())
    }

    #[test]
    fn answers_to_replaced_questions_are_forgotten() -> Result<(), Box<dyn std::error::Error>> {
        let dir = tempfile::tempdir()?;
        let path = dir.path().join("state.json");
        // Numbering 1: lesson 9's question 2 asked for approx_kl in epoch 1, since replaced
        // by a question on this run's ratio; its question 1 stays.
        std::fs::write(
            &path,
            r#"{"quiz":{"ratio#1":true,"ratio#2":true,"losses#1":false,"losses#2":true},
                "quiz_numbering":1}"#,
        )?;
        let (p, _) = Progress::load(&path);
        let kept: BTreeMap<String, bool> = [
            ("ratio#1".to_string(), true),
            ("losses#2".to_string(), true),
        ]
        .into();
        assert_eq!((p.quiz, p.quiz_numbering), (kept, QUIZ_NUMBERING));
        // Numbering 2: only the questions replaced since (section 5) are forgotten.
        std::fs::write(
            &path,
            r#"{"quiz":{"ratio#2":true,"training#1":true,"training#2":true,"training#3":false,
                "hyperparameters#4":true,"hyperparameters#5":true},"quiz_numbering":2}"#,
        )?;
        let (p, _) = Progress::load(&path);
        let kept: BTreeMap<String, bool> = [
            ("ratio#2".to_string(), true),
            ("training#1".to_string(), true),
            ("hyperparameters#5".to_string(), true),
        ]
        .into();
        assert_eq!((p.quiz, p.quiz_numbering), (kept, QUIZ_NUMBERING));
        // Every replaced question exists. Section 3's ask about the run (their prompts show
        // givens); section 5's about seeds, lesson 15's about its experiments.
        let course = Course::embedded_in(crate::i18n::Lang::En)?;
        for (id, n) in REPLACED {
            let q = course
                .get(id)
                .and_then(|l| l.quiz.get(n - 1))
                .ok_or(format!("{id}#{n}"))?;
            assert!(q.prompt.contains("{{"), "{id}#{n}: {}", q.prompt);
        }
        for (id, n) in REPLACED_3 {
            let q = course
                .get(id)
                .and_then(|l| l.quiz.get(n - 1))
                .ok_or(format!("{id}#{n}"))?;
            assert!(q.prompt.contains("five seeds"), "{id}#{n}: {}", q.prompt);
        }
        Ok(())
    }

    #[test]
    fn what_the_course_does_not_know_is_forgotten() -> Result<(), Box<dyn std::error::Error>> {
        let course = Course::embedded()?;
        let first = &course.lessons[0];
        let mut p = Progress {
            lesson: "no-such-lesson".into(),
            step: 99,
            ..Progress::default()
        };
        p.lessons_done.insert("no-such-lesson".into());
        p.lessons_done.insert(first.id.clone());
        p.exercises_done.insert("no_such_exercise".into());
        p.exercises_done.insert("n_step_target".into());
        p.record_quiz("no-such-lesson", 1, true);
        p.record_quiz(&first.id, first.quiz.len() + 1, true);
        p.record_quiz(&first.id, 1, true);
        assert_eq!(p.retain_known(&course, Some(&["n_step_target"])), 4);
        assert_eq!(p.lessons_done.len(), 1);
        assert_eq!(p.exercises_done.len(), 1);
        assert_eq!(p.quiz.len(), 1);
        // An unknown lesson opens the first lesson at its first step, not at step 99.
        assert_eq!((p.lesson.as_str(), p.step), ("", 0));
        // A known lesson past its end opens at its last step.
        p.lesson = first.id.clone();
        p.step = 99;
        p.retain_known(&course, None);
        assert_eq!(p.step, first.steps.len() - 1);
        Ok(())
    }
}
