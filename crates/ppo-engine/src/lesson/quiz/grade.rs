//! Grading an answer: a choice ([`Question::choose`]) or a prediction against the live value
//! ([`Question::predict`]), and the notebook's question with its run's numbers ([`ask`]) and
//! in-place graders [`answer`], [`answer_live`] and [`predict`].

use super::super::Snapshot;
use super::{Answer, Question, QuestionKind, QuizError, letter_index, letter_of, questions};
use crate::i18n::t;
use crate::tr;

/// The verdict on one answer, with what to read next.
#[derive(Debug, Clone, PartialEq)]
pub struct Verdict {
    /// Whether the learner gave an answer at all (a placeholder is not one).
    pub answered: bool,
    /// Whether it is right.
    pub right: bool,
    /// The live value, for a prediction (revealed only once answered).
    pub live: Option<f64>,
    /// What to show: the verdict line, then the explanation.
    pub text: String,
}

impl std::fmt::Display for Verdict {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.text)
    }
}

impl Verdict {
    fn unanswered(text: String) -> Self {
        Self {
            answered: false,
            right: false,
            live: None,
            text,
        }
    }

    /// Shows the verdict as a notebook cell's output (the evcxr kernel calls this).
    pub fn evcxr_display(&self) {
        for (mime, content) in crate::notebook::Rich::rich(self) {
            println!("EVCXR_BEGIN_CONTENT {mime}\n{content}\nEVCXR_END_CONTENT");
        }
    }
}

impl crate::notebook::Rich for Verdict {
    fn rich(&self) -> Vec<(&'static str, String)> {
        vec![("text/plain", self.text.clone())]
    }
}

impl Question {
    /// Grades the choice `letter` (`'a'`..) against the right choice in `snapshot` (the
    /// same in every snapshot unless the run decides it); a letter that is not a choice is
    /// no answer.
    #[must_use]
    pub fn choose(&self, letter: char, snapshot: &Snapshot) -> Verdict {
        let QuestionKind::Choice {
            choices,
            answer,
            explain,
        } = &self.kind
        else {
            return Verdict::unanswered(
                t(
                    "This question asks for a number: answer it with quiz::predict.",
                    "这道题要一个数：请用 quiz::predict 作答。",
                )
                .into(),
            );
        };
        let last = letter_of(choices.len() - 1);
        let Some(index) = letter_index(&letter.to_string()).filter(|&i| i < choices.len()) else {
            return Verdict::unanswered(tr!(
                "Not answered yet: put your choice (a to {last}) in place of '{letter}' and run it again.",
                "还没有作答：把 '{letter}' 换成你的选择（a 到 {last}），再运行一次。"
            ));
        };
        let Some(answer) = self.right_choice(snapshot) else {
            let about = match answer {
                Answer::Live(m) => m.describe(),
                Answer::Letter(_) => "",
            };
            return Verdict::unanswered(tr!(
                "The run has not decided this one yet ({about}): train at least one episode first.",
                "本次运行还没有给出这道题的答案（{about}）：请先至少训练一个回合。"
            ));
        };
        let answer = &answer;
        let right = index == *answer;
        let mut text = if right {
            tr!(
                "✓ Right: {}) {}",
                "✓ 答对了：{}) {}",
                letter_of(index),
                choices[index]
            )
        } else {
            tr!(
                "✗ Not {}). The answer is {}) {}",
                "✗ 不是 {}）。正确答案是 {}) {}",
                letter_of(index),
                letter_of(*answer),
                choices[*answer]
            )
        };
        text.push_str(&format!("\n\n{}) {}", letter_of(index), explain[index]));
        if !right {
            text.push_str(&format!("\n{}) {}", letter_of(*answer), explain[*answer]));
        }
        Verdict {
            answered: true,
            right,
            live: None,
            text,
        }
    }

