//! The parser of `lessons/NN-slug/quiz.toml`: the questions, their answers, measures and
//! tolerances, checked so that a bad file names the question and the fix.

use serde::Deserialize;

use super::measures::{Basis, all};
use super::{Answer, Measure, Question, QuestionKind, QuizError, measure, template};

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct QuizFile {
    question: Vec<RawQuestion>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawQuestion {
    prompt: String,
    #[serde(default)]
    choices: Vec<String>,
    #[serde(default)]
    answer: Option<String>,
    #[serde(default)]
    answer_from: Option<String>,
    #[serde(default)]
    predict: Option<String>,
    #[serde(default)]
    tolerance: Option<f64>,
    explain: Explain,
}

#[derive(Debug, Deserialize)]
#[serde(untagged)]
pub(super) enum Explain {
    /// One explanation, for a prediction.
    One(String),
    /// One explanation per choice.
    PerChoice(Vec<String>),
}

/// Parses the `quiz.toml` of lesson folder `dir`.
///
/// # Errors
/// [`QuizError::File`] naming the question and what to fix.
pub fn parse(dir: &str, text: &str) -> Result<Vec<Question>, QuizError> {
    let bad = |reason: String| QuizError::File {
        dir: dir.to_string(),
        reason,
    };
    let file: QuizFile = toml::from_str(text).map_err(|e| bad(e.message().to_string()))?;
    file.question
        .into_iter()
        .enumerate()
        .map(|(i, q)| {
            let n = i + 1;
            let shown = template::check(&q.prompt)
                .map_err(|e| bad(format!("question {n}: prompt: {e}")))?;
            let kind = match (q.predict, q.answer, q.answer_from, q.explain) {
                (Some(name), None, None, Explain::One(explain)) if q.choices.is_empty() => {
                    let measure = graded_by(&name, "predict", 0, n, &shown).map_err(&bad)?;
                    template::check(&explain)
                        .map_err(|e| bad(format!("question {n}: explain: {e}")))?;
                    let tolerance = q.tolerance.filter(|t| t.is_finite() && *t >= 0.0);
                    let tolerance = tolerance.ok_or_else(|| {
                        bad(format!(
                            "question {n}: a predict question needs tolerance = a number ≥ 0"
                        ))
                    })?;
                    QuestionKind::Predict {
                        measure,
                        tolerance,
                        explain,
                    }
                }
                (None, letter, from, Explain::PerChoice(explain))
                    if letter.is_some() != from.is_some() && q.tolerance.is_none() =>
                {
                    if !(3..=4).contains(&q.choices.len()) {
                        return Err(bad(format!("question {n}: give 3 or 4 choices")));
                    }
                    if explain.len() != q.choices.len() {
                        return Err(bad(format!(
                            "question {n}: explain needs one text per choice ({}), not {}",
                            q.choices.len(),
                            explain.len()
                        )));
                    }
                    let answer = match (letter, from) {
                        (Some(letter), _) => Answer::Letter(
                            letter_index(&letter)
                                .filter(|&a| a < q.choices.len())
                                .ok_or_else(|| {
                                    bad(format!(
                                        "question {n}: answer = '{letter}' must be the letter of a choice (a to {})",
                                        letter_of(q.choices.len() - 1)
                                    ))
                                })?,
                        ),
                        (None, from) => {
                            let name = from.unwrap_or_default();
                            Answer::Live(
                                graded_by(&name, "answer_from", q.choices.len(), n, &shown)
                                    .map_err(&bad)?,
                            )
                        }
                    };
                    QuestionKind::Choice {
                        choices: q.choices,
                        answer,
                        explain,
                    }
                }
                _ => {
                    return Err(bad(format!(
                        "question {n}: write either choices + answer (or answer_from) + explain = \
                         [one per choice], or predict + tolerance + explain = \"...\""
                    )));
                }
            };
            Ok(Question {
                prompt: q.prompt,
                kind,
            })
        })
        .collect()
}

/// The measure `name` that field `field` of question `n` grades against, checked: a
/// number for `predict` (`choices` 0), the index of one of `choices` choices for
/// `answer_from`; a run measure's givens shown in the prompt (`shown`), and the answer not.
fn graded_by(
    name: &str,
    field: &str,
    choices: usize,
    n: usize,
    shown: &[&str],
) -> Result<&'static Measure, String> {
    let m = measure(name).ok_or_else(|| {
        format!(
            "question {n}: {field} = '{name}' is not a measure; use one of: {}",
            all()
                .filter(|m| m.choices == choices && !matches!(m.basis, Basis::Given))
                .map(|m| m.name)
                .collect::<Vec<_>>()
                .join(", ")
        )
    })?;
    if matches!(m.basis, Basis::Given) {
        return Err(format!(
            "question {n}: {field} = '{name}' is a given, a number the prompt shows \
             ({{{{{name}}}}}); grade against a fact or a run measure"
        ));
    }
    if m.choices != choices {
        return Err(match (m.choices, choices) {
            (0, _) => format!(
                "question {n}: answer_from = '{name}' is a number, not the index of a choice; \
                 ask it with predict + tolerance"
            ),
            (k, 0) => format!(
                "question {n}: predict = '{name}' is the index of one of {k} choices; ask it \
                 with {k} choices and answer_from"
            ),
            (k, c) => format!(
                "question {n}: answer_from = '{name}' picks one of {k} choices (index 0 to \
                 {}), but the question has {c}",
                k - 1
            ),
        });
    }
    if shown.contains(&m.name) {
        return Err(format!(
            "question {n}: the prompt shows {{{{{name}}}}}, the answer itself"
        ));
    }
    if let Some(missing) = m.given().iter().find(|g| !shown.contains(g)) {
        return Err(format!(
            "question {n}: {field} = '{name}' follows from {}; the prompt must show \
             {{{{{missing}}}}}",
            m.given()
                .iter()
                .map(|g| format!("{{{{{g}}}}}"))
                .collect::<Vec<_>>()
                .join(", ")
        ));
    }
    Ok(m)
}

