//! The candle backend: a cargo project in the grading cache, `<cache>/<name>/`.
//!
//! Code that uses candle cannot be built with a bare `rustc`. The project depends on the
//! candle-core and candle-nn versions ppo-tutor itself uses (its `Cargo.lock` is copied in,
//! so the same versions build offline from cargo's download cache). Each learner file
//! becomes one binary target, `src/bin/l<key>/` (`main.rs`, the learner's file as
//! `learner.rs`, and the support files), built with `cargo build --release` into the
//! project's own target folder:
//!
//! - the first build compiles candle (minutes: about 2 min 15 s of two cores, some 380 MB
//!   kept in the project's target folder); later builds compile only the learner's small
//!   crate and link it (seconds); an unchanged file is not rebuilt at all;
//! - cargo's progress (the crate it compiles, steps done of the total) is passed on as
//!   [`GradeProgress::Compiling`], read from its progress bar, which it is asked to print even
//!   though its output is a pipe;
//! - distinct files never overwrite each other, so graders running at the same time (the
//!   tutor and the command line, parallel tests) are safe: cargo locks the target folder;
//! - each build deletes the learner programs beyond the [`KEEP`](super::KEEP) most recently used (about
//!   5 MB each), so the project stays at candle's build and a few programs.

use std::io::Read;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

use super::{Build, Program, Source, excess, is_key, key, mark_used};
use crate::error::GradeError;
use crate::progress::GradeProgress;

