//! The learner's program for `ppo_losses`: a small cargo project in the grading cache.
//!
//! The learner's file uses candle, so it cannot be built with a bare `rustc` like the
//! plain exercises. The grader keeps one cargo project, `<cache>/ppo_losses/`, depending on
//! the candle-core and candle-nn versions ppo-tutor itself uses (its `Cargo.lock` is copied
//! in, so the same versions build offline from cargo's download cache). Each learner file
//! becomes one binary target, `src/bin/l<hash>/` (`main.rs`, the learner's file as
//! `learner.rs`, and [`protocol`](super::protocol) copied as text), built with
//! `cargo build --release` into the project's own target folder:
//!
//! - the first build compiles candle (minutes); later builds compile only the learner's
//!   small crate and link it (seconds); an unchanged file is not rebuilt at all;
//! - distinct files never overwrite each other, so graders running at the same time (the
//!   tutor and the command line, parallel tests) are safe: cargo locks the target folder.
//!
//! The program answers one request per line; [`Session`] drives it with a time limit on
//! every answer and reports a panic, an error, a crash or a hang like the plain harness.

use std::hash::{Hash, Hasher};
use std::io::{BufRead, BufReader, Read, Write};
use std::path::{Path, PathBuf};
use std::process::{Child, ChildStdin, Command, Stdio};
use std::sync::mpsc::{Receiver, RecvTimeoutError};
use std::time::Duration;

use super::protocol::{Inputs, Reply};
use crate::grade::GradeError;

/// The evaluation code both sides share, copied next to the learner's file.
const PROTOCOL: &str = include_str!("protocol.rs");
/// ppo-tutor's manifest, for the candle versions to depend on.
const MANIFEST: &str = include_str!("../../../Cargo.toml");
/// ppo-tutor's lock file: the project builds the very versions ppo-tutor was tested with.
const LOCK: &str = include_str!("../../../Cargo.lock");
/// The folder of the project inside the grading cache.
const PROJECT: &str = "ppo_losses";
/// How many learner programs the project keeps (older ones are deleted).
const KEEP: usize = 16;

/// The program's `main.rs`: the learner's function through a pointer of the exercise's
/// exact type (a mismatch is a compile error located here), served over stdin/stdout.
const MAIN: &str = r#"#![allow(warnings)]
#[path = "learner.rs"]
mod learner;
#[path = "protocol.rs"]
mod protocol;

fn main() {
    let losses: protocol::LossesFn = learner::ppo_losses;
    protocol::serve(losses);
}
"#;

/// The outcome of building the learner's program.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Build {
    /// The program.
    Ready(Program),
    /// The learner's file does not compile: a one-line summary and the compiler's errors.
    Failed {
        /// What went wrong, in one sentence.
        summary: String,
        /// The compiler's output, with the learner's path.
        compiler: String,
    },
}

/// A built learner program and the path its messages use for the learner's file.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Program {
    /// The executable.
    pub binary: PathBuf,
    /// The learner's file as the compiler names it (`src/bin/l<hash>/learner.rs`).
    pub learner_path: String,
}

impl Program {
    /// `text` with the program's name for the learner's file replaced by `display`.
    #[must_use]
    pub fn rename(&self, text: &str, display: &str) -> String {
        text.replace(&self.learner_path, display)
    }
}

/// The `cargo` to use: `$CARGO` (set when ppo-tutor runs under cargo), else `cargo`.
#[must_use]
pub fn cargo() -> PathBuf {
    std::env::var_os("CARGO").map_or_else(|| PathBuf::from("cargo"), PathBuf::from)
}

/// The project's folder inside the grading cache `cache`.
#[must_use]
pub fn project_dir(cache: &Path) -> PathBuf {
    cache.join(PROJECT)
}

/// Whether the next build compiles candle from scratch (minutes rather than seconds).
#[must_use]
pub fn first_build_pending(cache: &Path) -> bool {
    let deps = project_dir(cache).join("target/release/deps");
    std::fs::read_dir(deps).map_or(true, |entries| {
        !entries.filter_map(Result::ok).any(|e| {
            let name = e.file_name();
            let name = name.to_string_lossy();
            name.starts_with("libcandle_nn") && name.ends_with(".rlib")
        })
    })
}

fn hash_key(parts: &[&str]) -> String {
    let mut h = std::hash::DefaultHasher::new();
    env!("CARGO_PKG_VERSION").hash(&mut h);
    for p in parts {
        p.hash(&mut h);
    }
    format!("{:016x}", h.finish())
}

