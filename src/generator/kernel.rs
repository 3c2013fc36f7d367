//! Executing notebook cells on the evcxr engine, as the Jupyter kernel does (feature
//! `notebook-runner`: evcxr brings rust-analyzer's crates, so the tutor's default build
//! leaves it out).
//!
//! Two processes take part besides evcxr's own runtime:
//!
//! - evcxr re-executes the current binary as its runtime: [`runtime_hook`] must be the first
//!   call in that binary's `main` (`ppo-tutor` with the feature, `tests/notebooks.rs`);
//! - evcxr reads its work folder from `evcxr.toml` in the working directory, and
//!   `:dep ppo-engine = { path = "../crates/ppo-engine" }` resolves against that directory:
//!   [`relaunch`] re-runs the binary as a *driver* in `notebooks/` (as Jupyter would run
//!   it), candle on one thread (faster for these small networks), with this workspace's
//!   `Cargo.lock` in the work folders so the kernels build the same dependency versions. The driver ([`is_driver`]) starts a [`Kernel`] per notebook.
//!
//! A panic, a failed `assert!` or a `?` error in a cell is not an error to evcxr (the
//! Jupyter kernel replies "ok" and prints to stderr): [`Kernel::run`] fails on anything
//! written to stderr, as well as on a compile error.

use std::path::Path;
use std::process::{Command, ExitStatus};
use std::sync::{Arc, Mutex};
use std::time::Duration;

use super::build::Cell;
use super::ipynb::Outputs;

/// Marks the re-executed driver process (see [`relaunch`]).
pub const DRIVER_VAR: &str = "PPO_TUTOR_NOTEBOOK_DRIVER";

/// What can go wrong running cells.
#[derive(Debug, thiserror::Error)]
pub enum KernelError {
    /// evcxr could not start.
    #[error("starting evcxr: {0}")]
    Start(String),
    /// Preparing or starting the driver process failed.
    #[error("{what}: {source}")]
    Io {
        /// What was being done, naming the path.
        what: String,
        /// The I/O error.
        source: std::io::Error,
    },
    /// The cell does not compile.
    #[error("the cell does not compile:\n{errors}\n{stderr}")]
    Compile {
        /// The compiler's rendered errors.
        errors: String,
        /// What the runtime wrote to stderr meanwhile.
        stderr: String,
    },
    /// evcxr reported another failure.
    #[error("the cell failed: {message}\n{stderr}")]
    Failed {
        /// evcxr's message.
        message: String,
        /// What the runtime wrote to stderr meanwhile.
        stderr: String,
    },
    /// The cell ran but wrote to stderr.
    #[error("the cell wrote to stderr (a panic, failed assert or `?` error):\n{0}")]
    Stderr(String),
    /// A cell of a notebook failed (the cause is the error's source).
    #[error("{notebook}, cell {index}:\n{code}")]
    Cell {
        /// The notebook, e.g. `notebooks/07-td-target.ipynb`.
        notebook: String,
        /// The cell's index in the notebook, from 0.
        index: usize,
        /// The cell's code.
        code: String,
        /// Why it failed.
        source: Box<KernelError>,
    },
}

/// evcxr's runtime hook: in the process evcxr started as its runtime, runs the runtime and
/// exits; elsewhere returns at once. Call it first in `main`.
pub fn runtime_hook() {
    evcxr::runtime_hook();
}

/// Whether this process is the driver [`relaunch`] started.
#[must_use]
pub fn is_driver() -> bool {
    std::env::var_os(DRIVER_VAR).is_some()
}

