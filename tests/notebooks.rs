//! The Jupyter notebooks: built, executed on the evcxr engine, and checked.
//!
//! Each `notebooks/NN-slug.ipynb` is generated from its lesson (`lessons/NN-slug/lesson.md`:
//! titles, explanations, the seed's Python, the exercise) and a recipe of code cells
//! (`notebooks/src/NN-slug.rs`, cells separated by `// %%` lines, `// %% step: TITLE` where
//! a lesson step begins, `// %% exercise` where the exercise goes). This test:
//!
//! 1. checks the course and the notebooks agree: one notebook per lesson, the steps' titles
//!    in order, every exercise function present, and the committed cells equal the
//!    generated ones;
//! 2. runs every notebook top to bottom in a fresh evcxr `CommandContext` (what the kernel
//!    uses), with `:dep ppo-tutor = { path = ".." }` resolved from `notebooks/` as Jupyter
//!    would; a compile error, or anything on stderr (a panic, a failed `assert!`, a `?`
//!    error: the kernel reports those only there) fails the test;
//! 3. checks the cells marked `// check: NAME after N episodes`: the values the notebook
//!    computed itself must equal the library's live tensor NAME after N episodes (seed 0,
//!    the seed's settings);
//! 4. grades each exercise's reference solution in the notebook's own kernel: it must pass;
//! 5. compares the saved outputs with the fresh ones (numbers to 1e-4), so the committed
//!    notebooks show what the code really prints.
//!
//! Regenerate the notebooks (sources and outputs) with
//! `PPO_TUTOR_NOTEBOOKS=overwrite cargo test --test notebooks`. Run a few with
//! `cargo test --test notebooks -- 07 08` (lesson folders containing those strings).
//!
//! The first run compiles ppo-tutor and candle inside evcxr (a few minutes, cached under
//! `target/tmp/evcxr`); later runs take about a second per cell.

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::{Command, ExitCode};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use anyhow::{Context as _, Result, bail, ensure};
use ppo_tutor::lesson::{Course, Lesson};
use serde_json::{Value, json};

/// Set to `overwrite` to write the notebooks instead of comparing them.
const MODE_VAR: &str = "PPO_TUTOR_NOTEBOOKS";
/// Marks the re-executed driver process (see [`main`]).
const DRIVER_VAR: &str = "PPO_TUTOR_NOTEBOOK_DRIVER";
/// The first cell of every notebook.
const DEP_CELL: &str = ":dep ppo-tutor = { path = \"..\" }";
/// Exercises that a notebook cell can grade in place (`ppo_tutor::grade::in_process`).
const IN_PROCESS: [&str; 10] = [
    "sample_action",
    "td_target",
    "td_delta",
    "compute_advantage",
    "log_prob_of_actions",
    "ratio",
    "actor_loss",
    "critic_loss",
    "ppo_losses",
    "moving_average",
];
/// The exercise on candle tensors: its own starter and solution files, in its own cell.
const CANDLE: &str = "ppo_losses";

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn main() -> ExitCode {
    // The evcxr runtime is this same binary, re-executed: it must take over first.
    evcxr::runtime_hook();
    if std::env::var_os(DRIVER_VAR).is_none() {
        return relaunch();
    }
    match run() {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("\nnotebooks: FAILED\n{e:#}");
            ExitCode::FAILURE
        }
    }
}

/// evcxr reads its work folder from `EVCXR_TMPDIR`, and `:dep path = ".."` resolves
/// against the working directory: the driver runs as a child with both set (and candle on
/// one thread, which is faster for these small networks).
fn relaunch() -> ExitCode {
    let tmp = Path::new(env!("CARGO_TARGET_TMPDIR")).join("evcxr");
    if let Err(e) = std::fs::create_dir_all(&tmp) {
        eprintln!("notebooks: cannot create {}: {e}", tmp.display());
        return ExitCode::FAILURE;
    }
    // Pin the kernel's dependency versions to ours (cargo keeps a lock file's versions).
    let lock = tmp.join("Cargo.lock");
    if !lock.exists() {
        let _ = std::fs::copy(root().join("Cargo.lock"), &lock);
    }
    let exe = match std::env::current_exe() {
        Ok(exe) => exe,
        Err(e) => {
            eprintln!("notebooks: cannot find the test binary: {e}");
            return ExitCode::FAILURE;
        }
    };
    let status = Command::new(exe)
        .args(std::env::args_os().skip(1))
        .env(DRIVER_VAR, "1")
        .env("EVCXR_TMPDIR", &tmp)
        .env("RAYON_NUM_THREADS", "1")
        // evcxr finds its build under EVCXR_TMPDIR/target: a target folder set for this
        // project's build must not redirect the kernel's.
        .env_remove("CARGO_TARGET_DIR")
        .env_remove("CARGO_BUILD_TARGET_DIR")
        .current_dir(root().join("notebooks"))
        .status();
    match status {
        Ok(s) if s.success() => ExitCode::SUCCESS,
        Ok(_) => ExitCode::FAILURE,
        Err(e) => {
            eprintln!("notebooks: cannot start the driver: {e}");
            ExitCode::FAILURE
        }
    }
}

