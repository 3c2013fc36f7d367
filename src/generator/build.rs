//! The notebook generator: the cells of `notebooks/NN-slug.ipynb`, from the lesson and a
//! recipe of code cells.
//!
//! A recipe is `notebooks/src/NN-slug.rs`: code cells separated by `// %%` lines (text
//! before the first one is the recipe's own header), `// %% step: TITLE` where the lesson's
//! step TITLE begins, and `// %% exercise` where the exercise goes. The generator adds the
//! rest from `lessons/NN-slug/`: a title cell, the `:dep` cell, each step's explanation
//! (its notebook face, [`crate::lesson::face`]) with the seed's Python and the Rust code by
//! anchor, cells showing the step's live values (each value and view once per notebook:
//! a step shows only what no earlier step of the notebook has shown), and the exercise with
//! its grading cells.
//!
//! [`super::ipynb`] writes the cells (and their outputs) as a notebook file; executing them
//! needs the evcxr engine (`super::kernel`, feature `notebook-runner`). Regenerate every
//! notebook with [`REGENERATE`].
//!
//! ```
//! use ppo_tutor::lesson::Course;
//! use ppo_tutor::generator::build::{Cell, cells_from_recipe};
//! use std::path::Path;
//!
//! let course = Course::embedded()?;
//! let lesson = course.get("what-is-ppo").ok_or("no lesson 1")?;
//! let steps: String = lesson.steps.iter().map(|s| format!("// %% step: {}\n", s.title)).collect();
//! let recipe = format!("// %%\nlet x = 1;\n{steps}");
//! let cells = cells_from_recipe(lesson, &recipe, "recipe.rs", Path::new(env!("CARGO_MANIFEST_DIR")))?;
//! assert!(matches!(&cells[1], Cell::Code(c) if c.contains(r#":dep ppo-engine = { path = "../crates/ppo-engine" }"#)
//!     && c.ends_with("claim_work_folder();")));
//! assert_eq!(cells[2], Cell::Code("let x = 1;".to_string()));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use std::fmt::Write as _;
use std::path::Path;

use crate::i18n::{Lang, t};
use crate::lesson::face::Face;
use crate::lesson::{Course, Lesson, View};
use crate::tr;

mod exercise;

use exercise::exercise_cells;
pub use exercise::{exercise_code_cells, grade_cell, solution_cells};

/// The command that regenerates the notebooks (sources and outputs), run in the repository.
pub const REGENERATE: &str = "cargo run --features notebook-runner -- dev notebooks";

/// The first cell of every notebook: evcxr's cache of compiled dependencies (candle's build
/// is then done once, not in every new kernel), and the engine crate, resolved from
/// `notebooks/` as Jupyter does: no terminal app, command line, grading or generator.
/// evcxr never caches a local crate, so edits to it are always rebuilt.
pub const DEP_CELL: &str = ":cache 4000\n:dep ppo-engine = { path = \"../crates/ppo-engine\" }";

/// The first cell's last line: the kernel takes its folder's evcxr work folder
/// (`notebooks/evcxr.toml`) for its lifetime, and warns if another live kernel has it (two
/// kernels compiling in one work folder at once overwrite each other's cells).
pub const CLAIM_LINE: &str = "ppo_engine::notebook::claim_work_folder();";

/// The grading crate, which a lesson with exercises adds to its first cell: its cells grade
/// the exercises in place (`ppo_grade::in_process`).
pub const GRADE_DEP: &str = ":dep ppo-grade = { path = \"../crates/ppo-grade\" }";

/// The first cell of `lesson`'s notebook: [`DEP_CELL`], and [`GRADE_DEP`] when the lesson
/// has exercises.
///
/// A Chinese notebook (in `notebooks/zh/`, current language [`Lang::Zh`]) first sets its
/// kernel's language: evcxr links the crate into every cell anew, so the library reads it
/// from `PPO_TUTOR_LANG`, which `:env` sets for the runtime that `:restart` starts.
#[must_use]
pub fn dep_cell(lesson: &Lesson) -> String {
    let mut cell = DEP_CELL.to_string();
    if lesson.exercise.is_some() {
        cell = format!("{cell}\n{GRADE_DEP}");
    }
    cell = format!("{cell}\n{CLAIM_LINE}");
    match Lang::current() {
        Lang::En => cell,
        Lang::Zh => format!(
            ":env PPO_TUTOR_LANG=zh\n:restart\n{}",
            cell.replace("path = \"../crates/", "path = \"../../crates/")
        ),
    }
}

/// Where the current language's notebooks are, relative to the repository:
/// `notebooks` (English) or `notebooks/zh`.
#[must_use]
pub fn notebook_dir() -> &'static str {
    Lang::current().pick("notebooks", "notebooks/zh")
}

/// Where the current language's recipes are: `notebooks/src` or `notebooks/src/zh`.
#[must_use]
pub fn recipe_dir() -> &'static str {
    Lang::current().pick("notebooks/src", "notebooks/src/zh")
}

/// The current language's notebook of lesson folder `folder`, e.g. `notebooks/zh/07-td-target.ipynb`.
#[must_use]
pub fn notebook_file(folder: &str) -> String {
    format!("{}/{folder}.ipynb", notebook_dir())
}

/// One cell of a generated notebook.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Cell {
    /// Text: a title, a step's explanation, the exercise's instructions.
    Markdown(String),
    /// Rust the kernel runs.
    Code(String),
}

