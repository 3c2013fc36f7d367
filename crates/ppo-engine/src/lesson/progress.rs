//! Where the learner is and what is done, saved atomically between runs.
//!
//! The state file is small JSON (`.ppo-tutor-state.json` in the working directory, or
//! the path in `PPO_TUTOR_STATE`). It is written to a temporary file and renamed, so a
//! crash never leaves half a file ([`crate::files::write_atomically`]: the temporary file
//! goes on every failure); a file that cannot be understood (not JSON, not UTF-8 text) is
//! kept as `<path>.bak` and yields a warning and a fresh start. A save that fails says the
//! file, the cause and the fix ([`SaveError`]).

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use super::Course;
use crate::i18n::Lang;

/// The default state file name (in the working directory).
pub const STATE_FILE: &str = ".ppo-tutor-state.json";

/// The numbering of quiz questions that [`Progress::quiz`] keys follow now. A progress file
/// written before a numbering existed (with no `quiz_numbering`) is 0, and loading it moves
/// its answers by [`RENUMBERED`]; one written before numbering 2 forgets its answers to the
/// questions in [`REPLACED`], and one written before numbering 3 those in [`REPLACED_3`].
pub const QUIZ_NUMBERING: u32 = 3;

/// The version of the exercises' tasks that [`Progress::exercises_done`] follows now. A file
/// written before (with no `exercise_tasks`) is 0, and loading it forgets its passes of the
/// exercises in [`RETASKED_1`].
pub const EXERCISE_TASKS: u32 = 1;

/// Exercises whose task changed at version 1 under the same name: each now applies its
/// lesson's idea to a situation the lesson does not show (masked logits, the dual clip, an
/// autoreset stream's final observation). A pass saved before was a pass of the old task,
/// and is forgotten.
pub const RETASKED_1: &[&str] = &[
    "categorical_kl",
    "zero_gradient_rows",
    "td_target_truncation",
];