// ---------------------------------------------------------------------------------------
// Building a notebook from its lesson and recipe.

#[derive(Debug, Clone, PartialEq)]
enum Cell {
    Markdown(String),
    Code(String),
}

/// One piece of a recipe.
#[derive(Debug, Clone, PartialEq)]
enum Piece {
    Code(String),
    Step(String),
    Exercise,
}

fn parse_recipe(text: &str) -> Vec<Piece> {
    let mut pieces = Vec::new();
    let mut code: Option<String> = None;
    let flush = |code: &mut Option<String>, pieces: &mut Vec<Piece>| {
        if let Some(c) = code.take() {
            let c = c.trim().to_string();
            if !c.is_empty() {
                pieces.push(Piece::Code(c));
            }
        }
    };
    for line in text.lines() {
        if let Some(marker) = line.strip_prefix("// %%") {
            flush(&mut code, &mut pieces);
            let marker = marker.trim();
            if let Some(title) = marker.strip_prefix("step:") {
                pieces.push(Piece::Step(title.trim().to_string()));
            } else if marker == "exercise" {
                pieces.push(Piece::Exercise);
            }
            code = Some(String::new());
        } else if let Some(c) = code.as_mut() {
            c.push_str(line);
            c.push('\n');
        }
    }
    flush(&mut code, &mut pieces);
    pieces
}

fn step_markdown(lesson: &Lesson, k: usize) -> String {
    let step = &lesson.steps[k];
    let mut md = format!("## {}. {}\n\n{}\n", k + 1, step.title, step.body);
    if !step.python.is_empty() {
        let _ = write!(
            md,
            "\n**The seed (PyTorch):**\n\n```python\n{}\n```\n",
            step.python.trim()
        );
    }
    if let Some((path, code)) = (!step.code.is_empty())
        .then(|| ppo_tutor::lesson::anchor::find(&step.code))
        .flatten()
    {
        let _ = write!(
            md,
            "\n**ppo-tutor (`src/{path}`):**\n\n```rust\n{}\n```\n",
            code.trim_end()
        );
    }
    md
}

/// The cells that show a step's live values, as the terminal app does beside the text.
fn show_cells(lesson: &Lesson, k: usize) -> Vec<Cell> {
    let step = &lesson.steps[k];
    let tensors: Vec<String> = step
        .show
        .iter()
        .filter(|n| !ppo_tutor::lesson::VIEWS.contains(&n.as_str()))
        .map(|n| format!("{n:?}"))
        .collect();
    let mut cells = Vec::new();
    if !tensors.is_empty() {
        cells.push(Cell::Code(format!(
            "// What the terminal app shows beside this step:\nsnap.show(&[{}])",
            tensors.join(", ")
        )));
    }
    for view in &step.show {
        match view.as_str() {
            "plot" => cells.push(Cell::Code(
                "snap.return_plot(\"PPO on CartPole-v1\")?".to_string(),
            )),
            "cartpole" => cells.push(Cell::Code("snap.cartpole()".to_string())),
            "clip_chart" => cells.push(Cell::Code("snap.clip_chart()".to_string())),
            _ => {}
        }
    }
    cells
}

/// The learner's starter as a cell: the file without its `//!` header.
fn without_header(file: &str) -> String {
    file.lines()
        .skip_while(|l| l.starts_with("//!") || l.trim().is_empty())
        .collect::<Vec<_>>()
        .join("\n")
        .trim_end()
        .to_string()
}

/// The candle exercise's file as a cell: candle comes through ppo-tutor (no `:dep` of its
/// own), so `use candle_core::` becomes `use ppo_tutor::candle_core::`.
fn candle_cell(file: &str) -> String {
    without_header(file).replace("use candle_core::", "use ppo_tutor::candle_core::")
}