/// What can go wrong building a notebook; each message names the file and the fix.
#[derive(Debug, thiserror::Error)]
pub enum BuildError {
    /// A file or folder could not be read.
    #[error("{path}: cannot read it: {source}")]
    Read {
        /// The path, relative to the repository.
        path: String,
        /// The I/O error.
        source: std::io::Error,
    },
    /// `notebooks/src/` does not hold exactly one recipe per lesson.
    #[error(
        "notebooks/src/ must hold one recipe per lesson, named after its folder:\n  \
         lessons: {lessons:?}\n  recipes: {recipes:?}"
    )]
    Recipes {
        /// The lesson folders, in order.
        lessons: Vec<String>,
        /// The recipes found (file names without `.rs`), sorted.
        recipes: Vec<String>,
    },
    /// A `// %% step:` marker past the lesson's last step.
    #[error(
        "{file}: step '{title}' is beyond the lesson's last step; remove the marker or add \
         the step to the lesson"
    )]
    ExtraStep {
        /// The recipe.
        file: String,
        /// The marker's title.
        title: String,
    },
    /// A `// %% step:` marker whose title is not the lesson's next step.
    #[error(
        "{file}: step {index} is '{lesson}' in the lesson, '{recipe}' in the recipe; the \
         markers must name the lesson's steps in order"
    )]
    WrongStep {
        /// The recipe.
        file: String,
        /// The step's number, from 1.
        index: usize,
        /// The step's title in the lesson.
        lesson: String,
        /// The marker's title.
        recipe: String,
    },
    /// The recipe stops before the lesson's last step.
    #[error(
        "{file}: the recipe covers {covered} of the lesson's {total} steps; add `// %% step: {next}`"
    )]
    MissingStep {
        /// The recipe.
        file: String,
        /// Steps the recipe has markers for.
        covered: usize,
        /// Steps in the lesson.
        total: usize,
        /// The title of the first step without a marker.
        next: String,
    },
    /// The lesson has an exercise and the recipe no `// %% exercise` marker.
    #[error("{file}: the lesson has an exercise; add a `// %% exercise` cell marker")]
    MissingExercise {
        /// The recipe.
        file: String,
    },
    /// A `// %% exercise` marker in a lesson without an exercise.
    #[error(
        "{file}: `// %% exercise` in a lesson without an exercise; remove the marker or add \
         an [exercise] to the lesson's front matter"
    )]
    NoExercise {
        /// The recipe.
        file: String,
    },
    /// A notebook folder's `evcxr.toml` does not name evcxr's work folder.
    #[error(
        "{file}: {why}; it must hold `[evcxr]` with `tmpdir = \"...\"`, the folder (relative \
         to this one) where evcxr builds the notebooks' cells"
    )]
    WorkFolder {
        /// The file.
        file: String,
        /// What is wrong with it.
        why: String,
    },
    /// An exercise the grading registry does not have.
    #[error(
        "{file}: the lesson's exercise `{name}` is not in the registry; add it to \
         crates/ppo-grade/src/exercises.rs (CONTRIBUTING.md, \"Adding an exercise\")"
    )]
    Unregistered {
        /// The recipe.
        file: String,
        /// The exercise.
        name: String,
    },
    /// An exercise built with cargo (on candle) whose `exercise.toml` entry has no
    /// `notebook` text to introduce its cell.
    #[error(
        "lessons/{lesson}/exercise.toml: exercise `{name}` has its own notebook cell; add \
         `notebook = \"...\"` under [exercise.other] to introduce it"
    )]
    NoIntro {
        /// The lesson folder.
        lesson: String,
        /// The exercise.
        name: String,
    },
}

/// Where evcxr builds a notebook folder's cells: the `tmpdir` of `dir/evcxr.toml`
/// (`notebooks/evcxr.toml`, `notebooks/zh/evcxr.toml`: `.evcxr` in each), resolved against
/// `dir` as evcxr resolves it against the kernel's working folder. A fixed work folder lets every kernel of
/// that folder reuse the previous kernel's build (cargo finds `ppo-engine` unchanged and
/// skips it), so a fresh kernel's first cell takes seconds, not the engine's whole build.
///
/// # Errors
/// [`BuildError::Read`] if the file cannot be read, [`BuildError::WorkFolder`] if it has no
/// `[evcxr] tmpdir` string.
pub fn work_folder(dir: &Path) -> Result<std::path::PathBuf, BuildError> {
    let file = dir.join("evcxr.toml");
    let text = std::fs::read_to_string(&file).map_err(|source| BuildError::Read {
        path: file.display().to_string(),
        source,
    })?;
    let bad = |why: String| BuildError::WorkFolder {
        file: file.display().to_string(),
        why,
    };
    let value: toml::Table = text
        .parse()
        .map_err(|e: toml::de::Error| bad(e.to_string()))?;
    let tmpdir = value
        .get("evcxr")
        .and_then(|e| e.get("tmpdir"))
        .and_then(toml::Value::as_str)
        .ok_or_else(|| bad("no `tmpdir` string under `[evcxr]`".into()))?;
    Ok(dir.join(tmpdir))
}

/// The folder name of a lesson, `NN-slug`: its notebook is `notebooks/NN-slug.ipynb`, its
/// recipe `notebooks/src/NN-slug.rs`, its files are in `lessons/NN-slug/`.
#[must_use]
pub fn folder(lesson: &Lesson) -> String {
    format!("{:02}-{}", lesson.order, lesson.id)
}

/// The lesson folders of `course`, in order, after checking that `root/notebooks/src/`
/// holds one recipe for each and nothing else.
///
/// # Errors
/// [`BuildError::Recipes`] listing both sides, or [`BuildError::Read`].
pub fn recipe_folders(root: &Path, course: &Course) -> Result<Vec<String>, BuildError> {
    let lessons: Vec<String> = course.lessons.iter().map(folder).collect();
    let recipes = stems(root, recipe_dir(), ".rs")?;
    if recipes != lessons {
        return Err(BuildError::Recipes { lessons, recipes });
    }
    Ok(lessons)
}

