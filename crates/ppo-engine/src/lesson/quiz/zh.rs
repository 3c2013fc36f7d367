//! The Chinese twin of a quiz: structure (answers, measures, tolerances) from `quiz.toml`,
//! words (prompt, choices, explanations) from `quiz.zh.toml`.

use serde::Deserialize;

use super::parse::Explain;
use super::{Question, QuestionKind, QuizError};

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct TranslatedFile {
    question: Vec<TranslatedQuestion>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct TranslatedQuestion {
    prompt: String,
    #[serde(default)]
    choices: Vec<String>,
    explain: Explain,
}

/// Replaces the prose of `questions` with that of `text` (a `quiz.zh.toml`: per question
/// only `prompt`, `choices` and `explain`, as many as in `quiz.toml`).
///
/// # Errors
/// [`QuizError::File`] naming the question that does not match.
pub fn translate(dir: &str, questions: &mut [Question], text: &str) -> Result<(), QuizError> {
    let bad = |reason: String| QuizError::File {
        dir: dir.to_string(),
        reason: format!("quiz.zh.toml: {reason}"),
    };
    let file: TranslatedFile = toml::from_str(text).map_err(|e| {
        bad(format!(
            "{} (a translation holds only prompt, choices and explain)",
            e.message()
        ))
    })?;
    if file.question.len() != questions.len() {
        return Err(bad(format!(
            "{} questions, but quiz.toml has {}",
            file.question.len(),
            questions.len()
        )));
    }
    for (i, (q, t)) in questions.iter_mut().zip(file.question).enumerate() {
        let n = i + 1;
        match (&mut q.kind, t.explain) {
            (
                QuestionKind::Choice {
                    choices, explain, ..
                },
                Explain::PerChoice(zh_explain),
            ) if t.choices.len() == choices.len() && zh_explain.len() == explain.len() => {
                *choices = t.choices;
                *explain = zh_explain;
            }
            (QuestionKind::Predict { explain, .. }, Explain::One(zh_explain))
                if t.choices.is_empty() =>
            {
                *explain = zh_explain;
            }
            _ => {
                return Err(bad(format!(
                    "question {n}: give the same kind of question as quiz.toml, with as many \
                     choices and explanations"
                )));
            }
        }
        q.prompt = t.prompt;
    }
    Ok(())
}
