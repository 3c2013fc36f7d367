//! A lesson's exercise cells: the exercise's introduction, its starter code (the learner's
//! file without its header), the cell that grades it in place, and the reference solutions
//! the checks run instead of the starters.

use std::fmt::Write as _;
use std::path::Path;

use super::{BuildError, Cell, folder, read, recipe_dir};
use crate::grade::prose::Prose;
use crate::grade::{Backend, Exercise};
use crate::i18n::{Lang, t};
use crate::lesson::Lesson;
use crate::tr;

/// The starter `name` of lesson folder `dir` in the current language (`exercise.zh.rs`
/// beside `exercise.rs`).
fn starter_file(dir: &str, name: &str) -> String {
    match (Lang::current(), name.strip_suffix(".rs")) {
        (Lang::Zh, Some(stem)) => format!("{dir}/{stem}.zh.rs"),
        _ => format!("{dir}/{name}"),
    }
}

/// A lesson's Rust file as a cell: the file without its `//!` header.
fn without_header(file: &str) -> String {
    file.lines()
        .skip_while(|l| l.starts_with("//!") || l.trim().is_empty())
        .collect::<Vec<_>>()
        .join("\n")
        .trim_end()
        .to_string()
}

/// A candle exercise's file as a cell: candle comes through the engine (no `:dep` of its
/// own), so `use candle_core::` becomes `use ppo_engine::candle_core::`.
fn candle_cell(file: &str) -> String {
    without_header(file).replace("use candle_core::", "use ppo_engine::candle_core::")
}

/// The cell that grades the function `name` defined by an earlier cell, in place.
#[must_use]
pub fn grade_cell(name: &str) -> String {
    format!("ppo_grade::in_process::{name}({name})")
}

/// The lesson's exercises from the registry, in the lesson's order (`file` names the recipe
/// in errors); empty for a lesson without an exercise. Every registered exercise can be
/// graded in a cell (`ppo_grade::in_process::NAME`).
fn registered(lesson: &Lesson, file: &str) -> Result<Vec<&'static dyn Exercise>, BuildError> {
    let Some(ex) = &lesson.exercise else {
        return Ok(Vec::new());
    };
    ex.names()
        .into_iter()
        .map(|name| {
            crate::grade::find(name).map_err(|_| BuildError::Unregistered {
                file: file.to_string(),
                name: name.to_string(),
            })
        })
        .collect()
}

/// `exercises` split into those written in the lesson's shared starter (plain Rust, built
/// with `rustc`) and those with a starter and cells of their own (on candle, built with
/// cargo), each in course order.
fn by_starter(
    exercises: Vec<&'static dyn Exercise>,
) -> (Vec<&'static dyn Exercise>, Vec<&'static dyn Exercise>) {
    exercises
        .into_iter()
        .partition(|e| e.meta().backend == Backend::Rustc)
}

/// The markdown cell before the own cell of `ex` (built with cargo, on candle): its
/// heading, then the `notebook` text of its `exercise.toml` entry.
fn intro(ex: &dyn Exercise) -> Result<String, BuildError> {
    let m = ex.meta();
    let text = Prose::of(m.name)
        .ok()
        .and_then(|p| p.other("notebook"))
        .ok_or_else(|| BuildError::NoIntro {
            lesson: m.lesson.to_string(),
            name: m.name.to_string(),
        })?;
    Ok(tr!(
        "### The same on candle tensors: `{}`\n\n{text}\n",
        "### 同样的计算，用 candle 张量：`{}`\n\n{text}\n",
        m.name
    ))
}