    /// Grades the prediction `value` against the live value in `snapshot`.
    #[must_use]
    pub fn predict(&self, value: f64, snapshot: &Snapshot) -> Verdict {
        let QuestionKind::Predict {
            measure,
            tolerance,
            explain,
        } = &self.kind
        else {
            return Verdict::unanswered(
                t(
                    "This is a multiple-choice question: answer it with quiz::answer.",
                    "这是一道选择题：请用 quiz::answer 作答。",
                )
                .into(),
            );
        };
        if !value.is_finite() {
            return Verdict::unanswered(
                t(
                    "Not answered yet: predict a finite number.",
                    "还没有作答：请预测一个有限的数。",
                )
                .into(),
            );
        }
        let Some(live) = (measure.value)(snapshot) else {
            return Verdict::unanswered(tr!(
                "The live value ({}) does not exist yet: train at least one episode first.",
                "实时数值（{}）还不存在：请先至少训练一个回合。",
                measure.describe()
            ));
        };
        let right = (value - live).abs() <= *tolerance;
        let mark = if right {
            t("✓ Right", "✓ 答对了")
        } else {
            t("✗ Not quite", "✗ 不太对")
        };
        let explain = super::template::fill(explain, snapshot);
        let counts = if *tolerance == 0.0 {
            t("only the exact value counts", "只有完全等于这个数才算对").to_string()
        } else {
            tr!(
                "within ±{tolerance} counts",
                "相差不超过 ±{tolerance} 即算对"
            )
        };
        let text = tr!(
            "{mark}: you said {value}, the live value is {} ({}; {counts}).\n\n{explain}",
            "{mark}：你的预测是 {value}，实时数值是 {}（{}；{counts}）。\n\n{explain}",
            show(live),
            measure.describe()
        );
        Verdict {
            answered: true,
            right,
            live: Some(live),
            text,
        }
    }
}

/// A live value for reading: integers as integers, others to 6 significant digits.
fn show(x: f64) -> String {
    if x.fract() == 0.0 && x.abs() < 1e9 {
        format!("{x:.0}")
    } else {
        format!("{x:.6}")
    }
}

fn question(lesson: &str, number: usize) -> Result<Question, QuizError> {
    let all = questions(lesson)?;
    let count = all.len();
    all.into_iter()
        .nth(number.wrapping_sub(1))
        .ok_or_else(|| QuizError::NoSuchQuestion {
            lesson: lesson.to_string(),
            number,
            count,
        })
}

/// Grades choice `letter` for question `number` (from 1) of lesson `lesson`, as a notebook
/// cell does: `quiz::answer("gae", 2, 'b')`. A placeholder such as `'?'` is no answer yet.
/// A question whose right choice the run decides is answered with [`answer_live`].
#[must_use]
pub fn answer(lesson: &str, number: usize, letter: char) -> Verdict {
    numbered(
        number,
        match question(lesson, number) {
            Ok(q)
                if matches!(
                    q.kind,
                    QuestionKind::Choice {
                        answer: Answer::Live(_),
                        ..
                    }
                ) =>
            {
                Verdict::unanswered(tr!(
                    "The run decides this question's answer: grade it with quiz::answer_live(\"{lesson}\", {number}, '{letter}', &snap).",
                    "这道题的答案由本次运行决定：请用 quiz::answer_live(\"{lesson}\", {number}, '{letter}', &snap) 作答。"
                ))
            }
            Ok(q) => q.choose(letter, &Snapshot::default()),
            Err(e) => Verdict::unanswered(e.to_string()),
        },
    )
}

/// Grades choice `letter` for question `number` of lesson `lesson` against the run in
/// `snapshot`, for a question whose right choice the run decides (it grades the others as
/// [`answer`] does): `quiz::answer_live("clipping", 5, 'c', &snap)`.
#[must_use]
pub fn answer_live(lesson: &str, number: usize, letter: char, snapshot: &Snapshot) -> Verdict {
    numbered(
        number,
        match question(lesson, number) {
            Ok(q) => q.choose(letter, snapshot),
            Err(e) => Verdict::unanswered(e.to_string()),
        },
    )
}

/// A question as a notebook cell shows it: its prompt with the numbers of the run in
/// `snapshot` and its choices ([`ask`]).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Posed {
    /// The question, numbered, with its choices.
    pub text: String,
}

impl std::fmt::Display for Posed {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.text)
    }
}

impl Posed {
    /// Shows the question as a notebook cell's output (the evcxr kernel calls this).
    pub fn evcxr_display(&self) {
        for (mime, content) in crate::notebook::Rich::rich(self) {
            println!("EVCXR_BEGIN_CONTENT {mime}\n{content}\nEVCXR_END_CONTENT");
        }
    }
}

impl crate::notebook::Rich for Posed {
    fn rich(&self) -> Vec<(&'static str, String)> {
        vec![("text/plain", self.text.clone())]
    }
}

/// Question `number` of lesson `lesson` with the numbers of the run in `snapshot`, as a
/// notebook cell shows it before the learner answers: `quiz::ask("gae", 5, &snap)`.
#[must_use]
pub fn ask(lesson: &str, number: usize, snapshot: &Snapshot) -> Posed {
    let text = match question(lesson, number) {
        Ok(q) => tr!(
            "Question {number}: {}",
            "第 {number} 题：{}",
            q.text_in(snapshot)
        ),
        Err(e) => e.to_string(),
    };
    Posed { text }
}