/// A lesson file (`lessons/FOLDER/NAME`).
fn lesson_file(folder: &str, name: &str) -> Result<String> {
    std::fs::read_to_string(root().join("lessons").join(folder).join(name))
        .with_context(|| format!("reading lessons/{folder}/{name}"))
}

fn exercise_cells(lesson: &Lesson) -> Result<Vec<Cell>> {
    let ex = lesson
        .exercise
        .as_ref()
        .context("`// %% exercise` in a lesson without an exercise")?;
    let names = ex.names();
    let graded: Vec<&str> = names
        .iter()
        .copied()
        .filter(|n| IN_PROCESS.contains(n) && *n != CANDLE)
        .collect();
    let list: Vec<String> = names.iter().map(|n| format!("`{n}`")).collect();
    let mut md = format!("## Exercise: {}\n\n", list.join(" and "));
    md.push_str(
        "Replace each `todo!()` in the next cell with your code and run it; the cell after it \
         grades your function with the same checks, hints and messages as \
         `ppo-tutor grade` in a terminal. A function that never returns cannot be \
         interrupted: the grader reports it after 10 s, then restart the kernel.\n",
    );
    ensure!(
        names.iter().all(|n| IN_PROCESS.contains(n)),
        "exercises {names:?}: every exercise must be gradable in a notebook cell (IN_PROCESS)"
    );
    if !ex.hints.is_empty() {
        md.push_str("\n<details><summary>Hints</summary>\n\n");
        for (i, h) in ex.hints.iter().enumerate() {
            let _ = writeln!(md, "{}. {h}", i + 1);
        }
        md.push_str("\n</details>\n");
    }
    let folder = format!("{:02}-{}", lesson.order, lesson.id);
    let starter = lesson_file(&folder, "exercise.rs")?;
    let mut cells = vec![Cell::Markdown(md), Cell::Code(without_header(&starter))];
    for name in graded {
        cells.push(Cell::Code(format!(
            "ppo_tutor::grade::in_process::{name}({name})"
        )));
    }
    if names.contains(&CANDLE) {
        cells.push(Cell::Markdown(format!(
            "### The same on candle tensors: `{CANDLE}`\n\nBoth losses of one epoch, as the \
             agent computes them. Its grader also compares the gradients your losses send \
             back, then trains CartPole with them ({} episodes, a few seconds).\n",
            ppo_tutor::grade::exercises::ppo_losses::TRAIN_EPISODES
        )));
        let candle = lesson_file(&folder, ppo_tutor::grade::find(CANDLE)?.meta().starter)?;
        cells.push(Cell::Code(candle_cell(&candle)));
        cells.push(Cell::Code(format!(
            "ppo_tutor::grade::in_process::{CANDLE}({CANDLE})"
        )));
    }
    Ok(cells)
}

fn build(lesson: &Lesson, recipe: &str, file: &str) -> Result<Vec<Cell>> {
    let mut cells = vec![
        Cell::Markdown(format!(
            "# Lesson {}: {}\n\n{}\n\nThis notebook mirrors lesson {} of the terminal app \
             (`cargo run --release`), on the [evcxr](https://github.com/evcxr/evcxr) Rust \
             kernel. Every number below comes from the real PPO and CartPole of the \
             `ppo-tutor` crate. The first cell compiles the crate (with candle) once, which \
             takes a few minutes; after that each cell takes a second or two.",
            lesson.order, lesson.title, lesson.summary, lesson.order
        )),
        Cell::Code(DEP_CELL.to_string()),
    ];
    let mut next_step = 0;
    let mut pending_show: Vec<Cell> = Vec::new();
    let mut exercise_done = false;
    for piece in parse_recipe(recipe) {
        match piece {
            Piece::Code(code) => cells.push(Cell::Code(code)),
            Piece::Step(title) => {
                let Some(step) = lesson.steps.get(next_step) else {
                    bail!("{file}: step '{title}' is beyond the lesson's last step");
                };
                ensure!(
                    step.title == title,
                    "{file}: step {} is '{}' in the lesson, '{title}' in the recipe",
                    next_step + 1,
                    step.title
                );
                cells.append(&mut pending_show);
                cells.push(Cell::Markdown(step_markdown(lesson, next_step)));
                pending_show = show_cells(lesson, next_step);
                next_step += 1;
            }
            Piece::Exercise => {
                cells.append(&mut pending_show);
                cells.extend(exercise_cells(lesson).with_context(|| file.to_string())?);
                exercise_done = true;
            }
        }
    }
    cells.append(&mut pending_show);
    ensure!(
        next_step == lesson.steps.len(),
        "{file}: the recipe covers {next_step} of the lesson's {} steps; add `// %% step: {}`",
        lesson.steps.len(),
        lesson.steps.get(next_step).map_or("", |s| s.title.as_str())
    );
    ensure!(
        exercise_done == lesson.exercise.is_some(),
        "{file}: the lesson has an exercise; add a `// %% exercise` cell marker"
    );
    Ok(cells)
}

