//! Every notebook's code as plain Rust, for the default test tier: no evcxr.
//!
//! A notebook's code cells run in one kernel, one after the other, sharing their variables;
//! the same cells in order, as the body of one function, compile and run the same way. This
//! module writes that function for each notebook (`tests/notebook_code/en/` and
//! `tests/notebook_code/zh/`), and `tests/notebook_code.rs` runs them against the current
//! crate with the checks `tests/notebooks.rs` makes on evcxr ([`super::check`]): the
//! tensors a notebook computes equal the library's, the reference solutions pass when
//! graded in place, and the saved outputs are what the code prints now.
//!
//! What a cell does only on evcxr stays with the full tier: its `:` commands (`:dep` with
//! the lesson's features, `:env` and `:restart` for the language) and the kernel's own
//! display of rich outputs. Here:
//! - a cell's last expression, which the kernel displays, becomes a call that records what
//!   it would show: its [`Rich`](crate::notebook::Rich) outputs, or its `Debug` text as evcxr does;
//! - `println!` writes into the cell's recorded output (the test defines the macro);
//! - the exercise's cells (its starters, with `todo!()`, and their grading cells) form one
//!   block, so that the reference solutions, graded at the end as `tests/notebooks.rs`
//!   does, can define the same functions again.
//!
//! The files are generated, committed and compared with what this module makes now, so a
//! notebook whose recipe or lesson changed fails until they are regenerated with
//! [`REGENERATE_CODE`] (`ppo-tutor dev notebooks` writes them too).
//!
//! ```
//! use ppo_tutor::generator::native::split_tail;
//!
//! assert_eq!(split_tail("let x = 1;\nx + 1"), ("let x = 1;\n".to_string(), Some("x + 1".to_string())));
//! assert_eq!(split_tail("fn f() -> u32 {\n    1\n}").1, None);
//! ```

use std::fmt::Write as _;
use std::path::Path;

use super::build::{self, BuildError, Cell};
use crate::i18n::Lang;
use crate::lesson::{Course, Lesson};

/// The command that regenerates the files of this module, run in the repository.
pub const REGENERATE_CODE: &str = "cargo run -- dev notebook-code";

/// Where the current language's generated code is: `tests/notebook_code/en` or
/// `tests/notebook_code/zh`.
#[must_use]
pub fn code_dir() -> &'static str {
    Lang::current().pick("tests/notebook_code/en", "tests/notebook_code/zh")
}

/// The Rust module of lesson folder `folder`: `l08_gae` for `08-gae`.
#[must_use]
pub fn module_name(folder: &str) -> String {
    format!("l{}", folder.replace('-', "_"))
}

