//! The checks both test tiers make on a notebook: its committed cells are the generated
//! ones, the tensors it computes equal the library's, and its saved outputs are what its
//! code prints now (numbers to 1e-4). `tests/notebooks.rs` makes them on the evcxr engine
//! (the full tier), `tests/notebook_code.rs` on the notebooks' code compiled as plain Rust
//! ([`super::native`], the default tier).

use std::path::Path;

use anyhow::{Context as _, Result, bail, ensure};
use serde_json::Value;

use super::build::{self, Cell, REGENERATE};
use super::ipynb::{Outputs, joined};

/// `text` as its words and its numbers (a number is digits with `.` and `e`, and a `-`
/// that does not follow a letter or digit).
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

/// The same text, and numbers equal to 1e-4 (relative above 1).
#[must_use]
pub fn same_output(a: &str, b: &str) -> bool {
    let (wa, na) = split_numbers(a);
    let (wb, nb) = split_numbers(b);
    wa == wb
        && na.len() == nb.len()
        && na
            .iter()
            .zip(&nb)
            .all(|(x, y)| (x - y).abs() <= 1e-4 * (1.0 + x.abs().max(y.abs())))
}

/// A cell's `// check: NAME after N episodes` line, as `(NAME, N)`.
#[must_use]
pub fn parse_check(code: &str) -> Option<(String, usize)> {
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

/// The tensor a checked cell showed (`out`) must equal the library's live value `name`
/// after `episodes` episodes (seed 0, the seed's settings).
///
/// # Errors
/// When they differ, or the library has no such value.
pub fn against_library(name: &str, episodes: usize, out: &Outputs) -> Result<()> {
    let snap = ppo_engine::notebook::snapshot(crate::ppo::PpoConfig::default(), 0, episodes)?;
    let want = snap
        .tensor(name)
        .with_context(|| format!("the library has no live value '{name}'"))?;
    let want = ppo_engine::notebook::tensor_html(&want);
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

/// The committed notebook of lesson folder `folder` (current language) must hold `cells`,
/// the generated ones: sources and order.
///
/// # Errors
/// When a cell differs or the file cannot be read.
pub fn sources(root: &Path, folder: &str, cells: &[Cell]) -> Result<()> {
    let file = build::notebook_file(folder);
    let path = root.join(&file);
    let text = std::fs::read_to_string(&path).with_context(|| path.display().to_string())?;
    let nb: Value = serde_json::from_str(&text).with_context(|| path.display().to_string())?;
    ensure!(
        nb["metadata"]["kernelspec"]["name"] == "rust",
        "{file}: the kernel must be evcxr's `rust`"
    );
    let saved = nb["cells"].as_array().map_or(&[][..], Vec::as_slice);
    let fix = format!("regenerate with {REGENERATE} {folder}");
    ensure!(
        saved.len() == cells.len(),
        "{file} has {} cells, its lesson and recipe make {}: {fix}",
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
            "{file}, cell {i} is out of date with its lesson or recipe: {fix}"
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

/// The saved outputs of the notebook of `folder` must be `fresh`'s (a notebook's JSON),
/// cell by cell; cells for which `skip(i)` holds are not compared.
///
/// # Errors
/// The first cell whose saved output is not the fresh one.
pub fn outputs(
    root: &Path,
    folder: &str,
    fresh: &Value,
    skip: impl Fn(usize) -> bool,
) -> Result<()> {
    let file = build::notebook_file(folder);
    let path = root.join(&file);
    let saved = std::fs::read_to_string(&path).with_context(|| path.display().to_string())?;
    let saved: Value = serde_json::from_str(&saved)?;
    let fix = format!("regenerate with {REGENERATE} {folder}");
    let (Some(a), Some(b)) = (saved["cells"].as_array(), fresh["cells"].as_array()) else {
        bail!("{file} has no cells");
    };
    for (i, (s, f)) in a.iter().zip(b).enumerate() {
        if skip(i) {
            continue;
        }
        let (so, fo) = (output_texts(s), output_texts(f));
        let same = so.len() == fo.len()
            && so
                .iter()
                .zip(&fo)
                .all(|((k1, v1), (k2, v2))| k1 == k2 && same_output(v1, v2));
        ensure!(
            same,
            "{file}, cell {i}: the saved output is not what the cell prints now: {fix}\n\
             saved: {so:?}\nnow:   {fo:?}"
        );
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_compare_to_a_tolerance_and_words_exactly() {
        assert!(same_output("loss 0.123456 at 3", "loss 0.123457 at 3"));
        assert!(!same_output("loss 0.1234 at 3", "loss 0.1244 at 3"));
        assert!(!same_output("loss 0.1234 at 3", "gain 0.1234 at 3"));
        assert!(same_output("x-1 = -2", "x-1 = -2.00001"));
        assert!(!same_output("1 2", "1 2 3"));
    }

    #[test]
    fn check_lines_are_parsed() {
        assert_eq!(
            parse_check("// check: lambda_return after 30 episodes\nx"),
            Some(("lambda_return".into(), 30))
        );
        assert_eq!(parse_check("// check: ratio"), None);
        assert_eq!(parse_check("let x = 1;"), None);
    }
}
