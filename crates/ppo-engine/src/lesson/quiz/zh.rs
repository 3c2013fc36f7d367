//! The Chinese twin of a quiz: structure (answers, measures, tolerances) from `quiz.toml`,
//! words (prompt, choices, explanations) from `quiz.zh.toml`.

use serde::Deserialize;

use super::parse::Explain;
use super::{Question, QuestionKind, QuizError, template};

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
                same_givens(explain, &zh_explain)
                    .map_err(|e| bad(format!("question {n}: explain {e}")))?;
                *explain = zh_explain;
            }
            _ => {
                return Err(bad(format!(
                    "question {n}: give the same kind of question as quiz.toml, with as many \
                     choices and explanations"
                )));
            }
        }
        same_givens(&q.prompt, &t.prompt).map_err(|e| bad(format!("question {n}: prompt {e}")))?;
        q.prompt = t.prompt;
    }
    Ok(())
}

/// Checks that the translation `zh` of `en` shows the same `{{…}}` givens.
fn same_givens(en: &str, zh: &str) -> Result<(), String> {
    let (mut a, mut b) = (template::names(en), template::names(zh));
    a.sort();
    b.sort();
    if a == b {
        return Ok(());
    }
    let list = |v: &[(String, Option<usize>)]| {
        v.iter()
            .map(|(n, d)| match d {
                Some(d) => format!("{{{{{n}:.{d}}}}}"),
                None => format!("{{{{{n}}}}}"),
            })
            .collect::<Vec<_>>()
            .join(", ")
    };
    Err(format!(
        "shows {}, but quiz.toml shows {}: give the same givens",
        list(&b),
        list(&a)
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_translation_shows_the_same_givens() -> Result<(), QuizError> {
        let en = super::super::parse::tests::LIVE;
        let mut qs = super::super::parse("99-x", en)?;
        let zh = r#"
[[question]]
prompt = "r = {{ratio_max_last}}，Â = {{adv_at_ratio_max_last}}，ε = {{eps}}：损失怎样作用？"
choices = ["向上", "向下", "不作用"]
explain = ["甲", "乙", "丙"]

[[question]]
prompt = "θ = {{theta_last}}，θ̇ = {{theta_dot_last}}：下一个 θ？"
explain = "θ + 0.02·θ̇ = {{theta_last}} + 0.02·{{theta_dot_last}}。"
"#;
        translate("99-x", &mut qs, zh)?;
        let lost = zh.replace("，θ̇ = {{theta_dot_last}}", "");
        let mut qs = super::super::parse("99-x", en)?;
        let e = translate("99-x", &mut qs, &lost)
            .err()
            .map(|e| e.to_string());
        assert!(
            e.as_deref().is_some_and(|e| e.contains("question 2: prompt shows {{theta_last}}, but quiz.toml shows {{theta_dot_last}}, {{theta_last}}")),
            "{e:?}"
        );
        Ok(())
    }
}