/// `0` for `a`, `1` for `b`, ... (either case).
#[must_use]
pub fn letter_index(letter: &str) -> Option<usize> {
    let mut chars = letter.trim().chars();
    let c = chars.next()?.to_ascii_lowercase();
    (chars.next().is_none() && c.is_ascii_lowercase()).then(|| usize::from(c as u8 - b'a'))
}

/// `a` for `0`, `b` for `1`, ...
#[must_use]
pub fn letter_of(index: usize) -> char {
    char::from(b'a' + u8::try_from(index.min(25)).unwrap_or(25))
}

#[cfg(test)]
pub(super) mod tests {
    use super::*;

    /// A quiz file with one question of each kind.
    pub(in crate::lesson::quiz) const TWO: &str = r#"
[[question]]
prompt = "Which?"
choices = ["one", "two", "three"]
answer = "b"
explain = ["no 1", "yes", "no 3"]

[[question]]
prompt = "How many?"
predict = "batch_rows"
tolerance = 0.5
explain = "Because."
"#;

    /// A choice the run decides, and a prediction that follows from two givens.
    pub(in crate::lesson::quiz) const LIVE: &str = r#"
[[question]]
prompt = "r = {{ratio_max_last}}, Â = {{adv_at_ratio_max_last}}, ε = {{eps}}: what does the loss do?"
choices = ["up", "down", "nothing"]
answer_from = "pull_at_ratio_max_last"
explain = ["a", "b", "c"]

[[question]]
prompt = "θ = {{theta_last}}, θ̇ = {{theta_dot_last}}: the next θ?"
predict = "theta_next_last"
tolerance = 0.0005
explain = "θ + 0.02·θ̇ = {{theta_last}} + 0.02·{{theta_dot_last}}."
"#;

    #[test]
    fn bad_files_name_the_question_and_the_fix() {
        let cases = [
            (
                TWO.replace("answer = \"b\"", "answer = \"e\""),
                "answer = 'e'",
            ),
            (TWO.replace("\"no 3\"", ""), "one text per choice"),
            (TWO.replace("batch_rows", "batch_rowz"), "not a measure"),
            (TWO.replace("tolerance = 0.5\n", ""), "tolerance"),
            (
                TWO.replace("prompt = \"Which?\"", "prompt = \"Which?\"\nhint = 1"),
                "unknown field",
            ),
            (
                TWO.replace("prompt = \"Which?\"", "prompt = \"Which {{gama}}?\""),
                "question 1: prompt: {{gama}} is not a measure",
            ),
            (
                TWO.replace("predict = \"batch_rows\"", "predict = \"gamma\""),
                "predict = 'gamma' is a given",
            ),
            (
                LIVE.replace(
                    "answer_from = \"pull_at_ratio_max_last\"",
                    "answer_from = \"pull_at\"",
                ),
                "question 1: answer_from = 'pull_at' is not a measure",
            ),
            (
                LIVE.replace("\"nothing\"]", "\"nothing\", \"both\"]")
                    .replace("\"c\"]", "\"c\", \"d\"]"),
                "answer_from = 'pull_at_ratio_max_last' picks one of 3 choices (index 0 to 2), but the question has 4",
            ),
            (
                LIVE.replace(
                    "answer_from = \"pull_at_ratio_max_last\"",
                    "answer_from = \"batch_rows\"",
                ),
                "answer_from = 'batch_rows' is a number",
            ),
            (
                LIVE.replace(
                    "answer_from = \"pull_at_ratio_max_last\"",
                    "answer_from = \"pull_at_ratio_max_last\"\nanswer = \"a\"",
                ),
                "either choices + answer (or answer_from)",
            ),
            (
                LIVE.replace("θ̇ = {{theta_dot_last}}: the", "the"),
                "question 2: predict = 'theta_next_last' follows from {{theta_last}}, {{theta_dot_last}}; the prompt must show {{theta_dot_last}}",
            ),
            (
                LIVE.replace("the next θ?", "the next θ, {{theta_next_last}}?"),
                "question 2: the prompt shows {{theta_next_last}}, the answer itself",
            ),
        ];
        for (text, want) in cases {
            let e = parse("99-x", &text)
                .err()
                .map(|e| e.to_string())
                .unwrap_or_default();
            assert!(
                e.contains("lessons/99-x/quiz.toml") && e.contains(want),
                "{want}: {e}"
            );
        }
        assert!(parse("99-x", LIVE).is_ok());
    }
}
