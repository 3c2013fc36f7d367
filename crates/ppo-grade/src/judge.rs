//! The one judge: compares the learner's answers with the reference's, finds the first
//! failing case of each check, and names the likely mistake from the exercise's catalogue.
//!
//! A diagnosis is made per *part* (what a mistake concerns: the whole result of a plain
//! exercise; the actor or the critic loss of the candle one). A known mistake of a part
//! *explains* the learner when it accounts for the learner's wrong answers: of the cases
//! where the learner or the mistake is wrong, the mistake gives the learner's very answer
//! on at least half. So a variant that is wrong almost everywhere does not explain a
//! learner who is wrong on one edge case, nor one that coincides with the learner on a
//! few inputs, while a learner who makes the mistake with a slip of their own beside it is
//! still told it. Among the mistakes that explain the learner, the one with the largest
//! share wins (the first listed wins a tie). Its hint, from the lesson's `exercise.toml`,
//! goes with every failure in that part; when no mistake explains the learner, the failure
//! gets the exercise's own hint (`fallback`), which states the idea rather than name a
//! mistake the learner did not make.

use super::hints;
use super::learner::Answer;
use super::prose::Hints;
use super::report::{CheckReport, CheckStatus, Failure, Printed, Problem};
use super::spec::{Check, Spec};
use crate::i18n::Text;

/// The learner's, the reference's and the diagnosed mistakes' values on every case.
pub struct Judge<'a, S: Spec> {
    spec: &'a S,
    prose: Hints,
    cases: &'a [S::Case],
    answers: Vec<Answer<S::Reply>>,
    learner: Vec<Option<Result<S::Value, Text>>>,
    reference: Vec<Option<S::Value>>,
    /// The diagnosed mistake's id, per part.
    diagnosis: Vec<Option<&'static str>>,
}

impl<'a, S: Spec> Judge<'a, S> {
    /// Judges `answers`, one per case of `cases`.
    pub fn new(
        spec: &'a S,
        prose: Hints,
        cases: &'a [S::Case],
        answers: Vec<Answer<S::Reply>>,
    ) -> Self {
        let reference = cases
            .iter()
            .map(|c| spec.value(c, spec.reference(c)?).ok())
            .collect();
        let learner = answers
            .iter()
            .zip(cases)
            .map(|(a, c)| match a {
                Answer::Value(reply) => Some(spec.value(c, reply.clone())),
                _ => None,
            })
            .collect();
        let parts = spec
            .mistakes()
            .iter()
            .map(|(_, p)| p + 1)
            .max()
            .unwrap_or(1);
        let mut judge = Self {
            spec,
            prose,
            cases,
            answers,
            learner,
            reference,
            diagnosis: Vec::new(),
        };
        judge.diagnosis = (0..parts).map(|part| judge.diagnose(part)).collect();
        judge
    }

    fn learner_value(&self, i: usize) -> Option<&S::Value> {
        self.learner.get(i)?.as_ref()?.as_ref().ok()
    }

    /// The known mistake in `part` that best explains the learner's values (see the
    /// module's documentation for the rule).
    fn diagnose(&self, part: usize) -> Option<&'static str> {
        let wrong: Vec<bool> = (0..self.cases.len())
            .map(|i| match (self.learner_value(i), &self.reference[i]) {
                (Some(l), Some(r)) => !self.spec.agrees(l, r, part),
                _ => false,
            })
            .collect();
        let learner_wrong = wrong.iter().filter(|w| **w).count();
        if learner_wrong == 0 {
            return None;
        }
        // The best mistake so far, with its share as (reproduced, of).
        let mut best: Option<(&'static str, usize, usize)> = None;
        for (index, (id, p)) in self.spec.mistakes().into_iter().enumerate() {
            if p != part {
                continue;
            }
            let mut reproduced = 0;
            let mut mistake_wrong = 0;
            for (i, case) in self.cases.iter().enumerate() {
                let theirs = self
                    .spec
                    .mistake(index, case)
                    .and_then(|r| self.spec.value(case, r).ok());
                let Some(theirs) = theirs else { continue };
                if self.reference[i]
                    .as_ref()
                    .is_some_and(|r| !self.spec.agrees(&theirs, r, part))
                {
                    mistake_wrong += 1;
                }
                if self
                    .learner_value(i)
                    .is_some_and(|l| self.spec.agrees(l, &theirs, part))
                {
                    reproduced += usize::from(wrong[i]);
                }
            }
            // The cases where either is wrong (a reproduced case is wrong for both, but for
            // answers that agree within the tolerance on one side only).
            let either = (learner_wrong + mistake_wrong)
                .saturating_sub(reproduced)
                .max(reproduced);
            let explains = reproduced > 0 && 2 * reproduced >= either;
            if explains && best.is_none_or(|(_, r, e)| reproduced * e > r * either) {
                best = Some((id, reproduced, either));
            }
        }
        best.map(|(id, _, _)| id)
    }