/// A quiz question by lesson id and number (from 1), as in [`Progress::quiz_key`].
pub type QuestionAt = (&'static str, usize);

/// How questions moved from numbering 0 to 1: `(lesson, number)` before,
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

/// Questions replaced in place at numbering 2: the fixed-fact
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

/// Questions replaced in place at numbering 3: the hyper-parameter
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
    /// The interface language chosen last in the app, as its code (`en`, `zh`); `None` in a
    /// file written before the choice was kept, or when none was made. Read it with
    /// [`Self::language`] (an unknown code is no choice), set it with
    /// [`Self::set_language`].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub lang: Option<String>,
    /// The latest answer to each question, by the same key as [`Self::quiz`]: the chosen
    /// choice's text (not its letter, which a reordering would change) or the predicted
    /// number, so that a question seen again shows it. Empty in older files.
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub answers: BTreeMap<String, String>,
    /// The predictions made before lab experiments, by experiment name (`eps`): the chosen
    /// setting's label, or "" where the learner ran it without one. A step that asks for a
    /// prediction shows what the run found once this holds its experiment. Empty in older
    /// files.
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub predictions: BTreeMap<String, String>,
    /// The version of the exercises' tasks [`Self::exercises_done`] follows:
    /// [`EXERCISE_TASKS`], or 0 in a file written before it existed.
    #[serde(default)]
    pub exercise_tasks: u32,
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
            lang: None,
            answers: BTreeMap::new(),
            predictions: BTreeMap::new(),
            exercise_tasks: EXERCISE_TASKS,
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

    /// Keeps `answer` as the latest answer to a question (the choice's text, or the number
    /// predicted), shown when the question is seen again.
    pub fn record_answer(&mut self, lesson: &str, number: usize, answer: &str) {
        self.answers
            .insert(Self::quiz_key(lesson, number), answer.to_string());
    }

    /// The latest answer to question `number` of lesson `lesson`, if one was kept.
    #[must_use]
    pub fn answer(&self, lesson: &str, number: usize) -> Option<&str> {
        self.answers
            .get(&Self::quiz_key(lesson, number))
            .map(String::as_str)
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
        let quiz = &self.quiz;
        self.answers.retain(|key, _| quiz.contains_key(key));
        self.quiz_numbering = QUIZ_NUMBERING;
    }

    /// Forgets passes of exercises whose task changed since the file was written
    /// ([`RETASKED_1`]).
    pub fn forget_retasked(&mut self) {
        if self.exercise_tasks < 1 {
            self.exercises_done
                .retain(|e| !RETASKED_1.contains(&e.as_str()));
        }
        self.exercise_tasks = EXERCISE_TASKS;
    }

    /// The interface language saved with the progress, if one was chosen (and is one this
    /// build knows).
    #[must_use]
    pub fn language(&self) -> Option<Lang> {
        self.lang.as_deref().and_then(Lang::from_code)
    }

    /// Keeps `lang` as the interface language, written with the next [`Self::save`].
    pub fn set_language(&mut self, lang: Lang) {
        self.lang = Some(lang.code().to_string());
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
    /// corrupt one is a fresh start plus a one-line warning naming the file, and a file that
    /// was read but cannot be understood (not UTF-8 text, not JSON, not progress) is first
    /// copied to `<path>.bak` (the next save would overwrite it). Answers saved under an
    /// older numbering of the questions move to the current one ([`Self::renumber_quiz`]).
    #[must_use]
    pub fn load(path: &Path) -> (Self, Option<String>) {
        let file = path.display();
        let bytes = match std::fs::read(path) {
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => return (Self::default(), None),
            Err(e) => {
                let warning = crate::tr!(
                    "could not read {file} ({}); starting fresh",
                    "无法读取 {file}（{}）；从头开始",
                    crate::causes::message(&e)
                );
                return (Self::default(), Some(warning));
            }
            Ok(bytes) => bytes,
        };
        let parsed = std::str::from_utf8(&bytes)
            .map_err(|_| crate::i18n::t("not UTF-8 text", "不是 UTF-8 文本").to_string())
            .and_then(|text| {
                serde_json::from_str::<Self>(text).map_err(|e| {
                    let (line, column) = (e.line(), e.column());
                    crate::tr!("line {line}, column {column}", "第 {line} 行第 {column} 列")
                })
            });
        match parsed {
            Ok(mut p) => {
                p.renumber_quiz();
                p.forget_retasked();
                (p, None)
            }
            Err(why) => {
                let backup = backup_path(path);
                let kept = crate::files::write_atomically(&backup, &bytes).is_ok();
                let backup = backup.display();
                let warning = if kept {
                    crate::tr!(
                        "{file} is not valid progress ({why}); kept as {backup}, starting fresh",
                        "{file} 不是有效的进度文件（{why}）；已另存为 {backup}，从头开始"
                    )
                } else {
                    crate::tr!(
                        "{file} is not valid progress ({why}) and could not be kept; starting fresh",
                        "{file} 不是有效的进度文件（{why}），也无法另存；从头开始"
                    )
                };
                (Self::default(), Some(warning))
            }
        }
    }

    /// Forgets what the course does not know: lessons, quiz questions
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
        let quiz = &self.quiz;
        self.answers.retain(|key, _| quiz.contains_key(key));
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

    /// Saves to `path` atomically (write a sibling temporary file, then rename it; the
    /// temporary file is removed on any failure).
    ///
    /// # Errors
    /// [`SaveError`]: the folder is missing or not writable, or `path` is a folder; its
    /// message names the file, the cause and the fix.
    pub fn save(&self, path: &Path) -> Result<(), SaveError> {
        let json = serde_json::to_string_pretty(self).map_err(std::io::Error::other);
        json.and_then(|json| crate::files::write_atomically(path, json.as_bytes()))
            .map_err(|source| SaveError::new(path, source))
    }
}

/// The progress file could not be saved: which file, why (the file system's error) and
/// what to do, in the current language when shown.
#[derive(Debug)]
pub struct SaveError {
    /// The progress file.
    pub path: PathBuf,
    /// What the file system said.
    pub source: std::io::Error,
    /// What stood in the way, for the fix.
    obstacle: Obstacle,
}

/// What kept a progress file from being saved.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Obstacle {
    /// The path is a folder.
    Folder,
    /// The folder does not exist.
    NoFolder,
    /// The folder (or the file) may not be written.
    ReadOnly,
    /// Anything else (a full disk, say).
    Other,
}

impl SaveError {
    fn new(path: &Path, source: std::io::Error) -> Self {
        use std::io::ErrorKind;
        let obstacle = if path.is_dir() {
            Obstacle::Folder
        } else {
            match source.kind() {
                ErrorKind::NotFound => Obstacle::NoFolder,
                ErrorKind::PermissionDenied | ErrorKind::ReadOnlyFilesystem => Obstacle::ReadOnly,
                _ => Obstacle::Other,
            }
        };
        Self {
            path: path.to_path_buf(),
            source,
            obstacle,
        }
    }

    /// The folder the file is in (`.` for a bare name).
    fn folder(&self) -> PathBuf {
        match self.path.parent() {
            Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
            _ => PathBuf::from("."),
        }
    }
}