// ---------------------------------------------------------------------------------------
// Running cells on evcxr.

/// What one cell printed.
#[derive(Debug, Clone, Default, PartialEq)]
struct Outputs {
    stdout: String,
    /// Rich outputs by mime type (sorted, so the file is stable).
    data: BTreeMap<String, String>,
}

struct Kernel {
    ctx: evcxr::CommandContext,
    stdout: Arc<Mutex<String>>,
    stderr: Arc<Mutex<String>>,
}

/// Collects a kernel stream as it comes: evcxr waits for its stdout channel to be empty
/// before a cell returns, so it must be read while the cell runs.
fn collect(rx: crossbeam_channel::Receiver<String>) -> Arc<Mutex<String>> {
    let buf = Arc::new(Mutex::new(String::new()));
    let sink = Arc::clone(&buf);
    std::thread::spawn(move || {
        while let Ok(line) = rx.recv() {
            if let Ok(mut b) = sink.lock() {
                b.push_str(&line);
                b.push('\n');
            }
        }
    });
    buf
}

fn take(buf: &Mutex<String>) -> String {
    buf.lock()
        .map(|mut b| std::mem::take(&mut *b))
        .unwrap_or_default()
}

impl Kernel {
    fn start() -> Result<Self> {
        let (ctx, outputs) =
            evcxr::CommandContext::new().map_err(|e| anyhow::anyhow!("starting evcxr: {e}"))?;
        Ok(Self {
            ctx,
            stdout: collect(outputs.stdout),
            stderr: collect(outputs.stderr),
        })
    }

    /// Runs one cell; an error for a compile error or anything on stderr.
    fn run(&mut self, code: &str) -> Result<Outputs> {
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
                bail!("the cell does not compile:\n{}\n{stderr}", shown.join("\n"))
            }
            Err(e) => bail!("the cell failed: {e}\n{stderr}"),
        };
        ensure!(
            stderr.trim().is_empty(),
            "the cell wrote to stderr (a panic, failed assert or `?` error):\n{stderr}"
        );
        Ok(Outputs {
            stdout,
            data: out.content_by_mime_type.into_iter().collect(),
        })
    }
}

// ---------------------------------------------------------------------------------------
// The notebook file.

fn lines(text: &str) -> Value {
    let mut out: Vec<String> = text.split_inclusive('\n').map(str::to_string).collect();
    if out.is_empty() {
        out.push(String::new());
    }
    json!(out)
}

fn notebook_json(cells: &[Cell], outputs: &[Option<Outputs>]) -> Value {
    let mut count = 0;
    let cells: Vec<Value> = cells
        .iter()
        .zip(outputs)
        .map(|(cell, out)| match cell {
            Cell::Markdown(md) => json!({
                "cell_type": "markdown",
                "metadata": {},
                "source": lines(md.trim_end()),
            }),
            Cell::Code(code) => {
                count += 1;
                let mut outs = Vec::new();
                if let Some(out) = out {
                    if !out.stdout.is_empty() {
                        outs.push(json!({
                            "name": "stdout",
                            "output_type": "stream",
                            "text": lines(&out.stdout),
                        }));
                    }
                    if !out.data.is_empty() {
                        let data: serde_json::Map<String, Value> = out
                            .data
                            .iter()
                            .map(|(k, v)| (k.clone(), lines(v)))
                            .collect();
                        outs.push(json!({
                            "data": data,
                            "execution_count": count,
                            "metadata": {},
                            "output_type": "execute_result",
                        }));
                    }
                }
                json!({
                    "cell_type": "code",
                    "execution_count": count,
                    "metadata": {},
                    "outputs": outs,
                    "source": lines(code),
                })
            }
        })
        .collect();
    json!({
        "cells": cells,
        "metadata": {
            "kernelspec": {"display_name": "Rust", "language": "rust", "name": "rust"},
            "language_info": {
                "codemirror_mode": "rust",
                "file_extension": ".rs",
                "mimetype": "text/rust",
                "name": "Rust",
                "pygment_lexer": "rust",
                "version": "",
            },
        },
        "nbformat": 4,
        "nbformat_minor": 4,
    })
}

