//! The candle backend: a cargo project in the grading cache, `<cache>/<name>/`.
//!
//! Code that uses candle cannot be built with a bare `rustc`. The project depends on the
//! candle-core and candle-nn versions ppo-tutor itself uses (its `Cargo.lock` is copied in,
//! so the same versions build offline from cargo's download cache). Each learner file
//! becomes one binary target, `src/bin/l<key>/` (`main.rs`, the learner's file as
//! `learner.rs`, and the support files), built with `cargo build --release` into the
//! project's own target folder:
//!
//! - the first build compiles candle (minutes); later builds compile only the learner's
//!   small crate and link it (seconds); an unchanged file is not rebuilt at all;
//! - distinct files never overwrite each other, so graders running at the same time (the
//!   tutor and the command line, parallel tests) are safe: cargo locks the target folder.

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

use super::{Build, Program, Source, key};
use crate::error::GradeError;

/// ppo-tutor's manifest, for the candle versions to depend on.
const MANIFEST: &str = include_str!("../../Cargo.toml");
/// ppo-tutor's lock file: the project builds the very versions ppo-tutor was tested with.
const LOCK: &str = include_str!("../../../../Cargo.lock");
/// How many learner programs the project keeps (older ones are deleted).
const KEEP: usize = 16;

/// The `cargo` to use: `$CARGO` (set when ppo-tutor runs under cargo), else `cargo`.
#[must_use]
pub fn cargo() -> PathBuf {
    std::env::var_os("CARGO").map_or_else(|| PathBuf::from("cargo"), PathBuf::from)
}

/// The project's folder inside the grading cache `cache`, for exercise `name`.
#[must_use]
pub fn project_dir(name: &str, cache: &Path) -> PathBuf {
    cache.join(name)
}

/// Whether the next build compiles candle from scratch (minutes rather than seconds).
#[must_use]
pub fn first_build_pending(name: &str, cache: &Path) -> bool {
    let deps = project_dir(name, cache).join("target/release/deps");
    std::fs::read_dir(deps).map_or(true, |entries| {
        !entries.filter_map(Result::ok).any(|e| {
            let name = e.file_name();
            let name = name.to_string_lossy();
            name.starts_with("libcandle_nn") && name.ends_with(".rlib")
        })
    })
}

/// `dependencies.<name>` of ppo-tutor's manifest, as TOML text (`"0.11"`).
fn dependency(name: &str) -> Option<String> {
    let manifest: toml::Table = MANIFEST.parse().ok()?;
    let spec = manifest.get("dependencies")?.get(name)?;
    Some(spec.to_string())
}

/// The project's `Cargo.toml`, for exercise `name`.
///
/// # Errors
/// When ppo-tutor's own manifest names no candle dependency (a broken build).
pub fn manifest(name: &str) -> Result<String, crate::i18n::Text> {
    let missing = |dep| {
        crate::text!(
            "ppo-tutor's Cargo.toml has no {dep}",
            "ppo-tutor 的 Cargo.toml 里没有 {dep}"
        )
    };
    let core = dependency("candle-core").ok_or_else(|| missing("candle-core"))?;
    let nn = dependency("candle-nn").ok_or_else(|| missing("candle-nn"))?;
    Ok(format!(
        "# Written by ppo-tutor to grade the {name} exercise; rewritten as needed.\n\
         [package]\nname = \"ppo-tutor-grader\"\nversion = \"0.0.0\"\nedition = \"2021\"\n\
         publish = false\n\n\
         [dependencies]\ncandle-core = {core}\ncandle-nn = {nn}\n\n\
         # Not part of any workspace around the cache folder.\n[workspace]\n"
    ))
}

/// Writes `text` to `path` unless it already holds it (keeping cargo's timestamps), via a
/// temporary file so a concurrent reader never sees half a file.
fn write_if_changed(path: &Path, text: &str) -> std::io::Result<()> {
    if std::fs::read_to_string(path).is_ok_and(|old| old == text) {
        return Ok(());
    }
    let tmp = path.with_extension(format!("tmp{}", std::process::id()));
    std::fs::write(&tmp, text)?;
    std::fs::rename(&tmp, path)
}