impl std::fmt::Display for SaveError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let file = self.path.display();
        let cause = crate::causes::message(&self.source);
        let folder = self.folder();
        let folder = folder.display();
        let fix = match self.obstacle {
            Obstacle::Folder => crate::tr!(
                "it is a folder: move it away, or set PPO_TUTOR_STATE to a file path",
                "它是一个文件夹：请把它移走，或把 PPO_TUTOR_STATE 设为一个文件路径"
            ),
            Obstacle::NoFolder => crate::tr!(
                "create the folder {folder}, or set PPO_TUTOR_STATE to a file in a folder that exists",
                "请创建文件夹 {folder}，或把 PPO_TUTOR_STATE 设为某个已有文件夹中的文件"
            ),
            Obstacle::ReadOnly => crate::tr!(
                "make {folder} writable, or set PPO_TUTOR_STATE to a file in a folder you can write",
                "请让 {folder} 可写，或把 PPO_TUTOR_STATE 设为某个可写文件夹中的文件"
            ),
            Obstacle::Other => crate::tr!(
                "free some space, or set PPO_TUTOR_STATE to a file in another folder",
                "请腾出磁盘空间，或把 PPO_TUTOR_STATE 设为其他文件夹中的文件"
            ),
        };
        write!(
            f,
            "{}",
            crate::tr!(
                "could not save progress to {file} ({cause}); {fix}",
                "无法把进度保存到 {file}（{cause}）；{fix}"
            )
        )
    }
}