    /// The diagnosed mistake of `part`, if one explains the learner.
    #[must_use]
    pub fn diagnosis(&self, part: usize) -> Option<&'static str> {
        self.diagnosis.get(part).copied().flatten()
    }

    /// The first diagnosed mistake, in part order.
    pub fn any_diagnosis(&self) -> Option<&'static str> {
        self.diagnosis.iter().flatten().next().copied()
    }

    /// The hint for a wrong `part`: its diagnosed mistake's, else the prose at `fallback`.
    fn hint(&self, part: usize, fallback: &str) -> Text {
        match self.diagnosis.get(part).copied().flatten() {
            Some(id) => self.prose.mistake(id),
            None => self.prose.text(fallback),
        }
    }

    /// The report line of `check`: passed, or its first failing case; with what the
    /// learner printed (`printed`, one per case) on the failing case, else on the first
    /// case that printed.
    pub fn report_line(&self, check: &Check<S::Kind>, printed: &[Printed]) -> CheckReport {
        let (status, failing) = self.status(check);
        let of = |i: usize| printed.get(i).cloned().unwrap_or_default();
        let printed = match (&status, failing) {
            (CheckStatus::Failed(_), Some(i)) => of(i),
            (CheckStatus::Passed, _) => {
                let mut printing = check.cases.iter().filter(|&&i| !of(i).is_empty());
                printing.next().map_or_else(Printed::default, |&i| Printed {
                    other_cases: printing.count(),
                    ..of(i)
                })
            }
            _ => Printed::default(),
        };
        CheckReport {
            name: check.name.clone(),
            cases: check.cases.len(),
            status,
            printed,
        }
    }

    /// The status of `check`, and the case it failed on.
    fn status(&self, check: &Check<S::Kind>) -> (CheckStatus, Option<usize>) {
        for &i in &check.cases {
            let (problem, expected, got, detail, hint) = match &self.answers[i] {
                Answer::Value(_) => match (&self.learner[i], &self.reference[i]) {
                    (Some(Ok(l)), Some(r)) => {
                        let Some(d) = self.spec.differs(check.kind, l, r) else {
                            continue;
                        };
                        let hint = self.hint(d.part, d.fallback);
                        (Problem::Wrong, d.expected, d.got, d.detail, hint)
                    }
                    (Some(Err(why)), _) => (
                        Problem::Crashed(why.clone()),
                        Text::default(),
                        Text::default(),
                        Text::default(),
                        self.prose.text("fallback"),
                    ),
                    _ => (
                        Problem::Crashed(Text::new(
                            "the reference could not be computed",
                            "参考答案无法计算",
                        )),
                        Text::default(),
                        Text::default(),
                        Text::default(),
                        self.prose.text("fallback"),
                    ),
                },
                Answer::NotRun => {
                    let why = Text::new(
                        "an earlier case stopped the program",
                        "前面的用例让程序停止了",
                    );
                    return (CheckStatus::NotRun(why), None);
                }
                other => {
                    let (problem, hint) = self.problem(other);
                    (
                        problem,
                        Text::default(),
                        Text::default(),
                        Text::default(),
                        hint,
                    )
                }
            };
            let failure = Failure {
                problem,
                input: self.spec.show_input(&self.cases[i]),
                expected,
                got,
                detail,
                hint,
            };
            return (CheckStatus::Failed(Box::new(failure)), Some(i));
        }
        (CheckStatus::Passed, None)
    }

    /// A failure that is not a value, and its hint.
    pub fn problem(&self, answer: &Answer<S::Reply>) -> (Problem, Text) {
        problem(answer, self.prose)
    }
}

/// A failure that is not a value, and its hint (`timed_out` in the exercise's prose
/// overrides the general one).
pub fn problem<R>(answer: &Answer<R>, prose: Hints) -> (Problem, Text) {
    match answer {
        Answer::Error(m) => (Problem::Error(m.clone()), Text::in_each(|| hints::error(m))),
        Answer::Panicked(m) => (
            Problem::Panicked(m.clone()),
            Text::in_each(|| hints::panic(m)),
        ),
        Answer::TimedOut(s) => (
            Problem::TimedOut(*s),
            prose
                .other("timed_out")
                .unwrap_or_else(|| Text::in_each(|| hints::timed_out().to_string())),
        ),
        Answer::Crashed(m) => (
            Problem::Crashed(m.clone()),
            Text::in_each(|| hints::crashed().to_string()),
        ),
        Answer::Value(_) | Answer::NotRun => (Problem::Wrong, prose.text("fallback")),
    }
}