/// `dependencies.<name>` of ppo-tutor's manifest, as TOML text (`"0.11"`).
fn dependency(name: &str) -> Option<String> {
    let manifest: toml::Table = MANIFEST.parse().ok()?;
    let spec = manifest.get("dependencies")?.get(name)?;
    Some(spec.to_string())
}

/// The project's `Cargo.toml`.
///
/// # Errors
/// When ppo-tutor's own manifest names no candle dependency (a broken build).
pub fn manifest() -> Result<String, String> {
    let core = dependency("candle-core").ok_or("ppo-tutor's Cargo.toml has no candle-core")?;
    let nn = dependency("candle-nn").ok_or("ppo-tutor's Cargo.toml has no candle-nn")?;
    Ok(format!(
        "# Written by ppo-tutor to grade the ppo_losses exercise; rewritten as needed.\n\
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

/// Builds (or finds) the program around `learner`, the learner's source; `display` is the
/// learner's path for messages.
///
/// # Errors
/// [`GradeError::Cache`] if the project cannot be written, [`GradeError::NoCargo`] if
/// cargo cannot be started, [`GradeError::Cargo`] if cargo fails for a reason other than
/// the learner's code (no network for the first build, say).
pub fn build(learner: &str, display: &str, cache: &Path) -> Result<Build, GradeError> {
    let dir = project_dir(cache);
    let cache_err = |e: std::io::Error| GradeError::Cache {
        dir: dir.clone(),
        reason: e.to_string(),
    };
    let manifest = manifest().map_err(|reason| GradeError::Cache {
        dir: dir.clone(),
        reason,
    })?;
    let name = format!("l{}", hash_key(&[MAIN, PROTOCOL, &manifest, learner]));
    let program = Program {
        binary: dir
            .join("target/release")
            .join(format!("{name}{}", std::env::consts::EXE_SUFFIX)),
        learner_path: format!("src/bin/{name}/learner.rs"),
    };
    if program.binary.is_file() {
        return Ok(Build::Ready(program));
    }
    let src = dir.join("src/bin").join(&name);
    std::fs::create_dir_all(&src).map_err(cache_err)?;
    write_if_changed(&dir.join("Cargo.toml"), &manifest).map_err(cache_err)?;
    let lock_key = hash_key(&[LOCK]);
    let stamp = dir.join("Cargo.lock.source");
    if std::fs::read_to_string(&stamp).map_or(true, |k| k != lock_key) {
        write_if_changed(&dir.join("Cargo.lock"), LOCK).map_err(cache_err)?;
        write_if_changed(&stamp, &lock_key).map_err(cache_err)?;
    }
    write_if_changed(&src.join("main.rs"), MAIN).map_err(cache_err)?;
    write_if_changed(&src.join("protocol.rs"), PROTOCOL).map_err(cache_err)?;
    write_if_changed(&src.join("learner.rs"), learner).map_err(cache_err)?;
    let cargo = cargo();
    let out = Command::new(&cargo)
        .current_dir(&dir)
        .args(["build", "--release", "--quiet", "--color", "never", "--bin"])
        .arg(&name)
        .arg("--target-dir")
        .arg(dir.join("target"))
        .stdin(Stdio::null())
        .output()
        .map_err(|e| GradeError::NoCargo {
            cargo: cargo.clone(),
            reason: e.to_string(),
        })?;
    let stderr = String::from_utf8_lossy(&out.stderr);
    if out.status.success() && program.binary.is_file() {
        prune(&dir, &name);
        return Ok(Build::Ready(program));
    }
    let ours = format!("src/bin/{name}/");
    if !stderr.contains(&ours) {
        let tail: Vec<&str> = stderr.trim_end().lines().rev().take(20).collect();
        let tail: Vec<&str> = tail.into_iter().rev().collect();
        return Err(GradeError::Cargo {
            dir,
            message: tail.join("\n"),
        });
    }
    Ok(Build::Failed {
        summary: summarize(&stderr, &format!("{ours}main.rs"), display),
        compiler: program.rename(&stderr, display),
    })
}

/// One sentence for a failed build: the learner's own errors, or a missing, private or
/// mistyped `ppo_losses` (errors in `main.rs`, where the function is taken).
fn summarize(stderr: &str, main: &str, display: &str) -> String {
    let signature = super::SIGNATURE;
    if !stderr.contains(main) {
        return format!("{display} does not compile (the compiler's errors below)");
    }
    if stderr.contains("E0425") || stderr.contains("cannot find function `ppo_losses`") {
        format!("{display} has no function `ppo_losses`: write `{signature}`")
    } else if stderr.contains("E0603") {
        format!("`ppo_losses` in {display} is private: declare it `{signature}`")
    } else {
        format!("`ppo_losses` in {display} does not have the exercise's signature: `{signature}`")
    }
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

/// What the learner's function did on one request.
#[derive(Debug, Clone, PartialEq)]
pub enum Answer {
    /// Both losses and their gradients.
    Reply(Reply),
    /// It returned an error, or a loss that is not a scalar.
    Error(String),
    /// It panicked (message and place).
    Panicked(String),
    /// No answer within the time limit (seconds); the program was killed.
    TimedOut(u64),
    /// The program died (stack overflow, `process::exit`, ...) or answered nonsense.
    Crashed(String),
    /// Not asked: the program had already stopped.
    NotRun,
}

/// A running learner program.
#[derive(Debug)]
pub struct Session {
    child: Child,
    stdin: Option<ChildStdin>,
    lines: Receiver<String>,
    stderr: Option<std::thread::JoinHandle<String>>,
    program: Program,
    display: String,
    stopped: bool,
}

impl Session {
    /// Starts `program`; `display` replaces its name for the learner's file in messages.
    ///
    /// # Errors
    /// [`GradeError::Run`] if it cannot be started.
    pub fn start(program: &Program, display: &str) -> Result<Self, GradeError> {
        let mut child = Command::new(&program.binary)
            .env("RAYON_NUM_THREADS", "1")
            .env("RUST_BACKTRACE", "0")
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .map_err(|e| GradeError::Run {
                binary: program.binary.clone(),
                reason: e.to_string(),
            })?;
        let (tx, lines) = std::sync::mpsc::channel();
        if let Some(stdout) = child.stdout.take() {
            std::thread::spawn(move || {
                for line in BufReader::new(stdout).lines().map_while(Result::ok) {
                    if tx.send(line).is_err() {
                        return;
                    }
                }
            });
        }
        let stderr = child.stderr.take().map(|mut s| {
            std::thread::spawn(move || {
                let mut text = String::new();
                let _ = s.read_to_string(&mut text);
                text
            })
        });
        Ok(Self {
            stdin: child.stdin.take(),
            child,
            lines,
            stderr,
            program: program.clone(),
            display: display.to_string(),
            stopped: false,
        })
    }

    /// Whether the program has stopped (timed out, crashed): later questions are not asked.
    #[must_use]
    pub fn is_stopped(&self) -> bool {
        self.stopped
    }

    /// Asks for the losses on `inputs`, waiting at most `limit` for the answer.
    pub fn ask(&mut self, inputs: &Inputs, limit: Duration) -> Answer {
        if self.stopped {
            return Answer::NotRun;
        }
        let sent = self.stdin.as_mut().is_some_and(|stdin| {
            writeln!(stdin, "{}", inputs.encode())
                .and_then(|()| stdin.flush())
                .is_ok()
        });
        let line = if sent {
            self.lines.recv_timeout(limit)
        } else {
            Err(RecvTimeoutError::Disconnected)
        };
        match line {
            Ok(line) => self.parse(&line, inputs.len()),
            Err(RecvTimeoutError::Timeout) => {
                self.stop();
                Answer::TimedOut(limit.as_secs().max(1))
            }
            Err(RecvTimeoutError::Disconnected) => {
                let status = self.stop();
                let stderr = self
                    .stderr
                    .take()
                    .and_then(|h| h.join().ok())
                    .unwrap_or_default();
                let stderr = self.program.rename(stderr.trim(), &self.display);
                let last = stderr.lines().last().unwrap_or("no message");
                Answer::Crashed(format!("the program stopped ({status}): {last}"))
            }
        }
    }

    fn parse(&self, line: &str, n: usize) -> Answer {
        let rename = |m: &str| self.program.rename(m, &self.display);
        if let Some(payload) = line.strip_prefix("ok ") {
            Reply::decode(payload, n).map_or_else(
                || Answer::Crashed(format!("unreadable answer '{line}'")),
                Answer::Reply,
            )
        } else if let Some(m) = line.strip_prefix("error ") {
            Answer::Error(rename(m))
        } else if let Some(m) = line.strip_prefix("panic ") {
            Answer::Panicked(rename(m))
        } else {
            Answer::Crashed(format!("unexpected output '{line}'"))
        }
    }

    /// Kills the program (if still running) and says how it ended.
    fn stop(&mut self) -> String {
        self.stopped = true;
        self.stdin = None;
        let _ = self.child.kill();
        self.child
            .wait()
            .map_or_else(|e| e.to_string(), |s| s.to_string())
    }
}

impl Drop for Session {
    fn drop(&mut self) {
        if !self.stopped {
            self.stop();
        }
    }
}