/// Splits a cell's code into its statements and its last expression, the value the kernel
/// displays (`None` when the code ends with `;`, `}` or a comment). Comments, strings and
/// character literals are skipped; a `}` followed by `else`, `.` or `?` does not end a
/// statement. A block-like statement at the very end (`for`, `if`, `match`) is the
/// cell's value, as evcxr takes it (a loop shows `()`); an item at the end (`fn`, `struct`,
/// `impl`, `use`) has none.
#[must_use]
pub fn split_tail(code: &str) -> (String, Option<String>) {
    let code = code.trim_end();
    let chars: Vec<(usize, char)> = code.char_indices().collect();
    let at = |k: usize| chars.get(k).map(|&(_, c)| c);
    let mut depth = 0_i32;
    let mut end = 0; // byte index after the last statement
    let mut before_last = 0; // the same, one statement earlier
    let mut k = 0;
    while k < chars.len() {
        let (i, c) = chars[k];
        match c {
            '/' if at(k + 1) == Some('/') => {
                while k < chars.len() && chars[k].1 != '\n' {
                    k += 1;
                }
                continue;
            }
            '/' if at(k + 1) == Some('*') => {
                let mut nest = 0;
                while k < chars.len() {
                    if chars[k].1 == '/' && at(k + 1) == Some('*') {
                        nest += 1;
                        k += 2;
                    } else if chars[k].1 == '*' && at(k + 1) == Some('/') {
                        nest -= 1;
                        k += 2;
                        if nest == 0 {
                            break;
                        }
                    } else {
                        k += 1;
                    }
                }
                continue;
            }
            'r' if matches!(at(k + 1), Some('"' | '#'))
                && !chars[..k]
                    .last()
                    .is_some_and(|&(_, p)| p.is_alphanumeric() || p == '_') =>
            {
                // A raw string r"..." or r#"..."#.
                let mut j = k + 1;
                let mut hashes = 0;
                while at(j) == Some('#') {
                    hashes += 1;
                    j += 1;
                }
                if at(j) == Some('"') {
                    j += 1;
                    'raw: while j < chars.len() {
                        if chars[j].1 == '"' && (1..=hashes).all(|h| at(j + h) == Some('#')) {
                            j += 1 + hashes;
                            break 'raw;
                        }
                        j += 1;
                    }
                    k = j;
                    continue;
                }
            }
            '"' => {
                k += 1;
                while k < chars.len() && chars[k].1 != '"' {
                    if chars[k].1 == '\\' {
                        k += 1;
                    }
                    k += 1;
                }
                k += 1;
                continue;
            }
            '\'' => {
                // A character literal ('a', '\n', '\''), or a lifetime ('a).
                if at(k + 1) == Some('\\') {
                    k += 2;
                    while k < chars.len() && chars[k].1 != '\'' {
                        k += 1;
                    }
                    k += 1;
                    continue;
                }
                if at(k + 2) == Some('\'') {
                    k += 3;
                    continue;
                }
            }
            '(' | '[' | '{' => depth += 1,
            ')' | ']' => depth -= 1,
            '}' => {
                depth -= 1;
                if depth == 0 {
                    let rest = code[i + 1..].trim_start();
                    let continues = rest.starts_with('.')
                        || rest.starts_with('?')
                        || rest.strip_prefix("else").is_some_and(|r| {
                            !r.starts_with(|c: char| c.is_alphanumeric() || c == '_')
                        });
                    if !continues {
                        before_last = end;
                        end = i + 1;
                    }
                }
            }
            ';' if depth == 0 => {
                before_last = end;
                end = i + 1;
            }
            _ => {}
        }
        k += 1;
    }
    // A block-like statement last (`for`, `if`, `match`, a block) is the cell's value, as
    // evcxr takes it (a loop shows `()`); an item last (`fn`, `struct`, ...) is not.
    let end = if end == code.len() && code.ends_with('}') && !is_item(&code[before_last..]) {
        before_last
    } else {
        end
    };
    let tail = &code[end..];
    // Comment lines and blank lines at the start of the tail stay statements.
    let mut lead = 0;
    for line in tail.split_inclusive('\n') {
        let t = line.trim();
        if t.is_empty() || t.starts_with("//") {
            lead += line.len();
        } else {
            break;
        }
    }
    let expr = tail[lead..].trim();
    if expr.is_empty() {
        (code.to_string(), None)
    } else {
        (code[..end + lead].to_string(), Some(expr.to_string()))
    }
}

/// Whether a statement (comments and attributes before it skipped) is an item, which has
/// no value: `fn`, `struct`, `impl`, `use`, ...
fn is_item(statement: &str) -> bool {
    let first = statement
        .lines()
        .map(str::trim)
        .find(|l| !l.is_empty() && !l.starts_with("//") && !l.starts_with("#["))
        .unwrap_or("");
    let first = first.strip_prefix("pub ").unwrap_or(first);
    [
        "fn ",
        "struct ",
        "enum ",
        "impl ",
        "impl<",
        "trait ",
        "mod ",
        "use ",
        "const ",
        "static ",
        "type ",
        "extern ",
        "unsafe ",
        "async fn ",
        "macro_rules!",
    ]
    .iter()
    .any(|k| first.starts_with(k))
}

fn indent(code: &str, by: &str) -> String {
    let mut out = String::new();
    for line in code.lines() {
        if line.trim().is_empty() {
            out.push('\n');
        } else {
            let _ = writeln!(out, "{by}{line}");
        }
    }
    out
}

/// One cell as statements of the function: its statements, then its last expression
/// recorded as the cell's displayed value.
fn cell_code(code: &str, by: &str) -> String {
    let (stmts, expr) = split_tail(code);
    let mut out = indent(&stmts, by);
    if let Some(expr) = expr {
        let _ = writeln!(out, "{by}nb.show((&Shown(&({expr}))).outputs());");
    }
    out
}