/// The message says the cause (the file system's error) itself, so it has no `source`: a
/// chain printed below it would say it twice.
impl std::error::Error for SaveError {}

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

    /// A file that is not UTF-8 text is kept as `.bak` too (it used to be read as a text
    /// file that could not be read, and overwritten by the next save).
    #[test]
    fn binary_garbage_is_kept_before_a_fresh_start() -> Result<(), Box<dyn std::error::Error>> {
        let dir = tempfile::tempdir()?;
        let path = dir.path().join("state.json");
        let garbage = [0xff_u8, 0xfe, 0x00, 0x9c, b'{', 0xc3];
        std::fs::write(&path, garbage)?;
        for lang in Lang::ALL {
            let _lang = lang.scoped();
            let (after, warning) = Progress::load(&path);
            assert_eq!(after, Progress::default());
            let warning = warning.ok_or("no warning")?;
            let backup = dir.path().join("state.json.bak");
            assert_eq!(std::fs::read(&backup)?, garbage);
            assert!(warning.contains("state.json.bak"), "{warning}");
            let why = lang.pick("not UTF-8 text", "不是 UTF-8 文本");
            assert!(warning.contains(why), "{warning}");
        }
        Ok(())
    }

    /// A progress path that cannot be replaced (a folder) fails with the file, the cause
    /// and the fix, in both languages, and leaves no temporary file behind.
    #[test]
    fn a_failed_save_says_why_and_leaves_nothing() -> Result<(), Box<dyn std::error::Error>> {
        let dir = tempfile::tempdir()?;
        let path = dir.path().join("state.json");
        std::fs::create_dir(&path)?;
        let err = Progress::default().save(&path).err().ok_or("saved")?;
        assert_eq!(err.path, path);
        for (lang, says) in [
            (
                Lang::En,
                [
                    "could not save progress to",
                    "is a folder",
                    "PPO_TUTOR_STATE",
                ],
            ),
            (
                Lang::Zh,
                ["无法把进度保存到", "是一个文件夹", "PPO_TUTOR_STATE"],
            ),
        ] {
            let _lang = lang.scoped();
            let text = err.to_string();
            assert!(text.contains(&path.display().to_string()), "{text}");
            for word in says {
                assert!(text.contains(word), "{lang:?}: {text}");
            }
        }
        let left: Vec<_> = std::fs::read_dir(dir.path())?.collect::<Result<_, _>>()?;
        assert_eq!(left.len(), 1, "{left:?}");
        // A missing folder: the fix says to create it.
        let missing = dir.path().join("no/such/state.json");
        let err = Progress::default().save(&missing).err().ok_or("saved")?;
        let _en = Lang::En.scoped();
        assert!(err.to_string().contains("create the folder"), "{err}");
        Ok(())
    }

    /// A read-only folder: the save fails, says to make it writable, and leaves nothing.
    /// (Root writes anywhere: there the save succeeds and there is nothing to check.)
    #[cfg(unix)]
    #[test]
    fn a_read_only_folder_is_named_in_the_fix() -> Result<(), Box<dyn std::error::Error>> {
        use std::os::unix::fs::PermissionsExt as _;
        let dir = tempfile::tempdir()?;
        let folder = dir.path().join("ro");
        std::fs::create_dir(&folder)?;
        std::fs::set_permissions(&folder, std::fs::Permissions::from_mode(0o555))?;
        let path = folder.join("state.json");
        let saved = Progress::default().save(&path);
        let left = std::fs::read_dir(&folder)?.count();
        std::fs::set_permissions(&folder, std::fs::Permissions::from_mode(0o755))?;
        if let Err(err) = saved {
            let _en = Lang::En.scoped();
            assert!(err.to_string().contains("writable"), "{err}");
            assert_eq!(left, 0);
        }
        Ok(())
    }

    /// The language chosen in the app is kept; a file written before it was (no `lang`)
    /// reads as no choice, and so does an unknown code.
    #[test]
    fn the_language_is_kept_and_old_files_read() -> Result<(), Box<dyn std::error::Error>> {
        let dir = tempfile::tempdir()?;
        let path = dir.path().join("state.json");
        std::fs::write(&path, r#"{"lesson":"gae","step":1,"quiz_numbering":3}"#)?;
        let (mut p, warning) = Progress::load(&path);
        assert!(warning.is_none(), "{warning:?}");
        assert_eq!((p.lesson.as_str(), p.language()), ("gae", None));
        p.save(&path)?;
        assert!(!std::fs::read_to_string(&path)?.contains("lang"));
        p.set_language(Lang::Zh);
        p.save(&path)?;
        assert!(std::fs::read_to_string(&path)?.contains(r#""lang": "zh""#));
        assert_eq!(Progress::load(&path).0.language(), Some(Lang::Zh));
        std::fs::write(&path, r#"{"lang":"fr","lesson":"gae"}"#)?;
        let (p, warning) = Progress::load(&path);
        assert!(warning.is_none(), "{warning:?}");
        assert_eq!((p.lesson.as_str(), p.language()), ("gae", None));
        Ok(())
    }

    #[test]
    fn answers_saved_before_a_renumbering_follow_their_questions()
    -> Result<(), Box<dyn std::error::Error>> {
        let dir = tempfile::tempdir()?;
        let path = dir.path().join("state.json");
        // Written before lesson 1's questions 2 and 3 moved (no quiz_numbering), and so
        // before lesson 1's question 3 and gae's question 5 were replaced.
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
    fn passes_of_retasked_exercises_are_forgotten_once() -> Result<(), Box<dyn std::error::Error>> {
        let dir = tempfile::tempdir()?;
        let path = dir.path().join("state.json");
        // Written before the tasks' version: the retasked passes go, the others stay.
        std::fs::write(
            &path,
            r#"{"exercises_done":["categorical_kl","n_step_target","zero_gradient_rows"],
                "predictions":{"eps":"b","epochs":""}}"#,
        )?;
        let (p, _) = Progress::load(&path);
        assert_eq!(
            p.exercises_done
                .iter()
                .map(String::as_str)
                .collect::<Vec<_>>(),
            ["n_step_target"]
        );
        assert_eq!(p.exercise_tasks, EXERCISE_TASKS);
        assert_eq!(p.predictions.get("eps").map(String::as_str), Some("b"));
        // A pass of the new task, saved, is kept.
        let mut p = p;
        p.exercises_done.insert("categorical_kl".into());
        p.save(&path)?;
        assert!(
            Progress::load(&path)
                .0
                .exercises_done
                .contains("categorical_kl")
        );
        for name in RETASKED_1 {
            assert!(
                crate::lesson::Course::embedded()?.lessons.iter().any(|l| l
                    .exercise
                    .as_ref()
                    .is_some_and(|e| e.names().contains(name))),
                "{name} is no exercise of the course"
            );
        }
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

    /// The latest answer to a question is kept with the progress (as text), read back, and
    /// forgotten with its question; a file without answers reads as before.
    #[test]
    fn the_latest_answer_is_kept() -> Result<(), Box<dyn std::error::Error>> {
        let dir = tempfile::tempdir()?;
        let path = dir.path().join("state.json");
        let mut p = Progress::default();
        p.record_quiz("gae", 2, false);
        p.record_answer("gae", 2, "0.5");
        p.record_answer("gae", 2, "0.75");
        p.save(&path)?;
        let back = Progress::load(&path).0;
        assert_eq!(back.answer("gae", 2), Some("0.75"));
        assert_eq!(back.answer("gae", 3), None);
        std::fs::write(&path, r#"{"lesson":"gae","quiz":{"gae#2":true}}"#)?;
        let old = Progress::load(&path).0;
        assert!(old.answers.is_empty() && old.quiz.len() == 1);
        let course = Course::embedded()?;
        let mut unknown = back;
        unknown.record_quiz("no-such-lesson", 1, true);
        unknown.record_answer("no-such-lesson", 1, "a");
        unknown.retain_known(&course, None);
        assert_eq!(unknown.answer("no-such-lesson", 1), None);
        assert_eq!(unknown.answer("gae", 2), Some("0.75"));
        Ok(())
    }
}