/// `verdict` with the question's number in front, so that answers read apart in a notebook.
fn numbered(number: usize, mut verdict: Verdict) -> Verdict {
    verdict.text = tr!("Question {number}: {}", "第 {number} 题：{}", verdict.text);
    verdict
}

/// Grades the prediction `value` (a number as text, e.g. `"0.93"`; `"?"` is no answer yet)
/// for question `number` of lesson `lesson` against the live value in `snapshot`:
/// `quiz::predict("ratio", 3, "1.0", &snap)`.
#[must_use]
pub fn predict(lesson: &str, number: usize, value: &str, snapshot: &Snapshot) -> Verdict {
    let q = match question(lesson, number) {
        Ok(q) => q,
        Err(e) => return numbered(number, Verdict::unanswered(e.to_string())),
    };
    numbered(
        number,
        match value.trim().parse::<f64>() {
            Ok(v) => q.predict(v, snapshot),
            Err(_) => Verdict::unanswered(tr!(
                "Not answered yet: put your prediction (a number, like \"0.5\") in place of \"{value}\" and run it again.",
                "还没有作答：把 \"{value}\" 换成你的预测（一个数，例如 \"0.5\"），再运行一次。"
            )),
        },
    )
}

#[cfg(test)]
mod tests {
    use super::super::parse;
    use super::super::parse::tests::TWO;
    use super::*;

    #[test]
    fn parses_both_kinds_and_grades_them() -> Result<(), QuizError> {
        let qs = parse("99-x", TWO)?;
        assert_eq!(qs.len(), 2);
        let none = Snapshot::default();
        let right = qs[0].choose('B', &none);
        assert!(right.answered && right.right, "{right}");
        let wrong = qs[0].choose('c', &none);
        assert!(wrong.answered && !wrong.right);
        assert!(
            wrong.text.contains("no 3") && wrong.text.contains("yes"),
            "{wrong}"
        );
        assert!(!qs[0].choose('?', &none).answered);
        assert!(
            !qs[0].choose('d', &none).answered,
            "d is not a choice of three"
        );
        let mut snap = Snapshot::default();
        assert!(!qs[1].predict(3.0, &snap).answered, "nothing trained yet");
        snap.latest = crate::run::IntoLatest::into_latest(crate::lesson::live::CartPoleLatest {
            trace: crate::ppo::UpdateTrace {
                rewards: vec![1.0; 12],
                ..crate::ppo::UpdateTrace::default()
            },
            ..Default::default()
        });
        let close = qs[1].predict(12.4, &snap);
        assert!(close.right && close.live == Some(12.0), "{close}");
        assert!(!qs[1].predict(13.0, &snap).right);
        Ok(())
    }

    #[test]
    fn a_prediction_with_no_tolerance_says_it_needs_the_exact_value() -> Result<(), QuizError> {
        use crate::i18n::Lang;
        let exact = TWO.replace("tolerance = 0.5", "tolerance = 0");
        let snap = Snapshot {
            latest: crate::run::IntoLatest::into_latest(crate::lesson::live::CartPoleLatest {
                trace: crate::ppo::UpdateTrace {
                    rewards: vec![1.0; 12],
                    ..crate::ppo::UpdateTrace::default()
                },
                ..Default::default()
            }),
            ..Snapshot::default()
        };
        for (lang, exactly, within) in [
            (
                Lang::En,
                "; only the exact value counts).",
                "; within ±0.5 counts).",
            ),
            (
                Lang::Zh,
                "；只有完全等于这个数才算对）。",
                "；相差不超过 ±0.5 即算对）。",
            ),
        ] {
            let _lang = lang.scoped();
            let q = &parse("99-x", &exact)?[1];
            let (right, off) = (q.predict(12.0, &snap), q.predict(12.4, &snap));
            assert!(right.right && !off.right, "{right}\n{off}");
            for v in [&right, &off] {
                assert!(
                    v.text.contains(exactly) && !v.text.contains("±0"),
                    "{lang:?}: {v}"
                );
            }
            let loose = parse("99-x", TWO)?[1].predict(12.4, &snap);
            assert!(
                loose.right && loose.text.contains(within),
                "{lang:?}: {loose}"
            );
        }
        Ok(())
    }

