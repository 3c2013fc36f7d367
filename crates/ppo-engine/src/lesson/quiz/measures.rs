//! The measures a question is graded against: each reads one live value of the running
//! agent's [`Snapshot`].
//!
//! A measure is one of three kinds ([`Basis`]):
//!
//! - a **fact** ([`facts`]): what the course teaches, the same in every run with the seed's
//!   settings (every ratio of epoch 1 is 1; the actor has 898 parameters). Two questions of
//!   the course may not ask the same fact;
//! - a **given** ([`givens`]): a number of this run that a question shows in its prompt,
//!   written `{{name}}` there (the batch's last TD error, the run's γ);
//! - a **run** measure ([`run`]): a number of this run that follows from givens by what a
//!   lesson taught (Â from the last three δ and γλ). Its question shows those givens, and
//!   the learner computes the answer from them.
//!
//! A measure is a number, or the index of the true one of a question's choices
//! ([`Measure::choices`]), for a multiple-choice question whose right answer depends on the
//! run (`answer_from` in `quiz.toml`).

mod facts;
mod givens;
mod run;

use super::super::Snapshot;
use crate::i18n::Text;
use crate::lesson::live::Batch;

/// A number a prediction is graded against, measured on the running agent.
#[derive(Debug)]
pub struct Measure {
    /// The name a question's `predict`, `answer_from` or `{{…}}` uses.
    pub name: &'static str,
    /// What it is, in words, in both languages (shown with the revealed value).
    pub about: Text,
    /// Its value in a snapshot, `None` before anything computed it.
    pub value: fn(&Snapshot) -> Option<f64>,
    /// 0 for a number; `n` for the index (0 to `n − 1`) of the true one of a question's `n`
    /// choices.
    pub choices: usize,
    /// What the value rests on.
    pub basis: Basis,
}

/// What a measure's value rests on: a fact of the course, or this run.
#[derive(Debug, Clone, Copy)]
pub enum Basis {
    /// The same in every run with the seed's settings; the fact, in a few words (no two
    /// questions of the course ask the same one).
    Fact(&'static str),
    /// A number of this run that a question shows (`{{name}}` in its prompt).
    Given,
    /// A number of this run that follows from the givens `given` (shown in the question's
    /// prompt) by `from`, what the lesson taught: the value of [`Measure::value`] is the
    /// agent's own, and `from` is how the learner gets it from the shown numbers.
    Run {
        /// The givens the question shows, in the order `from` takes them.
        given: &'static [&'static str],
        /// The answer from the givens' values.
        from: fn(&[f64]) -> f64,
    },
}

impl Measure {
    /// What it is, in words, in the current language.
    #[must_use]
    pub fn describe(&self) -> &str {
        self.about.get()
    }

    /// Whether its value depends on the run: it follows from numbers of the run the
    /// question shows ([`Basis::Run`]). A test checks that it differs between runs.
    #[must_use]
    pub fn depends_on_run(&self) -> bool {
        matches!(self.basis, Basis::Run { .. })
    }

    /// The givens its question must show (none for a fact or a given).
    #[must_use]
    pub fn given(&self) -> &'static [&'static str] {
        match self.basis {
            Basis::Run { given, .. } => given,
            _ => &[],
        }
    }
}

impl PartialEq for Measure {
    fn eq(&self, other: &Self) -> bool {
        self.name == other.name
    }
}

/// Every measure, by kind: facts, givens, run measures.
pub static MEASURES: [&[Measure]; 3] = [facts::FACTS, givens::GIVENS, run::RUN];

/// Every measure, in [`MEASURES`]' order.
pub fn all() -> impl Iterator<Item = &'static Measure> {
    MEASURES.iter().flat_map(|kind| kind.iter())
}

/// The measure called `name`.
#[must_use]
pub fn measure(name: &str) -> Option<&'static Measure> {
    all().find(|m| m.name == name)
}

/// The hyper-parameter `name` of the run, as a number.
fn hyper(s: &Snapshot, name: &str) -> Option<f64> {
    s.hyper
        .iter()
        .find(|(n, _)| n == name)
        .and_then(|(_, v)| v.parse().ok())
}

/// Whether the run's setting `name` reads `value`.
fn setting_is(s: &Snapshot, name: &str, value: &str) -> bool {
    s.hyper.iter().any(|(n, v)| n == name && v == value)
}

/// GAE's λ as the update uses it: the run's `lmbda`, or 1 for REINFORCE.
fn lambda(s: &Snapshot) -> Option<f64> {
    if setting_is(s, "algorithm", "reinforce") {
        return Some(1.0);
    }
    hyper(s, "lmbda")
}

/// Whether the actor minimises the seed's clipped surrogate (not REINFORCE, no `no_clip`,
/// no other objective).
fn clipped_objective(s: &Snapshot) -> bool {
    !setting_is(s, "algorithm", "reinforce")
        && !setting_is(s, "no_clip", "true")
        && s.hyper
            .iter()
            .all(|(n, v)| n != "objective" || v.as_str() == "clip")
}

fn batch(s: &Snapshot) -> Option<Batch<'_>> {
    s.batch()
}

/// `xs[i]` as f64.
fn at(xs: &[f32], i: usize) -> Option<f64> {
    xs.get(i).map(|&x| f64::from(x))
}

/// `xs[len − k]` as f64 (`k = 1` is the last).
fn from_end(xs: &[f32], k: usize) -> Option<f64> {
    at(xs, xs.len().checked_sub(k)?)
}

/// The row with the largest (`largest`) or smallest ratio in the update's last epoch.
fn extreme_row(s: &Snapshot, largest: bool) -> Option<usize> {
    let b = batch(s)?;
    let ratio = b.epochs.last()?.ratio;
    let better = |a: f32, b: f32| if largest { a > b } else { a < b };
    (0..ratio.len()).reduce(|best, i| {
        if better(ratio[i], ratio[best]) {
            i
        } else {
            best
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_unique_and_run_measures_name_known_givens() {
        let mut names: Vec<&str> = all().map(|m| m.name).collect();
        let count = names.len();
        names.sort_unstable();
        names.dedup();
        assert_eq!(names.len(), count, "a measure name is used twice");
        for m in all() {
            for g in m.given() {
                assert!(
                    measure(g).is_some(),
                    "{}: given {g} is not a measure",
                    m.name
                );
                assert_ne!(*g, m.name, "{} is its own given", m.name);
            }
            assert_eq!(
                m.depends_on_run(),
                !m.given().is_empty(),
                "{}: a run measure follows from givens",
                m.name
            );
        }
    }
}
