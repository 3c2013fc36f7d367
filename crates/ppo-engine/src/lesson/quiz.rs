//! Check-your-understanding quizzes: the questions at the end of each lesson, kept as data
//! in `lessons/NN-slug/quiz.toml`, and how an answer is graded.
//!
//! A question is either **multiple choice** (one right letter, an explanation for every
//! choice) or **predict the number**: the learner commits to a number before the live value
//! is revealed, and is right within the question's tolerance. The live value is a
//! [`Measure`] of the running agent's [`Snapshot`](super::Snapshot), named in the question's
//! `predict` field and listed in [`MEASURES`].
//!
//! A question may depend on the run. Its prompt then shows numbers of the run, written
//! `{{name}}` (a measure, see [`template`]), and asks for a number that follows from them
//! by what the lesson taught (`predict` names a run measure), or asks a choice whose right
//! letter the run decides (`answer_from` names a measure whose value is the index of the
//! true choice). Both are graded against the same snapshot the prompt was filled from.
//!
//! One job per file: `measures` (the live values a question reads), `template` (the
//! `{{name}}` givens), `parse` (`quiz.toml`), `zh` (the Chinese twin `quiz.zh.toml`:
//! structure from English, words from Chinese) and `grade` (a choice, a prediction, the
//! [`Verdict`]); this file holds the types and loads a lesson's questions.
//!
//! The terminal app asks them after a lesson's last step; a notebook cell shows a question
//! with its run's numbers with [`ask`] and grades an answer in place with [`answer`],
//! [`answer_live`] or [`predict`]:
//!
//! ```
//! use ppo_engine::lesson::quiz;
//!
//! let verdict = quiz::answer("ratio", 1, '?');
//! assert!(!verdict.answered);
//! let lesson = quiz::questions("ratio")?;
//! assert!(lesson.len() >= 3);
//! # Ok::<(), ppo_engine::lesson::quiz::QuizError>(())
//! ```

mod grade;
mod measures;
mod parse;
pub mod template;
mod zh;

pub use grade::{Posed, Verdict, answer, answer_live, ask, predict};
pub use measures::{Basis, MEASURES, Measure, all as all_measures, measure};
pub use parse::{letter_index, letter_of, parse};
pub use zh::translate;

use super::files::embedded_file;
use crate::i18n::Lang;

/// One question.
#[derive(Debug, Clone, PartialEq)]
pub struct Question {
    /// The question, as the learner reads it.
    pub prompt: String,
    /// How it is answered.
    pub kind: QuestionKind,
}

/// How a question is answered and graded.
#[derive(Debug, Clone, PartialEq)]
pub enum QuestionKind {
    /// Pick one of 3 or 4 choices.
    Choice {
        /// The choices, shown as a), b), c), d).
        choices: Vec<String>,
        /// Which choice is right.
        answer: Answer,
        /// Why each choice is right or wrong, one per choice.
        explain: Vec<String>,
    },
    /// Predict a live value before it is shown.
    Predict {
        /// The measure whose live value is the answer.
        measure: &'static Measure,
        /// How far from the live value an answer may be and still be right.
        tolerance: f64,
        /// Why the value is what it is.
        explain: String,
    },
}

/// The right choice of a multiple-choice question.
#[derive(Debug, Clone, PartialEq)]
pub enum Answer {
    /// The same in every run: the index of the right choice (`answer = "b"`).
    Letter(usize),
    /// Decided by the run: the measure's value is the index of the right choice
    /// (`answer_from = "NAME"`).
    Live(&'static Measure),
}

impl Question {
    /// The question with its choices, as plain text (`a) ...` per line), its `{{name}}`
    /// givens left as they are written.
    #[must_use]
    pub fn text(&self) -> String {
        self.text_with(self.prompt.clone())
    }

    /// The question with its choices and with the givens of `snapshot` in its prompt (`…`
    /// where the run has not computed one yet).
    #[must_use]
    pub fn text_in(&self, snapshot: &super::Snapshot) -> String {
        self.text_with(self.prompt_in(snapshot))
    }

    fn text_with(&self, mut out: String) -> String {
        if let QuestionKind::Choice { choices, .. } = &self.kind {
            for (i, c) in choices.iter().enumerate() {
                out.push_str(&format!("\n  {}) {c}", letter_of(i)));
            }
        }
        out
    }