    /// A CartPole snapshot whose last state is (θ, θ̇), ending in θ + 0.02·θ̇, and whose last
    /// epoch's largest ratio `r` belongs to a row with advantage `adv` (ε = 0.2).
    fn run(theta: f32, theta_dot: f32, r: f32, adv: f32) -> Snapshot {
        Snapshot {
            hyper: vec![("eps".into(), "0.2".into())],
            latest: crate::run::IntoLatest::into_latest(crate::lesson::live::CartPoleLatest {
                trace: crate::ppo::UpdateTrace {
                    states: vec![[0.0, 0.0, theta, theta_dot]],
                    next_states: vec![[0.0, 0.0, theta + 0.02 * theta_dot, 0.0]],
                    advantage: vec![adv, 0.5],
                    epochs: vec![crate::ppo::EpochTrace {
                        ratio: vec![r, 1.0],
                        ..crate::ppo::EpochTrace::default()
                    }],
                    ..crate::ppo::UpdateTrace::default()
                },
                ..Default::default()
            }),
            ..Snapshot::default()
        }
    }

    #[test]
    fn run_dependent_questions_are_graded_against_their_run() -> Result<(), QuizError> {
        let qs = parse("99-x", super::super::parse::tests::LIVE)?;
        // A prediction that follows from the shown θ and θ̇: right within the tolerance of
        // this run's value, wrong outside it, and wrong for another run's value.
        let (a, b) = (run(0.15, 1.5, 1.3, 0.4), run(-0.1, -2.0, 1.1, 0.4));
        assert!(
            qs[1].prompt_in(&a).contains("θ = 0.15, θ̇ = 1.5:"),
            "{}",
            qs[1].prompt_in(&a)
        );
        let right = qs[1].predict(0.18, &a);
        assert!(
            right.right && right.text.contains("0.15 + 0.02·1.5."),
            "{right}"
        );
        assert!(qs[1].predict(0.1804, &a).right);
        assert!(!qs[1].predict(0.1806, &a).right, "outside ±0.0005");
        assert!(
            !qs[1].predict(0.18, &b).right,
            "another run, another answer"
        );
        assert!(qs[1].predict(-0.14, &b).right);
        // A choice the run decides: r = 1.3 with Â > 0 is past the band (nothing pulls);
        // r = 1.1 is inside (pushed up); Â < 0 at r = 1.3 is pushed down.
        for (snap, right, wrong) in [
            (&a, 'c', 'a'),
            (&b, 'a', 'c'),
            (&run(0.0, 0.0, 1.3, -0.4), 'b', 'c'),
        ] {
            assert_eq!(qs[0].right_choice(snap), letter_index(&right.to_string()));
            assert!(qs[0].choose(right, snap).right);
            let no = qs[0].choose(wrong, snap);
            assert!(no.answered && !no.right, "{no}");
        }
        let untrained = qs[0].choose('a', &Snapshot::default());
        assert!(
            !untrained.answered && untrained.text.contains("train"),
            "{untrained}"
        );
        assert!(qs[0].ready_in(&a) && !qs[0].ready_in(&Snapshot::default()));
        assert!(qs[0].prompt_in(&Snapshot::default()).contains("r = …"));
        Ok(())
    }

    #[test]
    fn notebooks_ask_with_the_run_and_answer_live_choices_with_it() {
        // Lesson 11's last question: its right choice comes from the run.
        let Ok(lesson) = questions("clipping") else {
            panic!("the clipping quiz loads");
        };
        let n = lesson
            .iter()
            .position(|q| {
                matches!(
                    q.kind,
                    QuestionKind::Choice {
                        answer: Answer::Live(_),
                        ..
                    }
                )
            })
            .map_or(0, |i| i + 1);
        assert!(n > 0, "lesson 11 has a choice the run decides");
        let told = answer("clipping", n, 'a');
        assert!(
            !told.answered && told.text.contains("quiz::answer_live"),
            "{told}"
        );
        let snap = run(0.0, 0.0, 1.3, 0.4);
        let posed = ask("clipping", n, &snap);
        assert!(
            posed.text.contains("r = 1.3 ") && posed.text.contains("c)"),
            "{posed}"
        );
        assert!(answer_live("clipping", n, 'c', &snap).right);
        assert!(!answer_live("clipping", n, 'a', &snap).right);
    }

    #[test]
    fn unknown_lessons_and_numbers_are_explained() {
        assert!(answer("nope", 1, 'a').text.contains("ppo-tutor lessons"));
        assert!(
            answer("ratio", 99, 'a')
                .text
                .contains("there is no question 99")
        );
        assert!(
            answer("ratio", 0, 'a')
                .text
                .contains("there is no question 0")
        );
    }
}
