//! `ppo-tutor dev`: developer commands that change the course's content, hidden from the
//! main help (rustlings' `dev`).
//!
//! `dev notebooks` regenerates `notebooks/*.ipynb` from the lessons and the recipes in
//! `notebooks/src/`, executing every cell on the evcxr engine. evcxr is behind the cargo
//! feature `notebook-runner`; without it the command says how to run it
//! ([`REGENERATE`](crate::generator::build::REGENERATE)) and exits with code 2.
//! `dev screenshots` redraws the README's pictures from the app's screens
//! ([`crate::screenshot`]).

use std::process::ExitCode;

use clap::{Args, Subcommand};

/// Developer commands: regenerate content from its sources.
#[derive(Debug, Args)]
pub struct DevArgs {
    /// What to regenerate.
    #[command(subcommand)]
    pub command: DevCommand,
}

/// The developer subcommands.
#[derive(Debug, Subcommand)]
pub enum DevCommand {
    /// Regenerate notebooks/*.ipynb (cells and outputs) from the lessons and notebooks/src/.
    #[command(
        long_about = "Regenerate notebooks/*.ipynb (cells and outputs) from the lessons and \
                      the recipes in notebooks/src/, executing every cell on the evcxr engine \
                      (the first run compiles ppo-tutor and candle inside it: several minutes).\n\n\
                      Needs the `notebook-runner` feature; in the repository run:\n  \
                      cargo run --features notebook-runner -- dev notebooks [LESSONS]...\n\
                      then check the result with `cargo test --test notebook_code` and \
                      `cargo test --features full-tests --test notebooks`."
    )]
    Notebooks(NotebooksArgs),
    /// Regenerate tests/notebook_code/ (every notebook's code as plain Rust) from the
    /// lessons and notebooks/src/.
    #[command(
        long_about = "Regenerate tests/notebook_code/{en,zh}/ from the lessons and the recipes \
                      in notebooks/src/: each notebook's code cells in order as one Rust \
                      function, which `cargo test --test notebook_code` compiles against the \
                      crate and runs without evcxr. Needs no feature; `dev notebooks` writes \
                      them too. In the repository run:\n  cargo run -- dev notebook-code"
    )]
    NotebookCode,
    /// Rewrite the markdown cells of notebooks/*.ipynb from the lessons, keeping every code
    /// cell and output (no evcxr).
    #[command(
        long_about = "Rewrite the markdown cells of notebooks/*.ipynb and notebooks/zh/*.ipynb \
                      from the lessons, keeping every code cell and its saved output: for a \
                      change of a lesson's text or of the code an anchor quotes, in seconds \
                      and without evcxr. Refuses a notebook whose code cells differ from its \
                      recipe (their outputs would be stale: run `dev notebooks`). In the \
                      repository run:\n  cargo run -- dev notebook-markdown"
    )]
    NotebookMarkdown,
    /// Redraw the README's pictures (assets/screens/*.png) from the app's own screens.
    #[command(
        long_about = "Redraw the README's pictures, assets/screens/{en,zh}-{lesson,training,exercise}.png, \
                      from the app's own screens: each is drawn at 160×50 as the tutor draws it \
                      (a real training run with seed 0, a real grading) and painted with the \
                      fonts in assets/fonts/. `cargo test --test cli screenshots` fails while a \
                      committed picture differs from what the app draws. In the repository \
                      run:\n  cargo run --release -- dev screenshots"
    )]
    Screenshots,
}

/// Arguments of `dev notebooks`.
#[derive(Debug, Args)]
pub struct NotebooksArgs {
    /// Only the lessons whose folder contains one of these strings (`07`, `gae`); all
    /// lessons when none is given.
    pub lessons: Vec<String>,
}

/// Runs a developer command.
///
/// # Errors
/// Whatever the command reports (a recipe out of step with its lesson, a failing cell, I/O).
pub fn run(args: &DevArgs) -> anyhow::Result<ExitCode> {
    match &args.command {
        DevCommand::Notebooks(args) => notebooks(args),
        DevCommand::NotebookCode => notebook_code(),
        DevCommand::NotebookMarkdown => notebook_markdown(),
        DevCommand::Screenshots => screenshots(),
    }
}

/// The checkout this binary was built from: its lessons are the embedded ones.
const ROOT: &str = env!("CARGO_MANIFEST_DIR");

/// `dev notebook-code`: writes every notebook's code as plain Rust.
fn notebook_code() -> anyhow::Result<ExitCode> {
    let root = std::path::Path::new(ROOT);
    if !root.join("notebooks").join("src").is_dir() {
        let (shown, command) = (root.display(), crate::generator::native::REGENERATE_CODE);
        anyhow::bail!(crate::tr!(
            "{shown} has no notebooks/src: run `{command}` in a checkout of ppo-tutor",
            "{shown} 中没有 notebooks/src：请在 ppo-tutor 的仓库副本中运行 `{command}`"
        ));
    }
    let written = crate::generator::native::write_all(root)?;
    let n = written.len();
    println!(
        "{}",
        crate::tr!(
            "wrote {n} files in tests/notebook_code/; check them with `cargo test --test notebook_code`",
            "已在 tests/notebook_code/ 中写入 {n} 个文件；请用 `cargo test --test notebook_code` 检查"
        )
    );
    Ok(ExitCode::SUCCESS)
}

