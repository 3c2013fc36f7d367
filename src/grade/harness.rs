//! Compiling and running the learner's plain-Rust file.
//!
//! The grader writes a small program (the harness) that declares the learner's file as a
//! module, reads one case per line on stdin, calls the exercise's function through a
//! function pointer of the exact signature, and prints one line per case: `ok <result>` or
//! `panic <message>` (panics are caught per case). It is built with `rustc -O` into a cache
//! folder keyed by the sources' hash, so grading an unchanged file again skips the build.
//! The run has a time limit; a harness still running then is killed.

use std::hash::{Hash, Hasher};
use std::io::{BufRead, BufReader, Read, Write};
use std::path::{Path, PathBuf};
use std::process::{Command, ExitStatus, Stdio};
use std::time::{Duration, Instant};

use super::GradeError;
use super::catalog::Spec;

/// The harness's name for the learner's file (rewritten to the real path in messages).
const LEARNER: &str = "learner.rs";

/// The outcome of building a harness.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Build {
    /// The harness binary.
    Ready(PathBuf),
    /// rustc refused: a one-line summary and rustc's errors (paths are the learner's).
    Failed {
        /// What went wrong, in one sentence.
        summary: String,
        /// rustc's output.
        compiler: String,
    },
}

/// What a harness run printed.
#[derive(Debug, Clone)]
pub struct Run {
    /// stdout, one entry per case answered.
    pub lines: Vec<String>,
    /// stderr (cut to its last 4000 characters).
    pub stderr: String,
    /// The exit status; `None` when it was killed at the time limit.
    pub status: Option<ExitStatus>,
}

const PRELUDE: &str = r#"#![allow(warnings)]
#[path = "learner.rs"]
mod learner;

use std::io::{BufRead, Write};

struct Fields<'a>(std::str::SplitWhitespace<'a>);

impl Fields<'_> {
    fn token<T: std::str::FromStr>(&mut self) -> T {
        match self.0.next().map(str::parse) {
            Some(Ok(v)) => v,
            _ => {
                eprintln!("ppo-tutor harness: malformed case");
                std::process::exit(3)
            }
        }
    }
}

