//! An exercise's teaching prose, read from its lesson's `exercise.toml` (embedded): the
//! hint for each typical mistake by id, the fallback hint, and hints for situations of the
//! exercise's own (`other`). The grader only looks texts up; writing them is content work.

use std::collections::BTreeMap;
use std::sync::OnceLock;

use super::error::GradeError;
use crate::i18n::{Lang, Text};
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
        Self::all_in(Lang::current())
    }

    /// [`Prose::all`] in `lang`.
    ///
    /// # Errors
    /// As [`Prose::all`].
    pub fn all_in(lang: Lang) -> Result<&'static BTreeMap<String, Prose>, GradeError> {
        type Table = OnceLock<Result<BTreeMap<String, Prose>, String>>;
        static EN: Table = OnceLock::new();
        static ZH: Table = OnceLock::new();
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
        Self::of_in(name, Lang::current())
    }

    /// [`Prose::of`] in `lang`.
    ///
    /// # Errors
    /// As [`Prose::of`].
    pub fn of_in(name: &str, lang: Lang) -> Result<&'static Prose, GradeError> {
        Self::all_in(lang)?.get(name).ok_or_else(|| {
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

/// One exercise's hints in both languages, as a report keeps them ([`Text`]: shown in
/// the language current when the report is rendered).
#[derive(Debug, Clone, Copy)]
pub struct Hints {
    en: &'static Prose,
    zh: &'static Prose,
}

impl Hints {
    /// Exercise `name`'s hints.
    ///
    /// # Errors
    /// As [`Prose::of`], in either language.
    pub fn of(name: &str) -> Result<Self, GradeError> {
        Ok(Self {
            en: Prose::of_in(name, Lang::En)?,
            zh: Prose::of_in(name, Lang::Zh)?,
        })
    }

    /// The hint for mistake `id` ([`Prose::mistake`]).
    #[must_use]
    pub fn mistake(&self, id: &str) -> Text {
        Text::new(self.en.mistake(id), self.zh.mistake(id))
    }

    /// The text at `key` ([`Prose::text`]).
    #[must_use]
    pub fn text(&self, key: &str) -> Text {
        Text::new(self.en.text(key), self.zh.text(key))
    }

    /// The `other` text at `key`, if both languages have it ([`Prose::other`]).
    #[must_use]
    pub fn other(&self, key: &str) -> Option<Text> {
        Some(Text::new(self.en.other(key)?, self.zh.other(key)?))
    }
}