    /// The prompt with the givens of `snapshot` filled in (`…` where the run has not
    /// computed one yet).
    #[must_use]
    pub fn prompt_in(&self, snapshot: &super::Snapshot) -> String {
        template::fill(&self.prompt, snapshot)
    }

    /// Whether the question shows numbers of the run or is graded against it: it has
    /// givens, a prediction or a choice the run decides.
    #[must_use]
    pub fn uses_the_run(&self) -> bool {
        !template::names(&self.prompt).is_empty()
            || matches!(
                self.kind,
                QuestionKind::Predict { .. }
                    | QuestionKind::Choice {
                        answer: Answer::Live(_),
                        ..
                    }
            )
    }

    /// Whether `snapshot` has every number the question shows and grades against.
    #[must_use]
    pub fn ready_in(&self, snapshot: &super::Snapshot) -> bool {
        let graded = match &self.kind {
            QuestionKind::Predict { measure, .. }
            | QuestionKind::Choice {
                answer: Answer::Live(measure),
                ..
            } => (measure.value)(snapshot).is_some(),
            QuestionKind::Choice { .. } => true,
        };
        graded
            && template::names(&self.prompt)
                .iter()
                .all(|(name, _)| measure(name).and_then(|m| (m.value)(snapshot)).is_some())
    }

    /// The index of the right choice in `snapshot` (`None` for a prediction, or while the
    /// run has not decided it yet).
    #[must_use]
    pub fn right_choice(&self, snapshot: &super::Snapshot) -> Option<usize> {
        match &self.kind {
            QuestionKind::Choice {
                answer: Answer::Letter(i),
                ..
            } => Some(*i),
            QuestionKind::Choice {
                answer: Answer::Live(m),
                choices,
                ..
            } => (m.value)(snapshot)
                .filter(|v| v.fract() == 0.0 && *v >= 0.0)
                .map(|v| v as usize)
                .filter(|&i| i < choices.len()),
            QuestionKind::Predict { .. } => None,
        }
    }
}

/// A quiz file that cannot be used, naming the file, the question and the fix.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum QuizError {
    /// No lesson has this id.
    #[error("{}", crate::tr!(
        "no lesson '{0}': `ppo-tutor lessons` lists the ids (for example 'gae')",
        "没有 '{0}' 这一课：`ppo-tutor lessons` 会列出各课的 id（例如 'gae'）",
        .0
    ))]
    UnknownLesson(String),
    /// The lesson has no question with this number.
    #[error("{}", crate::tr!(
        "lesson '{lesson}' has questions 1 to {count}; there is no question {number}",
        "'{lesson}' 这一课的题号是 1 到 {count}，没有第 {number} 题",
        lesson = lesson, count = count, number = number
    ))]
    NoSuchQuestion {
        /// The lesson id.
        lesson: String,
        /// The number asked for.
        number: usize,
        /// How many there are.
        count: usize,
    },
    /// The file is not valid.
    #[error("lessons/{dir}/quiz.toml: {reason}")]
    File {
        /// The lesson folder.
        dir: String,
        /// What is wrong and how to fix it.
        reason: String,
    },
}

/// The questions of lesson `id` (e.g. `gae`), from the embedded `quiz.toml`; none when the
/// lesson has no quiz file.
///
/// # Errors
/// [`QuizError::UnknownLesson`], or [`QuizError::File`] for a malformed file.
pub fn questions(id: &str) -> Result<Vec<Question>, QuizError> {
    questions_in(id, Lang::current())
}

/// [`questions`] in `lang`: for Chinese, the prompts, choices and explanations of
/// `quiz.zh.toml`, with the answers, measures and tolerances of `quiz.toml`.
///
/// # Errors
/// As [`questions`], or [`QuizError::File`] when `quiz.zh.toml` does not match `quiz.toml`.
pub fn questions_in(id: &str, lang: Lang) -> Result<Vec<Question>, QuizError> {
    let dir = super::files::lesson_dirs()
        .into_iter()
        .find(|d| d.split_once('-').is_some_and(|(_, slug)| slug == id))
        .ok_or_else(|| QuizError::UnknownLesson(id.to_string()))?;
    let Some(text) = embedded_file(&format!("{dir}/quiz.toml")) else {
        return Ok(Vec::new());
    };
    let mut questions = parse(&dir, text)?;
    if lang == Lang::Zh
        && let Some(zh) = embedded_file(&format!("{dir}/quiz.zh.toml"))
    {
        translate(&dir, &mut questions, zh)?;
    }
    Ok(questions)
}