/// Re-runs the current binary, with its arguments, as the driver: working directory
/// `root/notebooks`, `RAYON_NUM_THREADS=1`, and no `CARGO_TARGET_DIR` (evcxr finds its build
/// under its work folder's `target`; a target folder set for this project's build must not
/// redirect it).
///
/// evcxr builds in the work folder that each notebook folder's `evcxr.toml` names
/// ([`work_folder`](super::build::work_folder): `notebooks/.evcxr` and `notebooks/zh/.evcxr`,
/// the folders a user's Jupyter kernels use too), so every kernel reuses the last one's build.
/// The driver copies `root/Cargo.lock` into each, so the kernels build the same dependency
/// versions as the workspace.
///
/// The notebooks turn on evcxr's cache of compiled dependencies (`:cache`), which lives in
/// the user's cache folder. The driver keeps its own (`target/evcxr-cache`, through
/// `XDG_CACHE_HOME`), so that the cache and the build folders
/// always come from the same builds (a build folder left by older runs, filled up from a
/// cache written by other builds, failed here: the cached candle and serde did not load,
/// "can't find crate"), and the user's own kernels stay out of the tests' way.
///
/// # Errors
/// [`KernelError::Io`] when a work folder cannot be prepared or the driver cannot start,
/// [`KernelError::Start`] when an `evcxr.toml` does not name a work folder.
pub fn relaunch(root: &Path) -> Result<ExitStatus, KernelError> {
    spawn_driver(root, &[])?
        .wait()
        .map_err(|source| KernelError::Io {
            what: "waiting for the notebook driver".into(),
            source,
        })
}

/// Starts this binary again as a driver, as [`relaunch`] does, with the extra environment
/// `envs`, and returns at once: `tests/notebooks.rs` runs one driver per language side by
/// side (the two languages' notebooks have their own work folders).
///
/// # Errors
/// As [`relaunch`].
pub fn spawn_driver(
    root: &Path,
    envs: &[(&str, &str)],
) -> Result<std::process::Child, KernelError> {
    let io = |what: String| move |source| KernelError::Io { what, source };
    let ours = std::fs::read(root.join("Cargo.lock"))
        .map_err(io(format!("reading {}", root.join("Cargo.lock").display())))?;
    for dir in [root.join("notebooks"), root.join("notebooks").join("zh")] {
        let work =
            super::build::work_folder(&dir).map_err(|e| KernelError::Start(e.to_string()))?;
        std::fs::create_dir_all(&work).map_err(io(format!("creating {}", work.display())))?;
        let lock = work.join("Cargo.lock");
        if std::fs::read(&lock).ok().as_deref() != Some(ours.as_slice()) {
            std::fs::write(&lock, &ours)
                .map_err(io(format!("copying Cargo.lock to {}", lock.display())))?;
        }
    }
    let cache = root.join("target").join("evcxr-cache");
    let exe = std::env::current_exe().map_err(io("finding the current binary".into()))?;
    Command::new(&exe)
        .args(std::env::args_os().skip(1))
        .env(DRIVER_VAR, "1")
        .env("RAYON_NUM_THREADS", "1")
        .env("XDG_CACHE_HOME", cache)
        .env_remove("EVCXR_TMPDIR")
        .env_remove("CARGO_TARGET_DIR")
        .env_remove("CARGO_BUILD_TARGET_DIR")
        .envs(envs.iter().copied())
        .current_dir(root.join("notebooks"))
        .spawn()
        .map_err(io(format!("starting the driver {}", exe.display())))
}

/// A fresh evcxr context (what the Jupyter kernel uses), with its streams collected.
pub struct Kernel {
    ctx: evcxr::CommandContext,
    stdout: Arc<Mutex<String>>,
    stderr: Arc<Mutex<String>>,
}

/// Collects a kernel stream as it comes: evcxr waits for its stdout channel to be empty
/// before a cell returns, so it must be read while the cell runs.
fn collect(stream: impl IntoIterator<Item = String> + Send + 'static) -> Arc<Mutex<String>> {
    let buf = Arc::new(Mutex::new(String::new()));
    let sink = Arc::clone(&buf);
    std::thread::spawn(move || {
        for line in stream {
            if let Ok(mut b) = sink.lock() {
                b.push_str(&line);
                b.push('\n');
            }
        }
    });
    buf
}

/// Empties a collected stream.
fn take(buf: &Mutex<String>) -> String {
    buf.lock()
        .map(|mut b| std::mem::take(&mut *b))
        .unwrap_or_default()
}

impl Kernel {
    /// Starts a context with evcxr's runtime process.
    ///
    /// # Errors
    /// [`KernelError::Start`] with evcxr's reason.
    pub fn start() -> Result<Self, KernelError> {
        let (ctx, outputs) =
            evcxr::CommandContext::new().map_err(|e| KernelError::Start(e.to_string()))?;
        Ok(Self {
            ctx,
            stdout: collect(outputs.stdout),
            stderr: collect(outputs.stderr),
        })
    }