fn to_text(nb: &Value) -> Result<String> {
    let mut buf = Vec::new();
    let fmt = serde_json::ser::PrettyFormatter::with_indent(b" ");
    let mut ser = serde_json::Serializer::with_formatter(&mut buf, fmt);
    serde::Serialize::serialize(nb, &mut ser)?;
    let mut text = String::from_utf8(buf)?;
    text.push('\n');
    Ok(text)
}

/// The joined text of a notebook field stored as a list of lines.
fn joined(v: &Value) -> String {
    match v {
        Value::Array(parts) => parts.iter().filter_map(Value::as_str).collect(),
        Value::String(s) => s.clone(),
        _ => String::new(),
    }
}

// ---------------------------------------------------------------------------------------
// Comparing outputs: equal text, numbers within 1e-4.

fn split_numbers(text: &str) -> (Vec<String>, Vec<f64>) {
    let mut words = Vec::new();
    let mut numbers = Vec::new();
    let mut word = String::new();
    let mut chars = text.char_indices().peekable();
    while let Some((i, c)) = chars.next() {
        let starts_number = c.is_ascii_digit()
            || (c == '-'
                && text[i + 1..].starts_with(|d: char| d.is_ascii_digit())
                && !word.ends_with(|p: char| p.is_ascii_alphanumeric()));
        if starts_number {
            let mut end = i + c.len_utf8();
            while let Some(&(j, d)) = chars.peek() {
                if d.is_ascii_digit() || d == '.' || d == 'e' {
                    end = j + d.len_utf8();
                    chars.next();
                } else {
                    break;
                }
            }
            match text[i..end].parse::<f64>() {
                Ok(n) => {
                    words.push(std::mem::take(&mut word));
                    numbers.push(n);
                }
                Err(_) => word.push_str(&text[i..end]),
            }
        } else {
            word.push(c);
        }
    }
    words.push(word);
    (words, numbers)
}

fn same_output(a: &str, b: &str) -> bool {
    let (wa, na) = split_numbers(a);
    let (wb, nb) = split_numbers(b);
    wa == wb
        && na.len() == nb.len()
        && na
            .iter()
            .zip(&nb)
            .all(|(x, y)| (x - y).abs() <= 1e-4 * (1.0 + x.abs().max(y.abs())))
}

// ---------------------------------------------------------------------------------------
// `// check: NAME after N episodes`.

fn parse_check(code: &str) -> Option<(String, usize)> {
    let line = code
        .lines()
        .find_map(|l| l.trim().strip_prefix("// check:"))?;
    let mut words = line.split_whitespace();
    let name = words.next()?.to_string();
    let episodes = match (words.next(), words.next()) {
        (Some("after"), Some(n)) => n.parse().ok()?,
        _ => return None,
    };
    Some((name, episodes))
}

/// The value lines of a tensor's text (its caption, which carries marks, is skipped).
fn value_lines(text: &str) -> Vec<&str> {
    text.lines().skip(1).collect()
}

fn check_against_library(name: &str, episodes: usize, out: &Outputs) -> Result<()> {
    let snap = ppo_tutor::notebook::snapshot(ppo_tutor::ppo::PpoConfig::default(), 0, episodes)?;
    let want = snap
        .tensor(name)
        .with_context(|| format!("the library has no live value '{name}'"))?;
    let want = ppo_tutor::notebook::tensor_html(&want);
    let got = out
        .data
        .get("text/plain")
        .context("the checked cell shows no text/plain output")?;
    ensure!(
        value_lines(want.text()) == value_lines(got),
        "the notebook's {name} differs from the library's after {episodes} episodes:\n\
         notebook:\n{got}\nlibrary:\n{}",
        want.text()
    );
    Ok(())
}

// ---------------------------------------------------------------------------------------

fn recipe_files() -> Result<Vec<String>> {
    stems("notebooks/src", ".rs")
}

fn committed_notebooks() -> Result<Vec<String>> {
    stems("notebooks", ".ipynb")
}