/// The module for `lesson`'s notebook in the current language: one function `run` holding
/// every code cell in order.
///
/// # Errors
/// As [`build::notebook_cells`] and [`build::solution_cells`]; also
/// [`BuildError::Read`] when the exercise's cells are not in the notebook in order.
pub fn module_source(root: &Path, lesson: &Lesson) -> Result<String, BuildError> {
    let folder = build::folder(lesson);
    let cells = build::notebook_cells(root, lesson)?;
    let exercise = build::exercise_code_cells(root, lesson)?;
    let solutions = build::solution_cells(root, lesson)?;
    // Where the exercise's code cells are: in order, markdown between them.
    let code_at: Vec<usize> = cells
        .iter()
        .enumerate()
        .filter_map(|(i, c)| matches!(c, Cell::Code(_)).then_some(i))
        .collect();
    let block = match exercise.first() {
        None => None,
        Some(first) => {
            let start = code_at
                .iter()
                .position(|&i| matches!(&cells[i], Cell::Code(c) if c == first));
            let found = start.filter(|&s| {
                exercise.iter().enumerate().all(|(j, code)| {
                    code_at
                        .get(s + j)
                        .is_some_and(|&i| matches!(&cells[i], Cell::Code(c) if c == code))
                })
            });
            let Some(s) = found else {
                return Err(BuildError::Read {
                    path: build::notebook_file(&folder),
                    source: std::io::Error::other(
                        "the exercise's cells are not in the notebook in order",
                    ),
                });
            };
            Some((code_at[s], code_at[s + exercise.len() - 1]))
        }
    };

    let mut out = String::new();
    let _ = writeln!(
        out,
        "//! @generated by `{REGENERATE_CODE}` from {}/{folder}.rs and lessons/{folder}/:\n\
         //! every code cell of {} in order, as one function (src/generator/native.rs).\n\
         //! Do not edit; `tests/notebook_code.rs` runs it.\n",
        build::recipe_dir(),
        build::notebook_file(&folder),
    );
    out.push_str(
        "#![allow(warnings, clippy::all, clippy::pedantic, clippy::unwrap_used, clippy::expect_used)]\n\n\
         use crate::{Nb, ShowDebug as _, ShowRich as _, Shown};\n\n\
         /// The notebook's code cells, in order.\n\
         pub fn run(nb: &mut Nb) -> anyhow::Result<()> {\n",
    );
    for (i, cell) in cells.iter().enumerate() {
        let Cell::Code(code) = cell else { continue };
        let inside = block.is_some_and(|(a, b)| (a..=b).contains(&i));
        if block.is_some_and(|(a, _)| a == i) {
            out.push_str(
                "    // The exercise as the learner first meets it: starters and grading.\n    {\n",
            );
        }
        let by = if inside { "        " } else { "    " };
        if code.trim_start().starts_with(':') {
            let _ = writeln!(out, "{by}// cell {i}: evcxr's commands, run only on evcxr");
        } else {
            let _ = writeln!(out, "{by}nb.cell({i});");
            out.push_str(&cell_code(code, by));
        }
        if block.is_some_and(|(_, b)| b == i) {
            out.push_str("    }\n");
        }
    }
    if let Some(ex) = &lesson.exercise {
        out.push_str(
            "    // The reference solutions, graded in place: each must pass.\n    nb.solutions();\n    {\n",
        );
        for code in &solutions {
            out.push_str(&indent(code, "        "));
        }
        for name in ex.names() {
            let _ = writeln!(
                out,
                "        nb.passed(\"{name}\", {}.passed());",
                build::grade_cell(name)
            );
        }
        out.push_str("    }\n");
    }
    out.push_str("    Ok(())\n}\n");
    Ok(out)
}

/// The index of the current language's modules: one `mod` and one test per notebook.
#[must_use]
pub fn index_source(folders: &[String]) -> String {
    let lang = Lang::current().pick("En", "Zh");
    let mut out = format!(
        "//! @generated by `{REGENERATE_CODE}` (src/generator/native.rs): the notebooks of \
         {}/, one test each. Do not edit.\n\n",
        Lang::current().pick("notebooks", "notebooks/zh")
    );
    for f in folders {
        let _ = writeln!(out, "pub mod {};", module_name(f));
    }
    for f in folders {
        let m = module_name(f);
        let _ = write!(
            out,
            "\n#[test]\nfn {m}() -> anyhow::Result<()> {{\n    \
             crate::check(ppo_tutor::i18n::Lang::{lang}, \"{f}\", {m}::run)\n}}\n"
        );
    }
    out
}

