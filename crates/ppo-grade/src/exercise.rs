//! One exercise, as every face sees it: its files, its signature, and grading.
//!
//! The faces (the terminal app, `ppo-tutor grade`/`reset`, the notebooks, the tests) only
//! ever hold a `&dyn Exercise` from the registry ([`super::exercises::ALL`]); none of them
//! names a particular exercise. Every [`Spec`] is an `Exercise` through the one grading
//! pipeline in [`super::pipeline`].

use std::path::{Path, PathBuf};

use super::error::{GradeError, GradeOptions};
use super::pipeline;
use super::progress::GradeProgress;
use super::report::Report;
pub use super::spec::Meta;
use super::spec::Spec;

/// An exercise of the course: what the faces can ask of it.
pub trait Exercise: Sync {
    /// Its name, lesson, files and backend.
    fn meta(&self) -> Meta;

    /// `pub fn name(a: T, ...) -> R`, as the learner must declare it.
    fn signature(&self) -> String;

    /// Grades `source` (the text of a learner's file, shown as `display`).
    ///
    /// # Errors
    /// A [`GradeError`] when grading cannot happen (no compiler, unwritable cache); a file
    /// that does not compile, panics or loops is a failing [`Report`].
    fn grade_source(
        &self,
        source: &str,
        display: &str,
        opts: &GradeOptions,
    ) -> Result<Report, GradeError> {
        self.grade_source_with_progress(source, display, opts, &mut |_| {})
    }

    /// [`Exercise::grade_source`], calling `progress` with each step as it happens (see
    /// [`crate::progress`]).
    ///
    /// # Errors
    /// As [`Exercise::grade_source`].
    fn grade_source_with_progress(
        &self,
        source: &str,
        display: &str,
        opts: &GradeOptions,
        progress: &mut dyn FnMut(&GradeProgress),
    ) -> Result<Report, GradeError>;

    /// The ids of its typical mistakes, in the order the judge tries them (each has a
    /// hint in the lesson's `exercise.toml` and a wrong answer in `tests/wrong_answers/`).
    fn mistake_ids(&self) -> Vec<&'static str>;

    /// The typical mistakes that no case tells apart from the reference (a catalogue
    /// check: it must be empty).
    ///
    /// # Errors
    /// [`GradeError::Fixture`] if the cases cannot be made.
    fn uncaught_mistakes(&self) -> Result<Vec<&'static str>, GradeError>;

    /// The typical mistakes that the judge does not name when a learner makes exactly
    /// that mistake, each with what it named instead (a catalogue check: it must be empty).
    ///
    /// # Errors
    /// [`GradeError::Fixture`] if the cases cannot be made, [`GradeError::Content`] if the
    /// prose does not parse.
    fn misdiagnosed_mistakes(
        &self,
    ) -> Result<Vec<(&'static str, Option<&'static str>)>, GradeError>;

    /// The function's name.
    fn name(&self) -> &'static str {
        self.meta().name
    }

    /// The starter's path relative to the course root: `lessons/<lesson>/<starter>`.
    fn starter_path(&self) -> String {
        let m = self.meta();
        format!("lessons/{}/{}", m.lesson, m.starter)
    }

    /// The reference solution's path relative to the course root.
    fn solution_path(&self) -> String {
        let m = self.meta();
        format!("lessons/{}/{}", m.lesson, m.solution)
    }

    /// The embedded starter's text in the current language: for Chinese its twin with
    /// Chinese comments (`exercise.zh.rs` beside `exercise.rs`; the code is the same).
    fn starter(&self) -> Option<&'static str> {
        let m = self.meta();
        let english = format!("{}/{}", m.lesson, m.starter);
        let chinese = english
            .strip_suffix(".rs")
            .map(|stem| format!("{stem}.zh.rs"));
        match (crate::i18n::Lang::current(), chinese) {
            (crate::i18n::Lang::Zh, Some(zh)) => crate::lesson::files::embedded_file(&zh)
                .or_else(|| crate::lesson::files::embedded_file(&english)),
            _ => crate::lesson::files::embedded_file(&english),
        }
    }

    /// The embedded reference solution (shown after a pass).
    fn solution(&self) -> Option<&'static str> {
        let m = self.meta();
        crate::lesson::files::embedded_file(&format!("{}/{}", m.lesson, m.solution))
    }

    /// Writes the starter back to `root/<starter path>`: only this exercise's function when
    /// other exercises share the file, with the old text kept beside it
    /// ([`super::reset::restore`]).
    ///
    /// # Errors
    /// [`GradeError::Write`] if the file cannot be written.
    fn reset(&self, root: &Path) -> Result<super::reset::Restored, GradeError> {
        let rel = self.starter_path();
        let text = self.starter().ok_or_else(|| GradeError::Write {
            file: PathBuf::from(&rel),
            reason: crate::i18n::Text::new(
                "no starter is embedded for this exercise",
                "这个练习没有内置的初始文件",
            ),
        })?;
        let others: Vec<&str> = super::exercises()
            .iter()
            .filter(|e| e.name() != self.name() && e.starter_path() == rel)
            .map(|e| e.name())
            .collect();
        let variants: Vec<&str> = crate::i18n::Lang::ALL
            .iter()
            .filter_map(|lang| {
                let _lang = lang.scoped();
                self.starter()
            })
            .collect();
        super::reset::restore(&root.join(&rel), self.name(), text, &others, &variants)
    }
}

impl<S: Spec> Exercise for S {
    fn meta(&self) -> Meta {
        Spec::meta(self)
    }

    fn signature(&self) -> String {
        Spec::signature(self)
    }

    fn grade_source_with_progress(
        &self,
        source: &str,
        display: &str,
        opts: &GradeOptions,
        progress: &mut dyn FnMut(&GradeProgress),
    ) -> Result<Report, GradeError> {
        pipeline::grade_source(self, source, display, opts, progress)
    }

    fn mistake_ids(&self) -> Vec<&'static str> {
        Spec::mistakes(self).into_iter().map(|(id, _)| id).collect()
    }

    fn uncaught_mistakes(&self) -> Result<Vec<&'static str>, GradeError> {
        pipeline::uncaught_mistakes(self)
    }

    fn misdiagnosed_mistakes(
        &self,
    ) -> Result<Vec<(&'static str, Option<&'static str>)>, GradeError> {
        pipeline::misdiagnosed_mistakes(self)
    }
}