/// The sorted names, without `ext`, of the files in `dir` that end in `ext`.
fn stems(dir: &str, ext: &str) -> Result<Vec<String>> {
    let mut names = Vec::new();
    for entry in std::fs::read_dir(root().join(dir)).context(dir.to_string())? {
        let name = entry?.file_name().to_string_lossy().to_string();
        if let Some(stem) = name.strip_suffix(ext) {
            names.push(stem.to_string());
        }
    }
    names.sort();
    Ok(names)
}

fn run() -> Result<()> {
    let overwrite = std::env::var(MODE_VAR).is_ok_and(|v| v == "overwrite");
    let filters: Vec<String> = std::env::args()
        .skip(1)
        .filter(|a| !a.starts_with('-'))
        .collect();
    let course = Course::embedded()?;
    let folders: Vec<String> = course
        .lessons
        .iter()
        .map(|l| format!("{:02}-{}", l.order, l.id))
        .collect();

    // 1. One recipe and one notebook per lesson, and nothing else.
    ensure!(
        recipe_files()? == folders,
        "notebooks/src/ must hold one recipe per lesson, named after its folder:\n  lessons: {folders:?}\n  recipes: {:?}",
        recipe_files()?
    );
    if !overwrite {
        ensure!(
            committed_notebooks()? == folders,
            "notebooks/ must hold one notebook per lesson:\n  lessons:   {folders:?}\n  notebooks: {:?}\n\
             (regenerate: {MODE_VAR}=overwrite cargo test --test notebooks)",
            committed_notebooks()?
        );
    }
    let mut built = Vec::new();
    for (lesson, folder) in course.lessons.iter().zip(&folders) {
        let file = format!("notebooks/src/{folder}.rs");
        let recipe = std::fs::read_to_string(root().join(&file)).context(file.clone())?;
        let cells = build(lesson, &recipe, &file)?;
        if !overwrite {
            check_sources(folder, &cells)?;
        }
        built.push((lesson, folder, cells));
    }
    println!("notebooks: {} notebooks match their lessons", built.len());

    // The runner itself: each way a cell can fail must fail the test.
    self_check()?;
    println!("notebooks: the runner catches compile errors, panics, failed asserts and `?` errors");

    // 2-5. Execute.
    let mut checks = 0;
    for (lesson, folder, cells) in &built {
        if !filters.is_empty() && !filters.iter().any(|f| folder.contains(f.as_str())) {
            continue;
        }
        let started = Instant::now();
        let mut kernel = Kernel::start()?;
        let mut outputs = Vec::new();
        for (i, cell) in cells.iter().enumerate() {
            let Cell::Code(code) = cell else {
                outputs.push(None);
                continue;
            };
            let out = kernel
                .run(code)
                .with_context(|| format!("notebooks/{folder}.ipynb, cell {i}:\n{code}"))?;
            if let Some((name, episodes)) = parse_check(code) {
                check_against_library(&name, episodes, &out)
                    .with_context(|| format!("notebooks/{folder}.ipynb, cell {i}"))?;
                checks += 1;
            }
            outputs.push(Some(out));
        }
        check_solutions(&mut kernel, lesson, folder)?;
        let text = to_text(&notebook_json(cells, &outputs))?;
        let path = root().join("notebooks").join(format!("{folder}.ipynb"));
        if overwrite {
            std::fs::write(&path, &text).with_context(|| path.display().to_string())?;
        } else {
            check_outputs(folder, &path, &text)?;
        }
        println!(
            "notebooks: {folder}: {} cells ran in {:.1} s",
            cells.len(),
            started.elapsed().as_secs_f64()
        );
    }
    println!("notebooks: {checks} cells checked against the library");
    Ok(())
}

/// A failing cell of each kind must be reported as failing (the kernel itself replies
/// "ok" to all but the compile error).
fn self_check() -> Result<()> {
    let mut kernel = Kernel::start()?;
    let fine = kernel.run("let answer = 6 * 7;\nprintln!(\"{answer}\");")?;
    ensure!(
        fine.stdout == "42\n",
        "a plain cell printed {:?}",
        fine.stdout
    );
    for (what, code) in [
        ("a compile error", "let x: u32 = \"not a number\";"),
        ("a panic", "panic!(\"on purpose\");"),
        ("a failed assert", "assert_eq!(1 + 1, 3);"),
        (
            "a `?` error",
            "let r: Result<u32, String> = Err(\"on purpose\".into());\nlet v = r?;",
        ),
    ] {
        ensure!(
            kernel.run(code).is_err(),
            "the runner let {what} pass: {code}"
        );
    }
    Ok(())
}