/// Every generated file of the current language, as `(path relative to the repository,
/// contents)`: one module per notebook, then `mod.rs`.
///
/// # Errors
/// As [`module_source`].
pub fn files(root: &Path, course: &Course) -> Result<Vec<(String, String)>, BuildError> {
    let folders = build::recipe_folders(root, course)?;
    let mut files = Vec::new();
    for (lesson, folder) in course.lessons.iter().zip(&folders) {
        files.push((
            format!("{}/{}.rs", code_dir(), module_name(folder)),
            module_source(root, lesson)?,
        ));
    }
    files.push((format!("{}/mod.rs", code_dir()), index_source(&folders)));
    Ok(files)
}

/// Writes every generated file of both languages under `root`, and returns their paths.
///
/// # Errors
/// As [`files`]; an I/O error names the file.
pub fn write_all(root: &Path) -> anyhow::Result<Vec<String>> {
    use anyhow::Context as _;
    let mut written = Vec::new();
    for lang in Lang::ALL {
        let _lang = lang.scoped();
        let course = Course::embedded()?;
        let dir = root.join(code_dir());
        std::fs::create_dir_all(&dir)
            .with_context(|| format!("{}: cannot create it", dir.display()))?;
        for (path, text) in files(root, &course)? {
            let full = root.join(&path);
            std::fs::write(&full, text).with_context(|| format!("{path}: cannot write it"))?;
            written.push(path);
        }
    }
    Ok(written)
}

/// Rewrites the markdown cells of every committed notebook (both languages) from the
/// lessons, keeping each code cell and every output as they are: for a change of a lesson's
/// text or of the code an anchor quotes, without executing anything. Markdown cells may
/// come and go (a new cell after an exercise, say); the code cells must be the recipe's, in
/// order. Returns the notebook files it changed.
///
/// # Errors
/// When a notebook's code cells differ from the ones its recipe makes (their outputs would
/// be stale: run `dev notebooks` instead), or a file cannot be read or written.
pub fn write_markdown(root: &Path) -> anyhow::Result<Vec<String>> {
    use anyhow::Context as _;
    let mut changed = Vec::new();
    for lang in Lang::ALL {
        let _lang = lang.scoped();
        let course = Course::embedded()?;
        for lesson in &course.lessons {
            let folder = super::build::folder(lesson);
            let cells = super::build::notebook_cells(root, lesson)?;
            let name = super::build::notebook_file(&folder);
            let path = root.join(&name);
            let text = std::fs::read_to_string(&path).with_context(|| format!("reading {name}"))?;
            let mut nb: serde_json::Value =
                serde_json::from_str(&text).with_context(|| format!("parsing {name}"))?;
            let saved = nb["cells"].as_array().cloned().unwrap_or_default();
            let fix = format!("run `{}` {folder}", super::build::REGENERATE);
            nb["cells"] = serde_json::Value::Array(
                with_markdown(&saved, &cells).map_err(|e| anyhow::anyhow!("{name}{e}: {fix}"))?,
            );
            let new = super::ipynb::to_text(&nb)?;
            if new != text {
                std::fs::write(&path, new).with_context(|| format!("writing {name}"))?;
                changed.push(name);
            }
        }
    }
    Ok(changed)
}

