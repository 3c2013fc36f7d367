//! The Jupyter notebook file (`.ipynb`, nbformat 4.4) of generated cells and their outputs.
//!
//! The text is stable: one-space indentation, rich outputs sorted by mime type, execution
//! counts numbering the code cells from 1, so a regenerated notebook differs from the
//! committed one only where a cell or an output changed.
//!
//! ```
//! use ppo_tutor::generator::build::Cell;
//! use ppo_tutor::generator::ipynb::{Outputs, notebook_json, to_text};
//!
//! let cells = [Cell::Markdown("# Title".into()), Cell::Code("println!(\"hi\");".into())];
//! let outputs = [None, Some(Outputs { stdout: "hi\n".into(), ..Outputs::default() })];
//! let text = to_text(&notebook_json(&cells, &outputs))?;
//! assert!(text.contains("\"output_type\": \"stream\""));
//! # Ok::<(), serde_json::Error>(())
//! ```

use std::collections::BTreeMap;

use serde_json::{Value, json};

use super::build::Cell;

/// What one code cell printed.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Outputs {
    /// Everything the cell wrote to stdout (rich-output blocks excluded).
    pub stdout: String,
    /// Rich outputs by mime type (`text/plain`, `text/html`, `image/svg+xml`), sorted so the
    /// file is stable.
    pub data: BTreeMap<String, String>,
}

/// A text as a notebook stores it: a list of lines, each with its `\n` (one empty line for
/// an empty text).
/// `text` as a notebook field: a list of lines, each but the last ending in `\n`.
#[must_use]
pub fn source_lines(text: &str) -> Value {
    let mut out: Vec<String> = text.split_inclusive('\n').map(str::to_string).collect();
    if out.is_empty() {
        out.push(String::new());
    }
    json!(out)
}

/// The text of a notebook field stored as a list of lines (or as one string).
#[must_use]
pub fn joined(v: &Value) -> String {
    match v {
        Value::Array(parts) => parts.iter().filter_map(Value::as_str).collect(),
        Value::String(s) => s.clone(),
        _ => String::new(),
    }
}

/// The notebook of `cells`, with `outputs[i]` under code cell `i` (`None` for none, and
/// for markdown cells), for evcxr's `rust` kernel.
#[must_use]
pub fn notebook_json(cells: &[Cell], outputs: &[Option<Outputs>]) -> Value {
    let mut count = 0;
    let cells: Vec<Value> = cells
        .iter()
        .zip(outputs)
        .map(|(cell, out)| match cell {
            Cell::Markdown(md) => json!({
                "cell_type": "markdown",
                "metadata": {},
                "source": source_lines(md.trim_end()),
            }),
            Cell::Code(code) => {
                count += 1;
                json!({
                    "cell_type": "code",
                    "execution_count": count,
                    "metadata": {},
                    "outputs": output_json(out.as_ref(), count),
                    "source": source_lines(code),
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

/// A code cell's `outputs` list: its stdout stream, then its rich outputs.
fn output_json(out: Option<&Outputs>, count: usize) -> Vec<Value> {
    let mut outs = Vec::new();
    let Some(out) = out else {
        return outs;
    };
    if !out.stdout.is_empty() {
        outs.push(json!({
            "name": "stdout",
            "output_type": "stream",
            "text": source_lines(&out.stdout),
        }));
    }
    if !out.data.is_empty() {
        let data: serde_json::Map<String, Value> = out
            .data
            .iter()
            .map(|(k, v)| (k.clone(), source_lines(v)))
            .collect();
        outs.push(json!({
            "data": data,
            "execution_count": count,
            "metadata": {},
            "output_type": "execute_result",
        }));
    }
    outs
}

/// The file's text: JSON indented by one space, ending in a newline (Jupyter's layout).
///
/// # Errors
/// A serialisation error (not expected for the values [`notebook_json`] makes).
pub fn to_text(nb: &Value) -> Result<String, serde_json::Error> {
    let mut buf = Vec::new();
    let fmt = serde_json::ser::PrettyFormatter::with_indent(b" ");
    let mut ser = serde_json::Serializer::with_formatter(&mut buf, fmt);
    serde::Serialize::serialize(nb, &mut ser)?;
    let mut text = String::from_utf8_lossy(&buf).into_owned();
    text.push('\n');
    Ok(text)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn code_cells_are_counted_and_keep_their_outputs() -> Result<(), serde_json::Error> {
        let cells = [
            Cell::Markdown("# T\n\n".into()),
            Cell::Code("a".into()),
            Cell::Code("b".into()),
        ];
        let mut data = BTreeMap::new();
        data.insert("text/plain".to_string(), "1\n2".to_string());
        let outputs = [
            None,
            None,
            Some(Outputs {
                stdout: String::new(),
                data,
            }),
        ];
        let nb = notebook_json(&cells, &outputs);
        assert_eq!(joined(&nb["cells"][0]["source"]), "# T");
        assert_eq!(nb["cells"][2]["execution_count"], 2);
        assert_eq!(nb["cells"][2]["outputs"][0]["execution_count"], 2);
        assert_eq!(
            nb["cells"][2]["outputs"][0]["data"]["text/plain"],
            json!(["1\n", "2"])
        );
        assert_eq!(nb["cells"][1]["outputs"], json!([]));
        let text = to_text(&nb)?;
        assert!(text.starts_with("{\n \"cells\": [\n  {\n"), "{text}");
        assert!(text.ends_with("}\n"));
        Ok(())
    }
}