/// The sorted names, without `ext`, of the files in `root/dir` that end in `ext`.
///
/// # Errors
/// [`BuildError::Read`] naming `dir`.
pub fn stems(root: &Path, dir: &str, ext: &str) -> Result<Vec<String>, BuildError> {
    let read_error = |source| BuildError::Read {
        path: dir.to_string(),
        source,
    };
    let mut names = Vec::new();
    for entry in std::fs::read_dir(root.join(dir)).map_err(read_error)? {
        let name = entry.map_err(read_error)?.file_name();
        if let Some(stem) = name.to_string_lossy().strip_suffix(ext) {
            names.push(stem.to_string());
        }
    }
    names.sort();
    Ok(names)
}

/// Reads `root/path`.
fn read(root: &Path, path: &str) -> Result<String, BuildError> {
    std::fs::read_to_string(root.join(path)).map_err(|source| BuildError::Read {
        path: path.to_string(),
        source,
    })
}

/// The cells of `lesson`'s notebook, from its recipe `root/notebooks/src/NN-slug.rs`.
///
/// # Errors
/// See [`cells_from_recipe`]; also [`BuildError::Read`] for the recipe.
pub fn notebook_cells(root: &Path, lesson: &Lesson) -> Result<Vec<Cell>, BuildError> {
    let file = format!("{}/{}.rs", recipe_dir(), folder(lesson));
    let recipe = read(root, &file)?;
    cells_from_recipe(lesson, &recipe, &file, root)
}

/// The cells of `lesson`'s notebook from the text of its recipe (`file` names it in
/// errors); the exercise's starter files are read from `root/lessons/NN-slug/`.
///
/// # Errors
/// A [`BuildError`] when the recipe's step markers are not the lesson's steps in order,
/// the exercise marker is missing or extra, an exercise cannot be graded in a cell, or a
/// starter file cannot be read.
pub fn cells_from_recipe(
    lesson: &Lesson,
    recipe: &str,
    file: &str,
    root: &Path,
) -> Result<Vec<Cell>, BuildError> {
    let mut cells = vec![
        Cell::Markdown(title_markdown(lesson)),
        Cell::Code(dep_cell(lesson)),
    ];
    let mut next_step = 0;
    // The step whose live values are shown before the next marker, and what the notebook
    // has shown so far.
    let mut pending_show: Option<usize> = None;
    let mut shown = Shown::default();
    let mut exercise_done = false;
    // Recipes name steps by their English titles, in either language.
    let english: Vec<String> = match Lang::current() {
        Lang::En => lesson.steps.iter().map(|s| s.title.clone()).collect(),
        Lang::Zh => Course::embedded_in(Lang::En)
            .ok()
            .and_then(|c| c.get(&lesson.id).cloned())
            .map(|l| l.steps.into_iter().map(|s| s.title).collect())
            .unwrap_or_default(),
    };
    for piece in parse_recipe(recipe) {
        match piece {
            Piece::Code(code) => {
                if rebinds_snapshot(&code) {
                    shown = Shown::default();
                }
                cells.push(Cell::Code(code));
            }
            Piece::Step(title) => {
                let Some(step_title) = english.get(next_step) else {
                    return Err(BuildError::ExtraStep {
                        file: file.to_string(),
                        title,
                    });
                };
                if *step_title != title {
                    return Err(BuildError::WrongStep {
                        file: file.to_string(),
                        index: next_step + 1,
                        lesson: step_title.clone(),
                        recipe: title,
                    });
                }
                if let Some(k) = pending_show.take() {
                    cells.extend(step_end_cells(lesson, k, &mut shown));
                }
                cells.push(Cell::Markdown(step_markdown(lesson, next_step)));
                pending_show = Some(next_step);
                next_step += 1;
            }
            Piece::Exercise => {
                if let Some(k) = pending_show.take() {
                    cells.extend(step_end_cells(lesson, k, &mut shown));
                }
                cells.extend(exercise_cells(lesson, file, root)?);
                let course = course_in_current_language();
                cells.extend(course.and_then(|c| reveal_cell(&c, lesson)));
                exercise_done = true;
            }
        }
    }
    if let Some(k) = pending_show.take() {
        cells.extend(step_end_cells(lesson, k, &mut shown));
    }
    if next_step != lesson.steps.len() {
        return Err(BuildError::MissingStep {
            file: file.to_string(),
            covered: next_step,
            total: lesson.steps.len(),
            next: english.get(next_step).cloned().unwrap_or_default(),
        });
    }
    if lesson.exercise.is_some() && !exercise_done {
        return Err(BuildError::MissingExercise {
            file: file.to_string(),
        });
    }
    cells.extend(quiz_cells(lesson));
    Ok(cells)
}

/// The embedded course in the current language, for what a notebook shows of other
/// lessons (`None` if it does not load, which the content check reports).
fn course_in_current_language() -> Option<Course> {
    Course::embedded().ok()
}