/// The saved cells `saved` of a notebook with their markdown made `cells`' own: each saved
/// code cell (with its outputs) is kept where `cells` has the same code, the markdown cells
/// between them are `cells`' ones. An error (`", code cell N ..."`) when the code cells
/// differ.
fn with_markdown(
    saved: &[serde_json::Value],
    cells: &[Cell],
) -> Result<Vec<serde_json::Value>, String> {
    let saved_code: Vec<&serde_json::Value> =
        saved.iter().filter(|c| c["cell_type"] == "code").collect();
    let mut code = saved_code.iter();
    let mut out = Vec::with_capacity(cells.len());
    for (i, made) in cells.iter().enumerate() {
        match made {
            Cell::Markdown(md) => out.push(serde_json::json!({
                "cell_type": "markdown",
                "metadata": {},
                "source": super::ipynb::source_lines(md.trim_end()),
            })),
            Cell::Code(source) => match code.next() {
                Some(cell) if super::ipynb::joined(&cell["source"]) == *source => {
                    out.push((*cell).clone());
                }
                _ => {
                    return Err(format!(
                        ", cell {i}: the code cells differ from the recipe's (their outputs \
                         would be stale)"
                    ));
                }
            },
        }
    }
    if code.next().is_some() {
        return Err(", more code cells than the recipe makes".to_string());
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::{Cell, split_tail, with_markdown};

    fn tail(code: &str) -> Option<String> {
        split_tail(code).1
    }

    /// `dev notebook-markdown` adds and drops markdown cells, keeps each code cell with its
    /// outputs, and refuses code that is not the recipe's.
    #[test]
    fn markdown_cells_come_and_go_around_the_saved_code() {
        let code = |src: &str, out: &str| serde_json::json!({"cell_type": "code", "source": [src], "outputs": [out]});
        let md = |src: &str| serde_json::json!({"cell_type": "markdown", "source": [src]});
        let saved = [md("old"), code("a", "1"), md("gone"), code("b", "2")];
        let cells = [
            Cell::Markdown("new".into()),
            Cell::Code("a".into()),
            Cell::Code("b".into()),
            Cell::Markdown("added".into()),
        ];
        let out = with_markdown(&saved, &cells).unwrap_or_default();
        let kinds: Vec<&str> = out.iter().filter_map(|c| c["cell_type"].as_str()).collect();
        assert_eq!(kinds, ["markdown", "code", "code", "markdown"]);
        assert_eq!(out[1], saved[1]);
        assert_eq!(out[2], saved[3]);
        assert_eq!(out[3]["source"], serde_json::json!(["added"]));
        let other = [Cell::Code("a".into()), Cell::Code("c".into())];
        assert!(with_markdown(&saved, &other).is_err());
        assert!(with_markdown(&saved, &[Cell::Code("a".into())]).is_err());
    }

    #[test]
    fn the_last_expression_is_found() {
        assert_eq!(
            tail("snap.show(&[\"a\"])").as_deref(),
            Some("snap.show(&[\"a\"])")
        );
        assert_eq!(tail("let x = 1;\n// shown:\nx").as_deref(), Some("x"));
        assert_eq!(tail("plot(\"a; b\")?").as_deref(), Some("plot(\"a; b\")?"));
        assert_eq!(
            tail("let c = PpoConfig { eps: 0.1, ..PpoConfig::default() };\nc.eps").as_deref(),
            Some("c.eps")
        );
        assert_eq!(
            tail("let v = if a { 1 } else { 2 };\nv").as_deref(),
            Some("v")
        );
        assert_eq!(
            tail("Foo { a: 1 }.show()").as_deref(),
            Some("Foo { a: 1 }.show()")
        );
        assert_eq!(
            tail("quiz::answer(\"gae\", 1, '?')").as_deref(),
            Some("quiz::answer(\"gae\", 1, '?')")
        );
        assert_eq!(tail("let s = r#\"a \"; b\"#;\ns").as_deref(), Some("s"));
    }

    #[test]
    fn a_block_like_statement_last_is_the_value_as_evcxr_takes_it() {
        assert_eq!(
            tail("let a = true;\nif a { 1 } else { 2 }").as_deref(),
            Some("if a { 1 } else { 2 }")
        );
        assert_eq!(
            tail("let n = 3;\n// loop:\nfor i in 0..n {\n    f(i);\n}").as_deref(),
            Some("for i in 0..n {\n    f(i);\n}")
        );
        assert_eq!(
            tail("/// Doc.\n#[inline]\npub fn f() -> u32 {\n    1\n}"),
            None
        );
        assert_eq!(tail("let x = 1;\nimpl Foo {\n}"), None);
    }

    #[test]
    fn statements_have_no_value_to_show() {
        assert_eq!(tail("let x = 1;"), None);

        assert_eq!(tail("fn f() -> u32 {\n    1\n}"), None);
        assert_eq!(tail("let x = 1;\n// a comment; with a semicolon"), None);
        assert_eq!(tail("use a::{b, c};"), None);

        assert_eq!(tail("let c = ';';\nlet d = '}';"), None);
        assert_eq!(tail("fn f<'a>(x: &'a str) -> &'a str {\n    x\n}"), None);
    }
}
