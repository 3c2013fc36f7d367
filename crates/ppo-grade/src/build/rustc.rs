//! The plain backend: `rustc -O` on the generated `main.rs` beside the learner's file, in
//! `<cache>/<name>-<key>/`; the exercise's builds beyond the [`KEEP`](super::KEEP) most recently used
//! are deleted after each build.

use std::path::Path;
use std::process::{Command, Stdio};
use std::time::Instant;

use super::{Build, Program, Source, excess, is_key, key, mark_used};
use crate::error::GradeError;
use crate::progress::GradeProgress;

/// The `rustc` to use: `$RUSTC`, else `rustc` on the `PATH`.
#[must_use]
pub fn rustc() -> std::path::PathBuf {
    std::env::var_os("RUSTC").map_or_else(|| "rustc".into(), Into::into)
}

pub(super) fn build(
    name: &str,
    source: &Source,
    learner: &str,
    cache: &Path,
    progress: &mut dyn FnMut(&GradeProgress),
    failed: impl Fn(&str, &str, &Program, &str) -> Build,
) -> Result<Build, GradeError> {
    let mut parts = vec![source.main.as_str(), learner];
    parts.extend(source.files.iter().map(|(_, text)| *text));
    let folder = format!("{name}-{}", key(&parts));
    let dir = cache.join(&folder);
    let program = Program {
        binary: dir.join(format!("harness{}", std::env::consts::EXE_SUFFIX)),
        learner_path: "learner.rs".into(),
    };
    if program.binary.is_file() {
        mark_used(&dir);
        return Ok(Build::Ready(program));
    }
    progress(&GradeProgress::Building {
        first_time: false,
        dir: dir.clone(),
    });
    let cache_err = |e: std::io::Error| GradeError::Cache {
        dir: dir.clone(),
        reason: crate::error::reason(&e),
    };
    std::fs::create_dir_all(&dir).map_err(cache_err)?;
    std::fs::write(dir.join("main.rs"), &source.main).map_err(cache_err)?;
    std::fs::write(dir.join("learner.rs"), learner).map_err(cache_err)?;
    for (file, text) in &source.files {
        std::fs::write(dir.join(file), text).map_err(cache_err)?;
    }
    // Built under a unique name, then renamed: a concurrent grader never runs half a file.
    let unique = format!(
        "build-{}-{}{}",
        std::process::id(),
        key(&[&format!("{:?}", Instant::now())]),
        std::env::consts::EXE_SUFFIX
    );
    let rustc = rustc();
    let out = Command::new(&rustc)
        .current_dir(&dir)
        .args(["--edition", "2021", "-O", "-C", "overflow-checks=on"])
        // Without the standard library's debug information: 0.5 MB instead of 4.3 MB
        // (panic messages keep their file and line).
        .args(["-C", "strip=debuginfo"])
        .args([
            "-A",
            "warnings",
            "--crate-type",
            "bin",
            "--crate-name",
            "harness",
        ])
        .args(["main.rs", "-o"])
        .arg(&unique)
        .stdin(Stdio::null())
        .output()
        .map_err(|e| GradeError::NoRustc {
            rustc: rustc.clone(),
            reason: crate::error::reason(&e),
        })?;
    mark_used(&dir);
    prune(cache, name, &folder);
    if out.status.success() {
        std::fs::rename(dir.join(&unique), &program.binary).map_err(cache_err)?;
        return Ok(Build::Ready(program));
    }
    let stderr = String::from_utf8_lossy(&out.stderr);
    Ok(failed(&stderr, "main.rs", &program, "rustc"))
}

/// Deletes exercise `name`'s builds in `cache` beyond the [`KEEP`](super::KEEP) most recently used
/// (never `current`), quietly: a program another grader was about to run is at worst
/// built again.
fn prune(cache: &Path, name: &str, current: &str) {
    let prefix = format!("{name}-");
    let ours = |folder: &str| folder.strip_prefix(&prefix).is_some_and(is_key);
    for folder in excess(cache, current, ours) {
        let _ = std::fs::remove_dir_all(cache.join(folder));
    }
}