/// The lesson's quiz, last: a heading, then for each question its text (a markdown cell)
/// and a code cell that grades an answer in place, generated unanswered (`'?'`, `"?"`) so
/// that a prediction's live value stays hidden until the learner commits to a number. A
/// question that shows numbers of the run has a cell between the two that shows it with
/// this notebook's (`quiz::ask`); a choice the run decides is graded with
/// `quiz::answer_live`.
#[must_use]
pub fn quiz_cells(lesson: &Lesson) -> Vec<Cell> {
    use crate::lesson::quiz::{Answer, QuestionKind, letter_of, template};
    if lesson.quiz.is_empty() {
        return Vec::new();
    }
    let mut cells = vec![
        Cell::Markdown(
            t(
                "## Check your understanding\n\nAnswer each question in the code cell below it: \
                 replace `'?'` with the letter of your choice, or `\"?\"` with your prediction \
                 (a number), and run the cell. A prediction is graded against the live value of \
                 this notebook's agent (`snap`), shown only once you have answered.",
                "## 小测验：检验你的理解\n\n在每道题下面的代码单元格里作答：把 `'?'` 换成你选的字母，\
                 或把 `\"?\"` 换成你预测的数（一个数字），然后运行单元格。预测题对照本笔记本中智能体\
                 （`snap`）的实时数值评分，实时数值只在你作答之后才显示。",
            )
            .to_string(),
        ),
        Cell::Code("use ppo_engine::lesson::quiz;".to_string()),
    ];
    for (i, question) in lesson.quiz.iter().enumerate() {
        let n = i + 1;
        let givens = !template::names(&question.prompt).is_empty();
        let mut text = tr!(
            "**Question {n}.** {}",
            "**第 {n} 题。** {}",
            template::fill(&question.prompt, &crate::lesson::Snapshot::default())
        );
        let code = match &question.kind {
            QuestionKind::Choice {
                choices, answer, ..
            } => {
                text.push('\n');
                for (k, choice) in choices.iter().enumerate() {
                    let _ = write!(text, "\n- **{})** {choice}", letter_of(k));
                }
                match answer {
                    Answer::Letter(_) => format!("quiz::answer(\"{}\", {n}, '?')", lesson.id),
                    Answer::Live(_) => {
                        format!("quiz::answer_live(\"{}\", {n}, '?', &snap)", lesson.id)
                    }
                }
            }
            QuestionKind::Predict { tolerance, .. } if *tolerance == 0.0 => {
                text.push_str(t(
                    "\n\n(Only the exact live value counts.)",
                    "\n\n（只有与实时数值完全相等才算答对。）",
                ));
                format!("quiz::predict(\"{}\", {n}, \"?\", &snap)", lesson.id)
            }
            QuestionKind::Predict { tolerance, .. } => {
                text.push_str(&tr!(
                    "\n\n(An answer within ±{tolerance} of the live value counts.)",
                    "\n\n（与实时数值相差不超过 ±{tolerance} 即算答对。）"
                ));
                format!("quiz::predict(\"{}\", {n}, \"?\", &snap)", lesson.id)
            }
        };
        if givens {
            text.push_str(t(
                "\n\n(Each … is a number of this notebook's run: the cell below shows the \
                 question with them.)",
                "\n\n（每个 … 都是本笔记本这次运行中的一个数：下面的单元格会把它们填进题目里显示出来。）",
            ));
        }
        cells.push(Cell::Markdown(text));
        if givens {
            cells.push(Cell::Code(format!(
                "quiz::ask(\"{}\", {n}, &snap)",
                lesson.id
            )));
        }
        cells.push(Cell::Code(code));
    }
    cells
}

/// One piece of a recipe.
#[derive(Debug, Clone, PartialEq, Eq)]
enum Piece {
    /// A code cell, trimmed.
    Code(String),
    /// `// %% step: TITLE`.
    Step(String),
    /// `// %% exercise`.
    Exercise,
}

/// Splits a recipe at its `// %%` lines; text before the first one and empty cells are
/// dropped.
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

/// The notebook's first cell.
fn title_markdown(lesson: &Lesson) -> String {
    let (engine, engine_zh) = lesson.env.spec().engine_name;
    tr!(
        "# Lesson {n}: {title}\n\n{summary}\n\nThis notebook mirrors lesson {n} of the terminal app \
         (`cargo run --release`), on the [evcxr](https://github.com/evcxr/evcxr) Rust \
         kernel. Every number below comes from {engine} of the `ppo-engine` crate. The \
         first cell compiles it (and `ppo-grade` in a lesson with exercises): the very \
         first time, with candle, in several minutes. Kernels keep that build in `.evcxr` \
         beside the notebooks (`evcxr.toml`), so in a later kernel the first cell takes about \
         ten seconds, or about a minute after the crate has changed. After that each cell \
         takes a second or two. Run one notebook at a time: kernels of one folder share its \
         build.",
        "# 第 {n} 课：{title}\n\n{summary}\n\n本笔记本对应终端应用（`cargo run --release`）的第 {n} 课，\
         运行在 [evcxr](https://github.com/evcxr/evcxr) Rust 内核上。下面的每个数都来自 \
         `ppo-engine` 库中{engine_zh}。第一个单元格会编译这个库（有练习的课还有 `ppo-grade`）：\
         第一次连同 candle 一起编译，需要几分钟。内核把编译结果留在笔记本旁边的 `.evcxr` 文件夹里\
         （见 `evcxr.toml`），所以之后新开的内核，第一个单元格只需十秒左右；库的代码改动过，则约需一分钟。\
         此后每个单元格只需一两秒。请一次只运行一个笔记本：同一文件夹的内核共用这份编译结果。",
        n = lesson.order,
        title = lesson.title,
        summary = lesson.summary,
    )
}

/// Step `k`'s explanation (its notebook face), the seed's Python and the Rust code (by
/// anchor).
fn step_markdown(lesson: &Lesson, k: usize) -> String {
    let step = &lesson.steps[k];
    let mut md = format!(
        "## {}. {}\n\n{}\n",
        k + 1,
        step.title,
        step.parts(Face::Notebook).0
    );
    if !step.python.is_empty() {
        let source = match Lang::current() {
            Lang::En => format!("The {}", lesson.env.python_source()),
            Lang::Zh => lesson.env.source_name().to_string(),
        };
        let _ = write!(
            md,
            "\n**{source}{}{}**\n\n```python\n{}\n```\n",
            t(" (PyTorch)", "（PyTorch）"),
            t(":", "："),
            step.python.trim()
        );
    }
    if let Some(listing) = (!step.code.is_empty())
        .then(|| crate::lesson::reveal::listing(&step.code, &passed_before(lesson)))
        .flatten()
    {
        md.push_str(&listing_markdown(&listing));
    }
    md
}