/// Builds (or finds) the program `source` around `learner` in exercise `name`'s project.
pub(super) fn build(
    name: &str,
    source: &Source,
    learner: &str,
    cache: &Path,
    failed: impl Fn(&str, &str, &Program, &str) -> Build,
) -> Result<Build, GradeError> {
    let dir = project_dir(name, cache);
    let cache_err = |e: std::io::Error| GradeError::Cache {
        dir: dir.clone(),
        reason: crate::error::reason(&e),
    };
    let manifest = manifest(name).map_err(|reason| GradeError::Cache {
        dir: dir.clone(),
        reason,
    })?;
    let mut parts = vec![source.main.as_str(), &manifest, learner];
    parts.extend(source.files.iter().map(|(_, text)| *text));
    let bin = format!("l{}", key(&parts));
    let program = Program {
        binary: dir
            .join("target/release")
            .join(format!("{bin}{}", std::env::consts::EXE_SUFFIX)),
        learner_path: format!("src/bin/{bin}/learner.rs"),
    };
    if program.binary.is_file() {
        return Ok(Build::Ready(program));
    }
    let src = dir.join("src/bin").join(&bin);
    std::fs::create_dir_all(&src).map_err(cache_err)?;
    write_if_changed(&dir.join("Cargo.toml"), &manifest).map_err(cache_err)?;
    let lock_key = key(&[LOCK]);
    let stamp = dir.join("Cargo.lock.source");
    if std::fs::read_to_string(&stamp).map_or(true, |k| k != lock_key) {
        write_if_changed(&dir.join("Cargo.lock"), LOCK).map_err(cache_err)?;
        write_if_changed(&stamp, &lock_key).map_err(cache_err)?;
    }
    write_if_changed(&src.join("main.rs"), &source.main).map_err(cache_err)?;
    for (file, text) in &source.files {
        write_if_changed(&src.join(file), text).map_err(cache_err)?;
    }
    write_if_changed(&src.join("learner.rs"), learner).map_err(cache_err)?;
    let cargo = cargo();
    let out = Command::new(&cargo)
        .current_dir(&dir)
        .args(["build", "--release", "--quiet", "--color", "never", "--bin"])
        .arg(&bin)
        .arg("--target-dir")
        .arg(dir.join("target"))
        .stdin(Stdio::null())
        .output()
        .map_err(|e| GradeError::NoCargo {
            cargo: cargo.clone(),
            reason: crate::error::reason(&e),
        })?;
    let stderr = String::from_utf8_lossy(&out.stderr);
    if out.status.success() && program.binary.is_file() {
        prune(&dir, &bin);
        return Ok(Build::Ready(program));
    }
    let ours = format!("src/bin/{bin}/");
    if !stderr.contains(&ours) {
        let tail: Vec<&str> = stderr.trim_end().lines().rev().take(20).collect();
        let tail: Vec<&str> = tail.into_iter().rev().collect();
        return Err(GradeError::Cargo {
            dir,
            message: tail.join("\n"),
        });
    }
    Ok(failed(
        &stderr,
        &format!("{ours}main.rs"),
        &program,
        "cargo",
    ))
}

/// Deletes all but the newest [`KEEP`] learner programs (never `current`), quietly: a
/// program another grader is still building is at worst built again.
fn prune(dir: &Path, current: &str) {
    let Ok(entries) = std::fs::read_dir(dir.join("src/bin")) else {
        return;
    };
    let mut programs: Vec<(std::time::SystemTime, String)> = entries
        .filter_map(Result::ok)
        .filter_map(|e| {
            let name = e.file_name().to_string_lossy().into_owned();
            let modified = e.metadata().and_then(|m| m.modified()).ok()?;
            (name != current && name.starts_with('l')).then_some((modified, name))
        })
        .collect();
    programs.sort();
    let excess = (programs.len() + 1).saturating_sub(KEEP);
    let release = dir.join("target/release");
    for (_, name) in programs.into_iter().take(excess) {
        let _ = std::fs::remove_dir_all(dir.join("src/bin").join(&name));
        let _ =
            std::fs::remove_file(release.join(format!("{name}{}", std::env::consts::EXE_SUFFIX)));
        let _ = std::fs::remove_file(release.join(format!("{name}.d")));
        if let Ok(deps) = std::fs::read_dir(release.join("deps")) {
            for e in deps.filter_map(Result::ok) {
                if e.file_name()
                    .to_string_lossy()
                    .starts_with(&format!("{name}-"))
                {
                    let _ = std::fs::remove_file(e.path());
                }
            }
        }
    }
}