/// The message for a build without the notebook runner.
fn notebook_markdown() -> anyhow::Result<ExitCode> {
    let root = std::path::Path::new(ROOT);
    let changed = crate::generator::native::write_markdown(root)?;
    let (n, names) = (changed.len(), changed.join(", "));
    println!(
        "{}",
        crate::tr!(
            "{n} notebooks changed ({names}); check them with `cargo test --test notebook_code`",
            "{n} 个笔记本有改动（{names}）；请用 `cargo test --test notebook_code` 检查"
        )
    );
    Ok(ExitCode::SUCCESS)
}

/// `dev screenshots`: redraws the README's pictures and says which changed.
fn screenshots() -> anyhow::Result<ExitCode> {
    let written = crate::screenshot::write_all(std::path::Path::new(ROOT))?;
    for w in &written {
        let path = &w.path;
        println!(
            "{}",
            if w.changed {
                crate::tr!("{path}: redrawn", "{path}：已重新绘制")
            } else {
                crate::tr!("{path}: unchanged", "{path}：没有变化")
            }
        );
    }
    println!(
        "{}",
        crate::tr!(
            "check them with `cargo test --test cli screenshots`, and look at the changed ones",
            "请用 `cargo test --test cli screenshots` 检查，并看一看改动了的图片"
        )
    );
    Ok(ExitCode::SUCCESS)
}

#[cfg(any(test, not(feature = "notebook-runner")))]
fn no_runner_message() -> String {
    let command = crate::generator::build::REGENERATE;
    let why = crate::tr!(
        "`ppo-tutor dev notebooks` executes the notebooks on the evcxr engine, which this build \
         leaves out (cargo feature `notebook-runner`); in the repository, run:\n  {command}",
        "`ppo-tutor dev notebooks` 要在 evcxr 引擎上执行笔记本，而这次构建没有包含它（cargo 特性 \
         `notebook-runner`）；请在仓库中运行：\n  {command}"
    );
    format!("{}{why}", super::error_prefix())
}

#[cfg(not(feature = "notebook-runner"))]
fn notebooks(_args: &NotebooksArgs) -> anyhow::Result<ExitCode> {
    eprintln!("{}", no_runner_message());
    Ok(ExitCode::from(super::EXIT_USAGE))
}

#[cfg(feature = "notebook-runner")]
fn notebooks(args: &NotebooksArgs) -> anyhow::Result<ExitCode> {
    runner::notebooks(args)
}

/// The notebook runner, built with the `notebook-runner` feature.
#[cfg(feature = "notebook-runner")]
mod runner {
    use std::path::Path;
    use std::process::ExitCode;
    use std::time::Instant;

    use anyhow::{Context as _, bail};

    use super::NotebooksArgs;
    use crate::generator::build::{self, REGENERATE};
    use crate::generator::ipynb::{notebook_json, to_text};
    use crate::generator::kernel::{self, Kernel};
    use crate::lesson::Course;

    use super::ROOT;

    pub(super) fn notebooks(args: &NotebooksArgs) -> anyhow::Result<ExitCode> {
        let root = Path::new(ROOT);
        if !root.join("notebooks").join("src").is_dir() {
            bail!(
                "{} has no notebooks/src: run `{REGENERATE}` in a checkout of ppo-tutor",
                root.display()
            );
        }
        if !kernel::is_driver() {
            let status = kernel::relaunch(root)?;
            if status.code().is_none() {
                // Killed: the driver could not say why.
                bail!("the notebook driver stopped: {status}");
            }
            return Ok(if status.success() {
                ExitCode::SUCCESS
            } else {
                ExitCode::FAILURE
            });
        }
        let course = Course::embedded()?;
        build::recipe_folders(root, &course)?;
        // Build every notebook first: a recipe out of step with its lesson fails at once.
        let mut notebooks = Vec::new();
        for lesson in &course.lessons {
            notebooks.push((build::folder(lesson), build::notebook_cells(root, lesson)?));
        }
        // English in notebooks/, Chinese (`--lang zh`) in notebooks/zh/.
        std::fs::create_dir_all(root.join(build::notebook_dir()))
            .with_context(|| format!("creating {}", build::notebook_dir()))?;
        for (folder, cells) in &notebooks {
            if !args.lessons.is_empty() && !args.lessons.iter().any(|f| folder.contains(f.as_str()))
            {
                continue;
            }
            let started = Instant::now();
            let name = build::notebook_file(folder);
            let outputs = Kernel::start_in(
                crate::i18n::Lang::current(),
                &root.join(build::notebook_dir()),
            )?
            .run_cells(cells, &name)?;
            let text = to_text(&notebook_json(cells, &outputs))?;
            std::fs::write(root.join(&name), text).with_context(|| format!("writing {name}"))?;
            println!(
                "{name}: {} cells ran in {:.1} s",
                cells.len(),
                started.elapsed().as_secs_f64()
            );
        }
        let written = crate::generator::native::write_all(root)?;
        println!(
            "{} files of plain Rust in tests/notebook_code/; check them with \
             `cargo test --test notebook_code` and \
             `cargo test --features full-tests --test notebooks`",
            written.len()
        );
        Ok(ExitCode::SUCCESS)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_message_without_the_runner_gives_the_command() {
        let msg = no_runner_message();
        assert!(
            msg.ends_with("cargo run --features notebook-runner -- dev notebooks"),
            "{msg}"
        );
    }
}