/// What a notebook counts as passed before its own exercise: the exercises of earlier
/// lessons (a notebook has no progress file; the course is read in order). Code that an
/// exercise of this lesson or a later one asks for is a note ([`crate::lesson::reveal`]).
fn passed_before(lesson: &Lesson) -> impl Fn(&str) -> bool + use<> {
    let order = lesson.order;
    move |e: &str| crate::lesson::reveal::gate(e).is_some_and(|g| g.lesson < order)
}

/// An anchor's code as a notebook shows it: a bold line naming the file, then the code.
fn listing_markdown(listing: &crate::lesson::reveal::Listing) -> String {
    let krate = listing.krate;
    format!(
        "\n**{krate} (`crates/{krate}/src/{}`){}**\n\n```rust\n{}\n```\n",
        listing.path,
        t(":", "："),
        listing.text().trim_end()
    )
}

/// The cell after the exercise's grading cells: the crate's version of what the lesson's
/// exercises ask, which the steps above showed as notes. Each anchor a step of this lesson
/// or an earlier one shows with a region of these exercises is listed once, with every
/// region of this lesson's and earlier lessons' exercises shown; a region that a later
/// exercise also asks for stays a note, and the cell says which. `None` when the lesson's
/// exercises give away no code the course shows.
#[must_use]
pub fn reveal_cell(course: &Course, lesson: &Lesson) -> Option<Cell> {
    use crate::lesson::reveal::{self, Gate};
    let ex = lesson.exercise.as_ref()?;
    let order = lesson.order;
    let after = |e: &str| reveal::gate(e).is_some_and(|g| g.lesson <= order);
    let regions: Vec<&String> = reveal::exercises()
        .iter()
        .filter(|(g, _)| ex.names().contains(&g.exercise.as_str()))
        .flat_map(|(_, r)| r)
        .collect();
    // The anchors the steps so far showed, once each: this lesson's first, then the earlier
    // lessons' in course order.
    let mut anchors: Vec<&str> = Vec::new();
    let earlier = course.lessons.iter().filter(|l| l.order < order);
    for l in std::iter::once(lesson).chain(earlier) {
        for step in &l.steps {
            if !step.code.is_empty() && !anchors.contains(&step.code.as_str()) {
                anchors.push(&step.code);
            }
        }
    }
    let mut listings = String::new();
    let mut still: Vec<Gate> = Vec::new();
    for anchor in anchors {
        let inside: Vec<String> = std::iter::once(anchor.to_string())
            .chain(crate::lesson::anchor::nested(anchor))
            .collect();
        if !regions.iter().any(|r| inside.contains(r)) {
            continue;
        }
        let Some(listing) = reveal::listing(anchor, &after) else {
            continue;
        };
        for g in listing.hidden() {
            if !still.contains(g) {
                still.push(g.clone());
            }
        }
        if listing.shown.iter().any(|g| g.lesson == order) {
            listings.push_str(&listing_markdown(&listing));
        }
    }
    if listings.is_empty() && still.is_empty() {
        return None;
    }
    still.sort_by_key(|g| g.lesson);
    let note = reveal::note(&still);
    let mut md = t("### The crate's version\n\n", "### 本库的写法\n\n").to_string();
    if listings.is_empty() {
        md.push_str(&tr!(
            "The code the steps above showed as notes is also what a later exercise asks for: \
             {note}.\n",
            "上面各节用一行说明代替的代码，也是后面练习要写的：{note}。\n"
        ));
        return Some(Cell::Markdown(md));
    }
    md.push_str(t(
        "Once the grading cells above pass, compare your code with what ppo-engine runs: the \
         steps above showed these lines as notes.\n",
        "上面的评分单元格通过之后，把你的代码与 ppo-engine 实际运行的代码对照：上面各节只用一行\
         说明代替了这些代码。\n",
    ));
    md.push_str(&listings);
    if !still.is_empty() {
        md.push_str(&tr!(
            "\nThe rest is also what a later exercise asks for: {note}.\n",
            "\n其余部分也是后面练习要写的：{note}。\n"
        ));
    }
    Some(Cell::Markdown(md))
}

/// The comment that opens a cell of a step's live values.
pub const LIVE_VALUES: &str = "// This step's live values, from the training run `snap`:";

/// [`LIVE_VALUES`] in the current language.
#[must_use]
pub fn live_values_comment() -> &'static str {
    t(LIVE_VALUES, "// 本节的实时数值，来自训练运行 `snap`：")
}

/// What a notebook has shown of its snapshot `snap` so far: live values by name, views
/// (`plot`, `cartpole`, `clip_chart`) by name, experiments as `lab:NAME`.
type Shown = std::collections::BTreeSet<String>;

/// Whether a recipe cell binds `snap` anew (`let snap` or `let mut snap`): what the
/// notebook showed of the old snapshot says nothing about the new one.
fn rebinds_snapshot(code: &str) -> bool {
    code.lines().any(|l| {
        let l = l.trim_start();
        ["let snap", "let mut snap"].iter().any(|p| {
            l.strip_prefix(p)
                .is_some_and(|rest| rest.starts_with([' ', ':', '=']))
        })
    })
}

