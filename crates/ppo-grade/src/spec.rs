//! The typed side of an exercise: [`Spec`], what each exercise module implements (the
//! questions it asks, the reference and the catalogue of typical mistakes that answer
//! them, how answers are compared), and the data the pipeline passes around.

use std::time::Duration;

use super::build::{Backend, Source};
use super::error::GradeError;
use super::learner::Learner;
use super::prose::Hints;
use super::report::CheckReport;
use crate::i18n::Text;

/// Where an exercise lives and how its learner's file is built.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Meta {
    /// The function's name (also the name on the command line).
    pub name: &'static str,
    /// The lesson folder under `lessons/`, e.g. `07-td-target`.
    pub lesson: &'static str,
    /// The starter's file name in the lesson folder.
    pub starter: &'static str,
    /// The reference solution's file name in the lesson folder.
    pub solution: &'static str,
    /// How the learner's file is built: plain `rustc`, or cargo against candle.
    pub backend: Backend,
}

impl Meta {
    /// A plain-Rust exercise whose starter is `exercise.rs` and solution `solution.rs`.
    #[must_use]
    pub const fn plain(name: &'static str, lesson: &'static str) -> Self {
        Self {
            name,
            lesson,
            starter: "exercise.rs",
            solution: "solution.rs",
            backend: Backend::Rustc,
        }
    }
}

/// How a learner's value differs from the reference's.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Difference {
    /// The part that differs (what a mistake concerns).
    pub part: usize,
    /// The reference's result, shown.
    pub expected: Text,
    /// The learner's result, shown.
    pub got: Text,
    /// Where they first differ (empty when that says nothing more).
    pub detail: Text,
    /// The prose key of the hint when no known mistake explains it (`fallback`, or a key of
    /// the exercise's `other` table).
    pub fallback: &'static str,
}

/// A named group of cases: one line of the report.
#[derive(Debug, Clone, PartialEq)]
pub struct Check<K> {
    /// What the cases test, e.g. `every step done`, in both languages.
    pub name: Text,
    /// What the check compares.
    pub kind: K,
    /// The cases, as indices into the exercise's case list.
    pub cases: Vec<usize>,
}

/// An exercise's cases and the report lines over them.
#[derive(Debug, Clone)]
pub struct Cases<C, K> {
    /// Every case, in the order they are asked.
    pub all: Vec<C>,
    /// The checks, in report order.
    pub checks: Vec<Check<K>>,
}

/// The typed description of one exercise: the questions it asks, the reference and the
/// catalogue of typical mistakes that answer them, and how answers are compared.
pub trait Spec: Sync + Send + 'static {
    /// One case, with whatever the comparison needs beside the question.
    type Case;
    /// What the learner's function is given.
    type Question: Clone + Send + 'static;
    /// What the learner's function gives back.
    type Reply: Clone + Send + 'static;
    /// What the judge compares (the reply, or what follows from it).
    type Value;
    /// What a check compares.
    type Kind: Copy;

    /// Name, lesson, files and backend.
    fn meta(&self) -> Meta;
    /// `pub fn name(...) -> R`.
    fn signature(&self) -> String;
    /// The program around the learner's file for its backend.
    fn program(&self) -> Source;
    /// Every case and check (deterministic: seeded).
    ///
    /// # Errors
    /// [`GradeError::Fixture`] if an embedded fixture cannot be replayed.
    fn cases(&self) -> Result<Cases<Self::Case, Self::Kind>, GradeError>;
    /// The question of `case`.
    fn question<'a>(&self, case: &'a Self::Case) -> &'a Self::Question;
    /// The reference's reply.
    fn reference(&self, case: &Self::Case) -> Option<Self::Reply>;
    /// The typical mistakes, in the order they are tried: `(id, part)`.
    fn mistakes(&self) -> Vec<(&'static str, usize)>;
    /// Mistake number `index`'s reply.
    fn mistake(&self, index: usize, case: &Self::Case) -> Option<Self::Reply>;
    /// What is compared of `reply` on `case`, or why it cannot be.
    ///
    /// # Errors
    /// A sentence for the report when the reply cannot be judged.
    fn value(&self, case: &Self::Case, reply: Self::Reply) -> Result<Self::Value, Text>;
    /// Whether `got` agrees with `want` in `part` (what a mistake concerns).
    fn agrees(&self, got: &Self::Value, want: &Self::Value, part: usize) -> bool;
    /// How `got` differs from `want` for a check of `kind`, if it does.
    fn differs(
        &self,
        kind: Self::Kind,
        got: &Self::Value,
        want: &Self::Value,
    ) -> Option<Difference>;
    /// The case's input, for a failure: `(parameter, value)` pairs (a parameter's name is
    /// code, the same in both languages, unless it names a setting).
    fn show_input(&self, case: &Self::Case) -> Vec<(Text, Text)>;
    /// A question as one line to the learner's program.
    fn encode(&self, question: &Self::Question) -> String;
    /// The learner's program's reply to `question` (the text after `ok `).
    fn decode(&self, question: &Self::Question, payload: &str) -> Option<Self::Reply>;
    /// Whether the time limit holds for each question (else for all of them together).
    fn limit_per_question(&self) -> bool {
        false
    }
    /// The names of the checks run after the judged ones (1 case each).
    fn follow_up_names(&self) -> Vec<Text> {
        Vec::new()
    }
    /// Checks run after the judged ones (`earlier`, their report lines), with the learner
    /// still answering.
    fn follow_up(
        &self,
        _learner: &mut dyn Learner<Self::Question, Self::Reply>,
        _limit: Duration,
        _diagnosis: Option<&'static str>,
        _prose: Hints,
        _earlier: &[CheckReport],
    ) -> Vec<CheckReport> {
        Vec::new()
    }
}