/// The exercise's cells: instructions and hints, the starter, a grading cell per plain
/// exercise, then each candle exercise with its introduction, starter and grading cell.
pub(super) fn exercise_cells(
    lesson: &Lesson,
    file: &str,
    root: &Path,
) -> Result<Vec<Cell>, BuildError> {
    let Some(ex) = &lesson.exercise else {
        return Err(BuildError::NoExercise {
            file: file.to_string(),
        });
    };
    let (shared, own) = by_starter(registered(lesson, file)?);
    let list: Vec<String> = ex.names().iter().map(|n| format!("`{n}`")).collect();
    let mut md = tr!(
        "## Exercise: {}\n\n",
        "## 练习：{}\n\n",
        list.join(t(" and ", " 和 "))
    );
    md.push_str(t(
        "Replace each `todo!()` in the next cell with your code and run it; the cell after it \
         grades your function with the same checks, hints and messages as \
         `ppo-tutor grade` in a terminal. A function that never returns cannot be \
         interrupted: the grader reports it after 10 s, then restart the kernel.\n",
        "把下一个单元格里的每个 `todo!()` 换成你的代码并运行；再下一个单元格会给你的函数评分，\
         检查项、提示和消息都与终端里的 `ppo-tutor grade` 相同。永不返回的函数无法中断：\
         评分器会在 10 s 后报告它，之后请重启内核。\n",
    ));
    if !ex.hints.is_empty() {
        md.push_str(t(
            "\n<details><summary>Hints</summary>\n\n",
            "\n<details><summary>提示</summary>\n\n",
        ));
        for (i, h) in ex.hints.iter().enumerate() {
            let _ = writeln!(md, "{}. {h}", i + 1);
        }
        md.push_str("\n</details>\n");
    }
    let dir = format!("lessons/{}", folder(lesson));
    let mut cells = vec![Cell::Markdown(md)];
    if let Some(first) = shared.first() {
        let starter = read(root, &starter_file(&dir, first.meta().starter))?;
        cells.push(Cell::Code(without_header(&starter)));
    }
    for ex in &shared {
        cells.push(Cell::Code(grade_cell(ex.name())));
    }
    for ex in &own {
        cells.push(Cell::Markdown(intro(*ex)?));
        let starter = read(root, &starter_file(&dir, ex.meta().starter))?;
        cells.push(Cell::Code(candle_cell(&starter)));
        cells.push(Cell::Code(grade_cell(ex.name())));
    }
    Ok(cells)
}

/// The code cells of `lesson`'s exercise as its notebook shows them (starters and grading
/// cells, in order); empty for a lesson without one.
///
/// # Errors
/// As [`notebook_cells`].
pub fn exercise_code_cells(root: &Path, lesson: &Lesson) -> Result<Vec<String>, BuildError> {
    if lesson.exercise.is_none() {
        return Ok(Vec::new());
    }
    let file = format!("{}/{}.rs", recipe_dir(), folder(lesson));
    Ok(exercise_cells(lesson, &file, root)?
        .into_iter()
        .filter_map(|c| match c {
            Cell::Code(code) => Some(code),
            Cell::Markdown(_) => None,
        })
        .collect())
}

/// The code cells that define the reference solutions of `lesson`'s exercises (from
/// `root/lessons/NN-slug/`), in the notebook's form; empty for a lesson without one. Run
/// them, then each exercise's [`grade_cell`], to check that the solutions pass in a kernel.
///
/// # Errors
/// [`BuildError::Unregistered`], [`BuildError::NoIntro`] or [`BuildError::Read`].
pub fn solution_cells(root: &Path, lesson: &Lesson) -> Result<Vec<String>, BuildError> {
    let dir = format!("lessons/{}", folder(lesson));
    let file = format!("notebooks/src/{}.rs", folder(lesson));
    let (shared, own) = by_starter(registered(lesson, &file)?);
    let mut cells = Vec::new();
    if let Some(first) = shared.first() {
        let solution = read(root, &format!("{dir}/{}", first.meta().solution))?;
        cells.push(without_header(&solution));
    }
    for ex in &own {
        let solution = read(root, &format!("{dir}/{}", ex.meta().solution))?;
        cells.push(candle_cell(&solution));
    }
    Ok(cells)
}