/// The cells that end step `k`: its live values and views ([`show_cells`]), then what its
/// experiment's run found, where the step asks for a prediction first (the text after its
/// [`AFTER_THE_RUN`](crate::lesson::AFTER_THE_RUN) line).
fn step_end_cells(lesson: &Lesson, k: usize, shown: &mut Shown) -> Vec<Cell> {
    let mut cells = show_cells(lesson, k, shown);
    if let (_, Some(after)) = lesson.steps[k].parts(Face::Notebook) {
        cells.push(Cell::Markdown(after));
    }
    cells
}

/// The cell that asks for a prediction before experiment `e` runs: the question and the
/// lettered settings as comments, and the letter to fill in.
fn prediction_cell(e: crate::ppo::lab::Experiment, outcome: crate::ppo::lab::Outcome) -> Cell {
    let base = crate::ppo::PpoConfig::default();
    let choices: String = outcome
        .choices(e, &base)
        .iter()
        .map(|c| format!("//   {c}\n"))
        .collect();
    Cell::Code(tr!(
        "// {}\n{choices}// Write the letter of your answer between the quotes, then run this cell and the next two;\n\
         // the cell after the experiment grades it against the run.\n\
         let prediction = ' ';",
        "// {}\n{choices}// 把答案的字母写在引号之间，然后运行本单元格和后面两个；\n\
         // 实验之后的单元格会用这次运行的结果给它评分。\n\
         let prediction = ' ';",
        outcome.question(LAB_SEEDS.len())
    ))
}

/// The seeds a notebook's experiment cells run.
const LAB_SEEDS: [u64; 5] = [0, 1, 2, 3, 4];

