//! The plain backend: `rustc -O` on the generated `main.rs` beside the learner's file, in
//! `<cache>/<name>-<key>/`.

use std::path::Path;
use std::process::{Command, Stdio};
use std::time::Instant;

use super::{Build, Program, Source, key};
use crate::error::GradeError;

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
    failed: impl Fn(&str, &str, &Program, &str) -> Build,
) -> Result<Build, GradeError> {
    let mut parts = vec![source.main.as_str(), learner];
    parts.extend(source.files.iter().map(|(_, text)| *text));
    let dir = cache.join(format!("{name}-{}", key(&parts)));
    let program = Program {
        binary: dir.join(format!("harness{}", std::env::consts::EXE_SUFFIX)),
        learner_path: "learner.rs".into(),
    };
    if program.binary.is_file() {
        return Ok(Build::Ready(program));
    }
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
    if out.status.success() {
        std::fs::rename(dir.join(&unique), &program.binary).map_err(cache_err)?;
        return Ok(Build::Ready(program));
    }
    let stderr = String::from_utf8_lossy(&out.stderr);
    Ok(failed(&stderr, "main.rs", &program, "rustc"))
}
