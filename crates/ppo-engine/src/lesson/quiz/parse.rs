//! The parser of `lessons/NN-slug/quiz.toml`: the questions, their answers, measures and
//! tolerances, checked so that a bad file names the question and the fix.

use serde::Deserialize;

use super::{MEASURES, Question, QuestionKind, QuizError, measure};

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
            let kind = match (q.predict, q.answer, q.explain) {
                (Some(name), None, Explain::One(explain)) if q.choices.is_empty() => {
                    let measure = measure(&name).ok_or_else(|| {
                        bad(format!(
                            "question {n}: predict = '{name}' is not a measure; use one of: {}",
                            MEASURES.iter().map(|m| m.name).collect::<Vec<_>>().join(", ")
                        ))
                    })?;
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
                (None, Some(letter), Explain::PerChoice(explain)) => {
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
                    let answer = letter_index(&letter)
                        .filter(|&a| a < q.choices.len())
                        .ok_or_else(|| {
                            bad(format!(
                                "question {n}: answer = '{letter}' must be the letter of a choice (a to {})",
                                letter_of(q.choices.len() - 1)
                            ))
                        })?;
                    QuestionKind::Choice {
                        choices: q.choices,
                        answer,
                        explain,
                    }
                }
                _ => {
                    return Err(bad(format!(
                        "question {n}: write either choices + answer + explain = [one per choice], \
                         or predict + tolerance + explain = \"...\""
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
        ];
        for (text, want) in cases {
            let e = parse("99-x", &text)
                .err()
                .map(|e| e.to_string())
                .unwrap_or_default();
            assert!(
                e.contains("lessons/99-x/quiz.toml") && e.contains(want),
                "{e}"
            );
        }
    }
}