/// The cells that show step `k`'s live values and views, less those `shown` already holds
/// (which it then records); none when the step shows nothing new.
fn show_cells(lesson: &Lesson, k: usize, shown: &mut Shown) -> Vec<Cell> {
    let step = &lesson.steps[k];
    let mut fresh = |key: String| shown.insert(key);
    let tensors: Vec<String> = step
        .show
        .iter()
        .filter(|n| !crate::lesson::VIEWS.contains(&n.as_str()))
        .filter(|n| fresh((*n).clone()))
        .map(|n| format!("{n:?}"))
        .collect();
    let mut cells = Vec::new();
    if !tensors.is_empty() {
        cells.push(Cell::Code(format!(
            "{}\nsnap.show(&[{}])",
            live_values_comment(),
            tensors.join(", ")
        )));
    }
    for view in step.show.iter().filter_map(|v| View::from_name(v)) {
        let key = match (view, step.lab) {
            (View::Lab, Some(e)) => format!("lab:{}", e.name()),
            (v, _) => v.name().to_string(),
        };
        if !fresh(key) {
            continue;
        }
        match view {
            View::Plot => cells.push(Cell::Code(tr!(
                "snap.return_plot(\"PPO on {}\")?",
                "snap.return_plot(\"{} 上的 PPO\")?",
                lesson.env.as_str()
            ))),
            View::Pendulum => cells.push(Cell::Code("snap.pendulum()".to_string())),
            View::CartPole => cells.push(Cell::Code("snap.cartpole()".to_string())),
            View::ClipChart => cells.push(Cell::Code("snap.clip_chart()".to_string())),
            View::Lab => {
                if let (Some(e), Some(outcome)) = (step.lab, step.predict) {
                    cells.push(prediction_cell(e, outcome));
                }
                if let Some(e) = step.lab {
                    cells.push(Cell::Code(tr!(
                        "// This step's experiment, as `ppo-tutor lab {name}` runs it in a terminal:\n\
                         // every setting over seeds 0-4, LAB_EPISODES episodes each, on every core.\n\
                         let lab = ppo_engine::notebook::lab({name:?}, &[0, 1, 2, 3, 4], LAB_EPISODES)?;\n\
                         lab",
                        "// 本节的实验，与终端里 `ppo-tutor lab {name}` 的运行方式相同：\n\
                         // 每种设置跑随机种子 0-4，各 LAB_EPISODES 个回合，用上所有 CPU 核。\n\
                         let lab = ppo_engine::notebook::lab({name:?}, &[0, 1, 2, 3, 4], LAB_EPISODES)?;\n\
                         lab",
                        name = e.name()
                    )));
                }
                if let (Some(_), Some(outcome)) = (step.lab, step.predict) {
                    cells.push(Cell::Code(tr!(
                        "// Your prediction, graded against the run above:\n\
                         for line in lab.prediction_lines({:?}, prediction) {{\n    println!(\"{{line}}\");\n}}",
                        "// 你的预测，用上面这次运行的结果评分：\n\
                         for line in lab.prediction_lines({:?}, prediction) {{\n    println!(\"{{line}}\");\n}}",
                        outcome.name()
                    )));
                }
            }
            // The probe runs in the lesson's own code cells (it takes seconds).
            View::TrustRegion => {}
        }
    }
    cells
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lesson::{Exercise, Step};

    fn root() -> &'static Path {
        Path::new(env!("CARGO_MANIFEST_DIR"))
    }

    fn step(title: &str, show: &[&str]) -> Step {
        Step {
            title: title.into(),
            python: String::new(),
            code: String::new(),
            show: show.iter().map(|s| (*s).to_string()).collect(),
            body: format!("About {title}."),
            lab: None,
            predict: None,
        }
    }

    fn lesson(steps: Vec<Step>) -> Lesson {
        Lesson {
            id: "made-up".into(),
            title: "Made up".into(),
            summary: "A lesson for the generator's tests.".into(),
            order: 99,
            steps,
            exercise: None,
            quiz: Vec::new(),
            env: crate::lesson::AgentKind::CartPole,
        }
    }

    #[test]
    fn a_recipe_splits_at_its_markers() {
        let text = "//! header\n// %%\nlet a = 1;\n\n// %% step: One\n// %%\n\n// %% exercise\nx\n";
        assert_eq!(
            parse_recipe(text),
            vec![
                Piece::Code("let a = 1;".into()),
                Piece::Step("One".into()),
                Piece::Exercise,
                Piece::Code("x".into()),
            ]
        );
    }

    #[test]
    fn show_cells_follow_the_step_before_the_next_heading() -> Result<(), BuildError> {
        let l = lesson(vec![step("One", &["td_target", "plot"]), step("Two", &[])]);
        let cells = cells_from_recipe(&l, "// %% step: One\na\n// %% step: Two\n", "r.rs", root())?;
        let code: Vec<&Cell> = cells.iter().skip(3).collect();
        assert_eq!(
            code,
            [
                &Cell::Code("a".into()),
                &Cell::Code(format!("{LIVE_VALUES}\nsnap.show(&[\"td_target\"])")),
                &Cell::Code("snap.return_plot(\"PPO on CartPole-v1\")?".into()),
                &Cell::Markdown("## 2. Two\n\nAbout Two.\n".into()),
            ]
        );
        Ok(())
    }

    #[test]
    fn a_predicted_experiment_asks_before_it_runs_and_shows_its_findings_after()
    -> Result<(), BuildError> {
        let _en = crate::i18n::Lang::En.scoped();
        let mut lab = step("One", &["lab"]);
        lab.lab = Some(crate::ppo::lab::Experiment::Eps);
        lab.predict = Some(crate::ppo::lab::Outcome::EndsHighest);
        lab.body = "Before.\n<!-- after the run -->\nFound.\n".into();
        let l = lesson(vec![lab, step("Two", &[])]);
        let cells = cells_from_recipe(&l, "// %% step: One\n// %% step: Two\n", "r.rs", root())?;
        let rest: Vec<&Cell> = cells.iter().skip(2).collect();
        let code = |i: usize| match rest[i] {
            Cell::Code(c) => c.as_str(),
            Cell::Markdown(m) => m.as_str(),
        };
        assert!(matches!(rest[0], Cell::Markdown(_)), "{rest:?}");
        assert!(
            code(0).contains("Before.") && !code(0).contains("Found."),
            "{}",
            code(0)
        );
        assert!(
            code(1).contains("which setting will end highest"),
            "{}",
            code(1)
        );
        assert!(code(1).contains("//   c) no clip") && code(1).ends_with("let prediction = ' ';"));
        assert!(
            code(2).contains("ppo_engine::notebook::lab(\"eps\""),
            "{}",
            code(2)
        );
        assert!(code(3).contains("lab.prediction_lines(\"ends_highest\", prediction)"));
        assert_eq!(rest[4], &Cell::Markdown("Found.".into()));
        assert_eq!(rest[5], &Cell::Markdown("## 2. Two\n\nAbout Two.\n".into()));
        Ok(())
    }

    /// The code cells after the title and the `:dep` cell, as text.
    fn code_cells(cells: &[Cell]) -> Vec<&str> {
        cells
            .iter()
            .skip(2)
            .filter_map(|c| match c {
                Cell::Code(code) => Some(code.as_str()),
                Cell::Markdown(_) => None,
            })
            .collect()
    }

    #[test]
    fn a_step_shows_only_what_no_earlier_step_showed() -> Result<(), BuildError> {
        let l = lesson(vec![
            step("One", &["td_delta", "advantage", "clip_chart"]),
            step("Two", &["hyper", "td_delta", "advantage"]),
            step("Three", &["td_delta", "advantage", "clip_chart"]),
            step("Four", &["dones", "advantage", "plot"]),
        ]);
        let recipe = "// %% step: One\n// %% step: Two\n// %% step: Three\n// %% step: Four\n";
        let cells = cells_from_recipe(&l, recipe, "r.rs", root())?;
        assert_eq!(
            code_cells(&cells),
            [
                format!("{LIVE_VALUES}\nsnap.show(&[\"td_delta\", \"advantage\"])").as_str(),
                "snap.clip_chart()",
                format!("{LIVE_VALUES}\nsnap.show(&[\"hyper\"])").as_str(),
                // Step three shows nothing new: no cell at all.
                format!("{LIVE_VALUES}\nsnap.show(&[\"dones\"])").as_str(),
                "snap.return_plot(\"PPO on CartPole-v1\")?",
            ]
        );
        // The comment speaks of the step, not of the app.
        assert!(!LIVE_VALUES.contains("app") && !LIVE_VALUES.contains("beside"));
        Ok(())
    }

    #[test]
    fn a_new_snapshot_shows_its_values_again() -> Result<(), BuildError> {
        let l = lesson(vec![
            step("One", &["ratio", "clip_chart"]),
            step("Two", &["ratio", "clip_chart"]),
            step("Three", &["ratio", "clip_chart"]),
        ]);
        let recipe = "// %% step: One\n// %% step: Two\nlet snap = snapshot(config, 0, 5)?;\n\
                      // %% step: Three\nlet snapshot_b = 1;\n";
        let cells = cells_from_recipe(&l, recipe, "r.rs", root())?;
        let ratio = format!("{LIVE_VALUES}\nsnap.show(&[\"ratio\"])");
        assert_eq!(
            code_cells(&cells),
            [
                ratio.as_str(),
                "snap.clip_chart()",
                "let snap = snapshot(config, 0, 5)?;",
                ratio.as_str(),
                "snap.clip_chart()",
                "let snapshot_b = 1;",
            ]
        );
        assert!(rebinds_snapshot("x\n    let mut snap: Snapshot = s;"));
        assert!(!rebinds_snapshot("let snapshot = 1;\nsnap.show(&[])"));
        Ok(())
    }

    /// Every notebook of the course shows each live value and view at most once per
    /// snapshot (a cell that binds `snap` anew starts over), and none of its generated cells
    /// repeats another.
    #[test]
    fn no_notebook_shows_a_live_value_twice() -> Result<(), Box<dyn std::error::Error>> {
        let course = Course::embedded()?;
        for l in &course.lessons {
            let cells = notebook_cells(root(), l)?;
            let mut names = std::collections::BTreeSet::new();
            for code in code_cells(&cells) {
                if rebinds_snapshot(code) {
                    // another run: what was shown of the old one says nothing of it
                    names.clear();
                }
                let shown: Vec<String> = if let Some(list) = code
                    .strip_prefix(LIVE_VALUES)
                    .and_then(|c| c.trim().strip_prefix("snap.show(&["))
                {
                    list.trim_end_matches("])")
                        .split(", ")
                        .map(str::to_string)
                        .collect()
                } else if code.starts_with("snap.") {
                    vec![code.to_string()]
                } else {
                    continue;
                };
                for name in shown {
                    assert!(
                        names.insert(name.clone()),
                        "{}: {name} is shown twice",
                        folder(l)
                    );
                }
            }
        }
        Ok(())
    }

    /// The notebook reads the notebook face of a step: `<notebook>` passages kept, `<app>`
    /// passages dropped, no tags left.
    #[test]
    fn a_step_s_markdown_is_its_notebook_face() -> Result<(), BuildError> {
        let mut one = step("One", &[]);
        one.body = "Run it<app> with `x`</app><notebook> in the next cell</notebook>.".into();
        let cells = cells_from_recipe(&lesson(vec![one]), "// %% step: One\n", "r.rs", root())?;
        assert_eq!(
            cells[2],
            Cell::Markdown("## 1. One\n\nRun it in the next cell.\n".into())
        );
        Ok(())
    }

    #[test]
    fn a_step_not_in_the_lesson_names_the_recipe() {
        let l = lesson(vec![step("One", &[])]);
        let err = cells_from_recipe(
            &l,
            "// %% step: One\n// %% step: Two\n",
            "notebooks/src/99-made-up.rs",
            root(),
        )
        .err()
        .map(|e| e.to_string())
        .unwrap_or_default();
        assert!(
            err.starts_with("notebooks/src/99-made-up.rs: step 'Two' is beyond"),
            "{err}"
        );
    }

    #[test]
    fn steps_out_of_order_or_missing_are_errors() {
        let l = lesson(vec![step("One", &[]), step("Two", &[])]);
        let wrong = cells_from_recipe(&l, "// %% step: Two\n", "r.rs", root());
        assert!(
            matches!(&wrong, Err(BuildError::WrongStep { index: 1, recipe, .. }) if recipe == "Two"),
            "{wrong:?}"
        );
        let short = cells_from_recipe(&l, "// %% step: One\n", "r.rs", root());
        let msg = short.err().map(|e| e.to_string()).unwrap_or_default();
        assert!(
            msg.contains("covers 1 of the lesson's 2 steps; add `// %% step: Two`"),
            "{msg}"
        );
    }

    #[test]
    fn the_exercise_marker_must_match_the_lesson() {
        let mut l = lesson(vec![]);
        let extra = cells_from_recipe(&l, "// %% exercise\n", "r.rs", root());
        assert!(
            matches!(extra, Err(BuildError::NoExercise { .. })),
            "{extra:?}"
        );
        l.exercise = Some(Exercise {
            name: "td_target".into(),
            also: vec![],
            hints: vec![],
            ideas: vec![],
        });
        let missing = cells_from_recipe(&l, "// %%\nx\n", "r.rs", root());
        assert!(
            matches!(missing, Err(BuildError::MissingExercise { .. })),
            "{missing:?}"
        );
    }

    #[test]
    fn an_unregistered_exercise_is_an_error() {
        let mut l = lesson(vec![]);
        l.exercise = Some(Exercise {
            name: "not_an_exercise".into(),
            also: vec![],
            hints: vec![],
            ideas: vec![],
        });
        let err = cells_from_recipe(&l, "// %% exercise\n", "r.rs", root());
        assert!(
            matches!(&err, Err(BuildError::Unregistered { name, .. }) if name == "not_an_exercise"),
            "{err:?}"
        );
    }

    #[test]
    fn the_candle_exercise_has_its_own_cells() -> Result<(), Box<dyn std::error::Error>> {
        let course = Course::embedded()?;
        let losses = course.get("losses").ok_or("no lesson `losses`")?;
        let cells = notebook_cells(root(), losses)?;
        let grading: Vec<&Cell> = cells
            .iter()
            .filter(|c| matches!(c, Cell::Code(code) if code.starts_with("ppo_grade::")))
            .collect();
        let last = grading.last().ok_or("no grading cell")?;
        assert_eq!(**last, Cell::Code(grade_cell("ppo_losses")));
        assert!(cells.iter().any(
            |c| matches!(c, Cell::Code(code) if code.contains("use ppo_engine::candle_core::"))
        ));
        assert_eq!(solution_cells(root(), losses)?.len(), 2);
        Ok(())
    }

    #[test]
    fn every_lesson_has_a_recipe_that_builds() -> Result<(), Box<dyn std::error::Error>> {
        let course = Course::embedded()?;
        let folders = recipe_folders(root(), &course)?;
        assert_eq!(folders.len(), course.lessons.len());
        for l in &course.lessons {
            let cells = notebook_cells(root(), l)?;
            assert_eq!(cells[1], Cell::Code(dep_cell(l)), "{}", folder(l));
        }
        Ok(())
    }
}