/// ppo-tutor's manifest, for the candle versions to depend on.
const MANIFEST: &str = include_str!("../../Cargo.toml");
/// ppo-tutor's lock file: the project builds the very versions ppo-tutor was tested with.
const LOCK: &str = include_str!("../../../../Cargo.lock");

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
    progress: &mut dyn FnMut(&GradeProgress),
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
    let src = dir.join("src/bin").join(&bin);
    if program.binary.is_file() {
        mark_used(&src);
        return Ok(Build::Ready(program));
    }
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
    let first_time = first_build_pending(name, cache);
    progress(&GradeProgress::Building {
        first_time,
        dir: dir.clone(),
    });
    let cargo = cargo();
    let no_cargo = |e: std::io::Error| GradeError::NoCargo {
        cargo: cargo.clone(),
        reason: crate::error::reason(&e),
    };
    let mut child = Command::new(&cargo)
        .current_dir(&dir)
        .args(["build", "--release", "--color", "never", "--bin"])
        .arg(&bin)
        .arg("--target-dir")
        .arg(dir.join("target"))
        // cargo's progress bar (`Building [==> ] 37/120: candle-core`) even into a pipe.
        .env("CARGO_TERM_PROGRESS_WHEN", "always")
        .env("CARGO_TERM_PROGRESS_WIDTH", "100")
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .map_err(no_cargo)?;
    let mut said = Said::new(first_time);
    if let Some(err) = child.stderr.take() {
        each_line(err, |line| said.line(line, progress));
    }
    let status = child.wait().map_err(no_cargo)?;
    let stderr = said.rest.trim_matches('\n').to_string();
    mark_used(&src);
    if status.success() && program.binary.is_file() {
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

/// What cargo printed on stderr: its progress, passed on as it comes, and the rest (the
/// compiler's errors, cargo's own) kept.
struct Said {
    first_time: bool,
    /// The crate last reported compiling, and the steps done and in all.
    krate: String,
    done: usize,
    total: usize,
    last: Option<GradeProgress>,
    rest: String,
}

impl Said {
    fn new(first_time: bool) -> Self {
        Self {
            first_time,
            krate: String::new(),
            done: 0,
            total: 0,
            last: None,
            rest: String::new(),
        }
    }

    /// Takes one line (or one redraw of the progress bar).
    fn line(&mut self, line: &str, progress: &mut dyn FnMut(&GradeProgress)) {
        let word = line.trim_start();
        let next = if let Some(bar) = word.strip_prefix("Building [") {
            // `=====>   ] 37/120: candle-core, gemm(build)`
            let counts = bar.split_once("] ").map_or("", |(_, c)| c);
            let (counts, names) = counts.split_once(':').unwrap_or((counts, ""));
            if let Some((done, total)) = counts.trim().split_once('/') {
                self.done = done.parse().unwrap_or(self.done);
                self.total = total.parse().unwrap_or(self.total);
            }
            if self.krate.is_empty() {
                let first = names.split(',').next().unwrap_or("").trim();
                self.krate = first.split('(').next().unwrap_or("").to_string();
            }
            self.compiling()
        } else if let Some(what) = word.strip_prefix("Compiling ") {
            self.krate = what.split_whitespace().next().unwrap_or("").to_string();
            self.compiling()
        } else if word.starts_with("Blocking ") {
            Some(GradeProgress::Waiting)
        } else if CARGO_STATUS.iter().any(|s| word.starts_with(s)) {
            None
        } else {
            self.rest.push_str(line);
            self.rest.push('\n');
            None
        };
        if let Some(next) = next
            && self.last.as_ref() != Some(&next)
        {
            progress(&next);
            self.last = Some(next);
        }
    }

    fn compiling(&self) -> Option<GradeProgress> {
        (!self.krate.is_empty()).then(|| GradeProgress::Compiling {
            krate: self.krate.clone(),
            done: self.done.min(self.total),
            total: self.total,
            first_time: self.first_time,
        })
    }
}

/// cargo's status lines that are neither progress nor errors.
const CARGO_STATUS: [&str; 8] = [
    "Finished ",
    "Locking ",
    "Adding ",
    "Updating ",
    "Downloading ",
    "Downloaded ",
    "Fresh ",
    "Dirty ",
];

/// Calls `each` with every line of `reader`, a line ending at `\n` or at `\r` (cargo
/// redraws its progress bar after a `\r`).
fn each_line(mut reader: impl Read, mut each: impl FnMut(&str)) {
    let mut buf = [0_u8; 4096];
    let mut line = Vec::new();
    loop {
        let n = match reader.read(&mut buf) {
            Ok(0) => break,
            Ok(n) => n,
            Err(e) if e.kind() == std::io::ErrorKind::Interrupted => continue,
            Err(_) => break,
        };
        for &b in &buf[..n] {
            if b == b'\n' || b == b'\r' {
                each(&String::from_utf8_lossy(&line));
                line.clear();
            } else {
                line.push(b);
            }
        }
    }
    if !line.is_empty() {
        each(&String::from_utf8_lossy(&line));
    }
}

/// Deletes the learner programs beyond the [`KEEP`](super::KEEP) most recently used (never `current`),
/// with what cargo made of them, quietly: a program another grader is still building is at
/// worst built again.
fn prune(dir: &Path, current: &str) {
    let bins = dir.join("src/bin");
    let ours = |name: &str| name.strip_prefix('l').is_some_and(is_key);
    let release = dir.join("target/release");
    let fingerprints: Vec<PathBuf> = std::fs::read_dir(release.join(".fingerprint"))
        .map(|entries| {
            entries
                .filter_map(Result::ok)
                .map(|e| e.path())
                .filter(|p| {
                    p.file_name()
                        .is_some_and(|n| n.to_string_lossy().starts_with("ppo-tutor-grader-"))
                })
                .collect()
        })
        .unwrap_or_default();
    for name in excess(&bins, current, ours) {
        let _ = std::fs::remove_dir_all(bins.join(&name));
        let exe = format!("{name}{}", std::env::consts::EXE_SUFFIX);
        let _ = std::fs::remove_file(release.join(exe));
        let _ = std::fs::remove_file(release.join(format!("{name}.d")));
        let mine =
            |file: &str| file.starts_with(&format!("{name}-")) || file == format!("{name}.pdb");
        remove_files(&release.join("deps"), &mine);
        // cargo's record of the program: a folder of its own, which names it inside.
        let named = format!("bin-{name}");
        for folder in &fingerprints {
            let holds = std::fs::read_dir(folder).is_ok_and(|mut files| {
                files.any(|f| f.is_ok_and(|f| f.file_name().to_string_lossy().contains(&named)))
            });
            if holds {
                let _ = std::fs::remove_dir_all(folder);
            }
        }
    }
}

/// Deletes the files in `folder` whose names `mine` accepts.
fn remove_files(folder: &Path, mine: &dyn Fn(&str) -> bool) {
    let Ok(entries) = std::fs::read_dir(folder) else {
        return;
    };
    for e in entries.filter_map(Result::ok) {
        if mine(&e.file_name().to_string_lossy()) {
            let _ = std::fs::remove_file(e.path());
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cargo_s_progress_bar_and_status_lines_become_progress_and_errors_are_kept() {
        // What cargo writes into a pipe with CARGO_TERM_PROGRESS_WHEN=always (shortened).
        let stderr = "   Compiling proc-macro2 v1.0.107\n    Building [  ] 0/16: proc-macro2(…\r   \
                      Compiling quote v1.0.47\n    Building [>  ] 1/16: quote(build.rs)\r    \
                      Building [=> ] 3/16: quote\r    Blocking waiting for file lock on build directory\n\
                      error[E0308]: mismatched types\n --> src/bin/l0/learner.rs:2:5\n\n\
                      error: could not compile `ppo-tutor-grader`\n    Finished `release` profile\n";
        let mut said = Said::new(true);
        let mut seen = Vec::new();
        each_line(stderr.as_bytes(), |line| {
            said.line(line, &mut |p| seen.push(p.clone()))
        });
        let compiling = |krate: &str, done, total| GradeProgress::Compiling {
            krate: krate.into(),
            done,
            total,
            first_time: true,
        };
        assert_eq!(
            seen,
            [
                compiling("proc-macro2", 0, 0),
                compiling("proc-macro2", 0, 16),
                compiling("quote", 0, 16),
                compiling("quote", 1, 16),
                compiling("quote", 3, 16),
                GradeProgress::Waiting,
            ]
        );
        assert_eq!(
            said.rest.trim_matches('\n'),
            "error[E0308]: mismatched types\n --> src/bin/l0/learner.rs:2:5\n\n\
             error: could not compile `ppo-tutor-grader`"
        );
        assert_eq!(
            seen[4].text().in_lang(crate::i18n::Lang::En),
            "building candle (first time, ~2 min): Compiling quote (3/16)"
        );
    }
}