/// The committed notebook's cells must be the generated ones (sources and order).
fn check_sources(folder: &str, cells: &[Cell]) -> Result<()> {
    let path = root().join("notebooks").join(format!("{folder}.ipynb"));
    let text = std::fs::read_to_string(&path).with_context(|| path.display().to_string())?;
    let nb: Value = serde_json::from_str(&text).with_context(|| path.display().to_string())?;
    ensure!(
        nb["metadata"]["kernelspec"]["name"] == "rust",
        "notebooks/{folder}.ipynb: the kernel must be evcxr's `rust`"
    );
    let saved = nb["cells"].as_array().map_or(&[][..], Vec::as_slice);
    let fix = format!("regenerate with {MODE_VAR}=overwrite cargo test --test notebooks");
    ensure!(
        saved.len() == cells.len(),
        "notebooks/{folder}.ipynb has {} cells, its lesson and recipe make {}: {fix}",
        saved.len(),
        cells.len()
    );
    for (i, (s, c)) in saved.iter().zip(cells).enumerate() {
        let (kind, source) = match c {
            Cell::Markdown(md) => ("markdown", md.trim_end()),
            Cell::Code(code) => ("code", code.as_str()),
        };
        ensure!(
            s["cell_type"] == kind && joined(&s["source"]) == source,
            "notebooks/{folder}.ipynb, cell {i} is out of date with its lesson or recipe: {fix}"
        );
    }
    Ok(())
}

/// A cell's outputs as `(mime type or "stream", text)` pairs, in order.
fn output_texts(cell: &Value) -> Vec<(String, String)> {
    let mut texts = Vec::new();
    for o in cell["outputs"].as_array().map_or(&[][..], Vec::as_slice) {
        if let Some(data) = o["data"].as_object() {
            texts.extend(data.iter().map(|(k, d)| (k.clone(), joined(d))));
        }
        texts.push(("stream".into(), joined(&o["text"])));
    }
    texts
}

/// The saved outputs must be what the cells print now.
fn check_outputs(folder: &str, path: &Path, fresh: &str) -> Result<()> {
    let saved = std::fs::read_to_string(path)?;
    let saved: Value = serde_json::from_str(&saved)?;
    let fresh: Value = serde_json::from_str(fresh)?;
    let fix = format!("regenerate with {MODE_VAR}=overwrite cargo test --test notebooks");
    let (Some(a), Some(b)) = (saved["cells"].as_array(), fresh["cells"].as_array()) else {
        bail!("notebooks/{folder}.ipynb has no cells");
    };
    for (i, (s, f)) in a.iter().zip(b).enumerate() {
        let (so, fo) = (output_texts(s), output_texts(f));
        let same = so.len() == fo.len()
            && so
                .iter()
                .zip(&fo)
                .all(|((k1, v1), (k2, v2))| k1 == k2 && same_output(v1, v2));
        ensure!(
            same,
            "notebooks/{folder}.ipynb, cell {i}: the saved output is not what the cell prints now: {fix}"
        );
    }
    Ok(())
}

/// Each exercise's reference solution, run in the notebook's kernel, passes its grader.
fn check_solutions(kernel: &mut Kernel, lesson: &Lesson, folder: &str) -> Result<()> {
    let Some(ex) = &lesson.exercise else {
        return Ok(());
    };
    let solution = lesson_file(folder, "solution.rs")?;
    kernel
        .run(&without_header(&solution))
        .with_context(|| format!("{folder}: the reference solution in the notebook"))?;
    if ex.names().contains(&CANDLE) {
        let candle = lesson_file(folder, ppo_tutor::grade::find(CANDLE)?.meta().solution)?;
        kernel
            .run(&candle_cell(&candle))
            .with_context(|| format!("{folder}: the candle reference solution in the notebook"))?;
    }
    for name in ex.names().into_iter().filter(|n| IN_PROCESS.contains(n)) {
        let out = kernel.run(&format!("ppo_tutor::grade::in_process::{name}({name})"))?;
        let text = out.data.get("text/plain").cloned().unwrap_or_default();
        ensure!(
            text.contains("checks passed: passed"),
            "{folder}: the reference {name} does not pass in the notebook:\n{text}"
        );
    }
    Ok(())
}