trait Dec: Sized {
    fn dec(f: &mut Fields<'_>) -> Self;
}
impl Dec for f32 { fn dec(f: &mut Fields<'_>) -> Self { f.token() } }
impl Dec for f64 { fn dec(f: &mut Fields<'_>) -> Self { f.token() } }
impl Dec for usize { fn dec(f: &mut Fields<'_>) -> Self { f.token() } }
impl Dec for bool { fn dec(f: &mut Fields<'_>) -> Self { f.token::<u8>() != 0 } }
impl Dec for [f32; 2] { fn dec(f: &mut Fields<'_>) -> Self { [f.token(), f.token()] } }
impl<T: Dec> Dec for Vec<T> {
    fn dec(f: &mut Fields<'_>) -> Self {
        let n: usize = f.token();
        (0..n).map(|_| T::dec(f)).collect()
    }
}

trait Enc { fn enc(&self) -> String; }
impl Enc for f32 { fn enc(&self) -> String { format!("{:?}", self) } }
impl Enc for f64 { fn enc(&self) -> String { format!("{:?}", self) } }
impl Enc for usize { fn enc(&self) -> String { self.to_string() } }
impl<T: Enc> Enc for Vec<T> {
    fn enc(&self) -> String {
        let mut s = self.len().to_string();
        for x in self { s.push(' '); s.push_str(&x.enc()); }
        s
    }
}

fn main() {
    let message = std::sync::Arc::new(std::sync::Mutex::new(String::new()));
    let slot = message.clone();
    std::panic::set_hook(Box::new(move |info| {
        let payload = info.payload();
        let text = payload
            .downcast_ref::<&str>()
            .map(|s| s.to_string())
            .or_else(|| payload.downcast_ref::<String>().cloned())
            .unwrap_or_else(|| "a panic without a message".to_string());
        let place = info
            .location()
            .map(|l| format!(" (at {}:{}:{})", l.file(), l.line(), l.column()))
            .unwrap_or_default();
        if let Ok(mut m) = slot.lock() {
            *m = format!("{text}{place}");
        }
    }));
    let stdin = std::io::stdin();
    let stdout = std::io::stdout();
    let mut out = stdout.lock();
    for line in stdin.lock().lines() {
        let Ok(line) = line else { break };
        let mut fields = Fields(line.split_whitespace());
        let result = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| case(&mut fields)));
        let text = match result {
            Ok(s) => format!("ok {s}"),
            Err(_) => {
                let m = message.lock().map(|m| m.replace('\n', " ")).unwrap_or_default();
                format!("panic {m}")
            }
        };
        if writeln!(out, "{text}").and_then(|_| out.flush()).is_err() {
            break;
        }
    }
}
"#;

/// The harness's source for `spec`.
#[must_use]
pub fn source(spec: &Spec) -> String {
    let mut body = String::from("\nfn case(f: &mut Fields<'_>) -> String {\n");
    let mut types = Vec::new();
    let mut args = Vec::new();
    for (i, (_, kind)) in spec.params.iter().enumerate() {
        body.push_str(&format!(
            "    let a{i}: {} = Dec::dec(f);\n",
            kind.rust_owned()
        ));
        types.push(kind.rust_param());
        args.push(if kind.is_slice() {
            format!("&a{i}")
        } else {
            format!("a{i}")
        });
    }
    body.push_str(&format!(
        "    let function: fn({}) -> {} = learner::{};\n    function({}).enc()\n}}\n",
        types.join(", "),
        spec.output.rust(),
        spec.name,
        args.join(", ")
    ));
    format!("{PRELUDE}{body}")
}

/// The `rustc` to use: `$RUSTC`, else `rustc` on the `PATH`.
#[must_use]
pub fn rustc() -> PathBuf {
    std::env::var_os("RUSTC").map_or_else(|| PathBuf::from("rustc"), PathBuf::from)
}

fn cache_key(parts: &[&str]) -> String {
    let mut h = std::hash::DefaultHasher::new();
    env!("CARGO_PKG_VERSION").hash(&mut h);
    for p in parts {
        p.hash(&mut h);
    }
    format!("{:016x}", h.finish())
}

/// Builds (or finds in the cache) the harness for `spec` around `learner`, the learner's
/// source. `display` is the path shown in compiler messages.
///
/// # Errors
/// [`GradeError::Cache`] if the cache folder cannot be written; [`GradeError::NoRustc`] if
/// rustc cannot be started.
pub fn build(spec: &Spec, learner: &str, display: &str, cache: &Path) -> Result<Build, GradeError> {
    let harness = source(spec);
    let dir = cache.join(format!("{}-{}", spec.name, cache_key(&[&harness, learner])));
    let binary = dir.join(format!("harness{}", std::env::consts::EXE_SUFFIX));
    if binary.is_file() {
        return Ok(Build::Ready(binary));
    }
    let cache_err = |e: std::io::Error| GradeError::Cache {
        dir: dir.clone(),
        reason: e.to_string(),
    };
    std::fs::create_dir_all(&dir).map_err(cache_err)?;
    std::fs::write(dir.join("main.rs"), harness).map_err(cache_err)?;
    std::fs::write(dir.join(LEARNER), learner).map_err(cache_err)?;
    let unique = format!(
        "build-{}-{}{}",
        std::process::id(),
        cache_key(&[&format!("{:?}", Instant::now())]),
        std::env::consts::EXE_SUFFIX
    );
    let rustc = rustc();
    let out = Command::new(&rustc)
        .current_dir(&dir)
        .args([
            "--edition",
            "2021",
            "-O",
            "-C",
            "overflow-checks=on",
            "-A",
            "warnings",
        ])
        .args([
            "--crate-type",
            "bin",
            "--crate-name",
            "harness",
            "main.rs",
            "-o",
        ])
        .arg(&unique)
        .stdin(Stdio::null())
        .output()
        .map_err(|e| GradeError::NoRustc {
            rustc: rustc.clone(),
            reason: e.to_string(),
        })?;
    if out.status.success() {
        std::fs::rename(dir.join(&unique), &binary).map_err(cache_err)?;
        return Ok(Build::Ready(binary));
    }
    let stderr = String::from_utf8_lossy(&out.stderr);
    Ok(Build::Failed {
        summary: summarize(spec, &stderr, display),
        compiler: rename_learner(&stderr, display),
    })
}

/// One sentence for a failed build: the learner's own errors, or a signature mismatch
/// (errors in the harness's `main.rs`, where the function is called).
fn summarize(spec: &Spec, stderr: &str, display: &str) -> String {
    let signature = spec.signature();
    if !stderr.contains("--> main.rs") {
        return format!("{display} does not compile (rustc's errors below)");
    }
    let name = spec.name;
    if stderr.contains("E0425") || stderr.contains(&format!("cannot find function `{name}`")) {
        format!("{display} has no function `{name}`: write `{signature}`")
    } else if stderr.contains("E0603") {
        format!("`{name}` in {display} is private: declare it `{signature}`")
    } else {
        format!("`{name}` in {display} does not have the exercise's signature: `{signature}`")
    }
}

/// Runs `binary` on `input` (one case per line) for at most `limit`.
///
/// # Errors
/// [`GradeError::Run`] if the harness cannot be started.
pub fn run(binary: &Path, input: String, limit: Duration) -> Result<Run, GradeError> {
    let run_err = |e: std::io::Error| GradeError::Run {
        binary: binary.to_path_buf(),
        reason: e.to_string(),
    };
    let mut child = Command::new(binary)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .map_err(run_err)?;
    let stdin = child.stdin.take();
    let writer = std::thread::spawn(move || {
        if let Some(mut stdin) = stdin {
            let _ = stdin.write_all(input.as_bytes());
        }
    });
    let stdout = child.stdout.take();
    let reader = std::thread::spawn(move || {
        stdout.map_or_else(Vec::new, |s| {
            BufReader::new(s).lines().map_while(Result::ok).collect()
        })
    });
    let stderr = child.stderr.take();
    let errors = std::thread::spawn(move || {
        let mut text = String::new();
        if let Some(mut s) = stderr {
            let _ = s.read_to_string(&mut text);
        }
        text
    });
    let deadline = Instant::now() + limit;
    let status = loop {
        match child.try_wait().map_err(run_err)? {
            Some(status) => break Some(status),
            None if Instant::now() >= deadline => {
                let _ = child.kill();
                let _ = child.wait();
                break None;
            }
            None => std::thread::sleep(Duration::from_millis(5)),
        }
    };
    let _ = writer.join();
    let lines = reader.join().unwrap_or_default();
    let stderr = errors.join().unwrap_or_default();
    let mut cut = stderr.len().saturating_sub(4000);
    while !stderr.is_char_boundary(cut) {
        cut += 1;
    }
    let stderr = stderr[cut..].to_string();
    Ok(Run {
        lines,
        stderr,
        status,
    })
}

/// Replaces the harness's name for the learner's file with the real path.
#[must_use]
pub fn rename_learner(text: &str, display: &str) -> String {
    text.replace(&format!("{LEARNER}:"), &format!("{display}:"))
}
