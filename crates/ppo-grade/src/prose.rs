//! An exercise's teaching prose, read from its lesson's `exercise.toml` (embedded): the
//! hint for each typical mistake by id, the fallback hint, and hints for situations of the
//! exercise's own (`other`). The grader only looks texts up; writing them is content work.

use std::collections::BTreeMap;
use std::sync::OnceLock;

use super::error::GradeError;
use crate::i18n::Lang;
use crate::lesson::loader::{ExerciseText, embedded_exercises_in};

/// One exercise's prose.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Prose {
    /// The lesson folder whose `exercise.toml` holds it.
    pub lesson: String,
    /// The texts.
    pub text: ExerciseText,
}

impl Prose {
    /// Every exercise's prose in the current language ([`Lang::current`]), parsed once
    /// per process and language, by exercise name.
    ///
    /// # Errors
    /// [`GradeError::Content`] if an embedded `exercise.toml` (or its `exercise.zh.toml`)
    /// does not parse (a broken build: the content tests catch it first).
    pub fn all() -> Result<&'static BTreeMap<String, Prose>, GradeError> {
        type Table = OnceLock<Result<BTreeMap<String, Prose>, String>>;
        static EN: Table = OnceLock::new();
        static ZH: Table = OnceLock::new();
        let lang = Lang::current();
        lang.pick(&EN, &ZH)
            .get_or_init(|| {
                let files = embedded_exercises_in(lang).map_err(|e| e.to_string())?;
                Ok(files
                    .into_iter()
                    .flat_map(|(lesson, texts)| {
                        texts.into_iter().map(move |text| {
                            let prose = Prose {
                                lesson: lesson.clone(),
                                text,
                            };
                            (prose.text.name.clone(), prose)
                        })
                    })
                    .collect())
            })
            .as_ref()
            .map_err(|e| GradeError::Content(e.clone()))
    }

    /// The prose of exercise `name`.
    ///
    /// # Errors
    /// [`GradeError::Content`] if its lesson has no `[[exercise]]` named `name`.
    pub fn of(name: &str) -> Result<&'static Prose, GradeError> {
        Self::all()?.get(name).ok_or_else(|| {
            GradeError::Content(format!(
                "no [[exercise]] named '{name}' in any lessons/*/exercise.toml"
            ))
        })
    }

    /// The hint for mistake `id` (the fallback if the file has none: a test forbids that).
    #[must_use]
    pub fn mistake(&self, id: &str) -> &str {
        self.text
            .mistakes
            .get(id)
            .map_or(self.text.fallback.as_str(), String::as_str)
    }

    /// The text at `key`: `fallback`, or a key of `other` (the fallback if absent).
    #[must_use]
    pub fn text(&self, key: &str) -> &str {
        if key == "fallback" {
            return &self.text.fallback;
        }
        self.other(key).unwrap_or(&self.text.fallback)
    }

    /// The `other` text at `key`, if the exercise has one.
    #[must_use]
    pub fn other(&self, key: &str) -> Option<&str> {
        self.text.other.get(key).map(String::as_str)
    }
}
