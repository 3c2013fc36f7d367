//! The `lessons/` folder, embedded in the binary: the files every other lesson module reads
//! (the loader, the quizzes, the exercises' starters), so none of them depends on another
//! to reach a file.

use include_dir::{Dir, include_dir};

static LESSONS: Dir<'static> = include_dir!("$CARGO_MANIFEST_DIR/../../lessons");

/// A file embedded from `lessons/`, by its path under that folder (for example
/// `07-td-target/exercise.rs`), as text.
#[must_use]
pub fn embedded_file(path: &str) -> Option<&'static str> {
    LESSONS.get_file(path).and_then(|f| f.contents_utf8())
}

/// The lesson folders under `lessons/` (for example `07-td-target`), in course order.
#[must_use]
pub fn lesson_dirs() -> Vec<String> {
    let mut dirs: Vec<String> = LESSONS
        .dirs()
        .filter_map(|d| d.path().file_name()?.to_str().map(str::to_string))
        .collect();
    dirs.sort();
    dirs
}

/// The embedded folder itself, for the loader's walk over every lesson's files.
pub(crate) fn root() -> &'static Dir<'static> {
    &LESSONS
}