    /// Starts a context for a notebook in folder `dir` (the folder Jupyter would run it
    /// in, which its `:dep` path is relative to) whose runtime process speaks `lang`
    /// (`PPO_TUTOR_LANG`, which the library reads in every cell), whatever an earlier
    /// notebook in this process set.
    ///
    /// # Errors
    /// [`KernelError::Io`] if `dir` cannot be entered, as [`Kernel::start`], or evcxr's
    /// failure to restart its runtime.
    pub fn start_in(lang: crate::i18n::Lang, dir: &Path) -> Result<Self, KernelError> {
        std::env::set_current_dir(dir).map_err(|source| KernelError::Io {
            what: format!("entering {}", dir.display()),
            source,
        })?;
        let mut kernel = Self::start()?;
        kernel.run(&format!(":env PPO_TUTOR_LANG={}\n:restart", lang.code()))?;
        Ok(kernel)
    }

    /// Runs one cell (code or `:` command) and returns what it printed.
    ///
    /// # Errors
    /// A compile error, another evcxr failure, or anything the cell wrote to stderr.
    pub fn run(&mut self, code: &str) -> Result<Outputs, KernelError> {
        let result = self.ctx.execute(code);
        // stderr is read from the runtime process by another thread: let it catch up.
        std::thread::sleep(Duration::from_millis(100));
        let stdout = take(&self.stdout);
        let stderr = take(&self.stderr);
        let out = match result {
            Ok(out) => out,
            Err(evcxr::Error::CompilationErrors(errors)) => {
                let shown: Vec<String> = errors
                    .iter()
                    .filter(|e| e.level() == "error")
                    .map(evcxr::CompilationError::rendered)
                    .collect();
                return Err(KernelError::Compile {
                    errors: shown.join("\n"),
                    stderr,
                });
            }
            Err(e) => {
                return Err(KernelError::Failed {
                    message: e.to_string(),
                    stderr,
                });
            }
        };
        if !stderr.trim().is_empty() {
            return Err(KernelError::Stderr(stderr));
        }
        Ok(Outputs {
            stdout,
            data: out.content_by_mime_type.into_iter().collect(),
        })
    }

    /// Runs a notebook's code cells top to bottom (`notebook` names it in errors): the
    /// outputs of cell `i` at `i`, `None` for markdown cells.
    ///
    /// # Errors
    /// [`KernelError::Cell`] for the first cell that fails, with its index and code.
    pub fn run_cells(
        &mut self,
        cells: &[Cell],
        notebook: &str,
    ) -> Result<Vec<Option<Outputs>>, KernelError> {
        self.run_cells_with(cells, notebook, |_| {})
    }

    /// [`Kernel::run_cells`], calling `after(index)` once each code cell has run (and
    /// succeeded): `tests/notebooks.rs` starts its second language once the first cell of
    /// the first has built the dependencies.
    ///
    /// # Errors
    /// As [`Kernel::run_cells`].
    pub fn run_cells_with(
        &mut self,
        cells: &[Cell],
        notebook: &str,
        mut after: impl FnMut(usize),
    ) -> Result<Vec<Option<Outputs>>, KernelError> {
        let mut outputs = Vec::with_capacity(cells.len());
        for (index, cell) in cells.iter().enumerate() {
            let Cell::Code(code) = cell else {
                outputs.push(None);
                continue;
            };
            let out = self.run(code).map_err(|source| KernelError::Cell {
                notebook: notebook.to_string(),
                index,
                code: code.clone(),
                source: Box::new(source),
            })?;
            // The dependency cell's only output is evcxr's own echo of `:cache`
            // ("cache: 4000 MiB"), which says nothing about the lesson: it is left out.
            let out = if code.lines().any(|l| l.trim_start().starts_with(":cache")) {
                Outputs::default()
            } else {
                out
            };
            outputs.push(Some(out));
            after(index);
        }
        Ok(outputs)
    }
}
