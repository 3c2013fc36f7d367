//! Code pulled from the crate's own source by anchor, so a lesson cannot drift from the code.
//!
//! Source files mark regions with `// ANCHOR: name` and `// ANCHOR_END: name` (the
//! mdBook convention). The whole `src/` tree of this crate and of the RL core it builds
//! on (`ppo-rl`, where nearly every anchor is) is embedded at compile time, so what the
//! tutor shows is exactly the code that was compiled into it.
//!
//! ```
//! let (path, code) = ppo_engine::lesson::anchor::find("physics").ok_or("no anchor")?;
//! assert!(path.ends_with("cartpole.rs"));
//! assert!(code.contains("fn physics"));
//! # Ok::<(), &str>(())
//! ```

use std::collections::BTreeMap;
use std::sync::OnceLock;

use include_dir::{Dir, include_dir};

/// Each embedded crate's name and `src/` tree: the RL core first, then this crate.
static SOURCES: [(&str, Dir<'static>); 2] = [
    ("ppo-rl", include_dir!("$CARGO_MANIFEST_DIR/../ppo-rl/src")),
    ("ppo-engine", include_dir!("$CARGO_MANIFEST_DIR/src")),
];

/// Every anchor in the embedded sources, indexed once: name → (crate, path, the whole
/// file's text).
fn index() -> &'static BTreeMap<String, (&'static str, String, &'static str)> {
    static INDEX: OnceLock<BTreeMap<String, (&'static str, String, &'static str)>> =
        OnceLock::new();
    INDEX.get_or_init(|| {
        let mut map = BTreeMap::new();
        let mut stack: Vec<(&'static str, &'static Dir<'static>)> =
            SOURCES.iter().map(|(krate, dir)| (*krate, dir)).collect();
        while let Some((krate, dir)) = stack.pop() {
            for file in dir.files() {
                let Some(text) = file.contents_utf8() else {
                    continue;
                };
                let path = file.path().display().to_string();
                for name in text
                    .lines()
                    .filter_map(|l| l.trim().strip_prefix("// ANCHOR: "))
                {
                    map.entry(name.to_string())
                        .or_insert_with(|| (krate, path.clone(), text));
                }
            }
            stack.extend(dir.dirs().map(|d| (krate, d)));
        }
        map
    })
}

/// One line of an anchor's code as [`find_masked`] gives it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Line {
    /// A line of code, de-indented with the rest.
    Code(String),
    /// A nested anchor left out: its name and the indentation (in spaces, after
    /// de-indenting) of its first line.
    Masked {
        /// The nested anchor's name.
        name: String,
        /// Spaces before the region's code.
        indent: usize,
    },
}

/// The lines between `// ANCHOR: name` and `// ANCHOR_END: name` in `text`, without
/// nested anchor lines; a nested anchor for which `mask` holds becomes one
/// [`Line::Masked`]. The outer anchor itself is never masked here.
fn extract_lines(text: &str, name: &str, mask: &dyn Fn(&str) -> bool) -> Vec<Line> {
    let start = format!("// ANCHOR: {name}");
    let end = format!("// ANCHOR_END: {name}");
    let mut raw: Vec<(Option<String>, &str)> = Vec::new();
    // The nested anchor being skipped, if any.
    let mut skipping: Option<String> = None;
    for l in text
        .lines()
        .skip_while(|l| l.trim() != start)
        .skip(1)
        .take_while(|l| l.trim() != end)
    {
        let trimmed = l.trim();
        if let Some(skipped) = &skipping {
            if trimmed.strip_prefix("// ANCHOR_END: ") == Some(skipped.as_str()) {
                skipping = None;
            }
            continue;
        }
        if let Some(inner) = trimmed.strip_prefix("// ANCHOR: ")
            && mask(inner)
        {
            raw.push((Some(inner.to_string()), l));
            skipping = Some(inner.to_string());
            continue;
        }
        if trimmed.starts_with("// ANCHOR") {
            continue;
        }
        raw.push((None, l));
    }
    let indent = raw
        .iter()
        .filter(|(_, l)| !l.trim().is_empty())
        .map(|(_, l)| l.len() - l.trim_start().len())
        .min()
        .unwrap_or(0);
    raw.into_iter()
        .map(|(masked, l)| match masked {
            Some(name) => Line::Masked {
                name,
                indent: (l.len() - l.trim_start().len()).saturating_sub(indent),
            },
            None => Line::Code(l.get(indent..).unwrap_or("").trim_end().to_string()),
        })
        .collect()
}

/// The code between `// ANCHOR: name` and `// ANCHOR_END: name` in `text`, de-indented,
/// without nested anchor lines.
fn extract(text: &str, name: &str) -> String {
    extract_lines(text, name, &|_| false)
        .into_iter()
        .map(|l| match l {
            Line::Code(code) => code,
            Line::Masked { .. } => String::new(),
        })
        .collect::<Vec<_>>()
        .join("\n")
}

/// Finds anchor `name` in the embedded sources: the file's path (relative to its crate's
/// `src/`, the crate named by [`crate_of`]) and the code between the markers, de-indented,
/// without nested anchor lines.
#[must_use]
pub fn find(name: &str) -> Option<(String, String)> {
    index()
        .get(name)
        .map(|(_, path, text)| (path.clone(), extract(text, name)))
}

/// The crate whose `src/` holds anchor `name` (`ppo-rl` or `ppo-engine`).
#[must_use]
pub fn crate_of(name: &str) -> Option<&'static str> {
    index().get(name).map(|(krate, _, _)| *krate)
}

/// [`find`], line by line, with each nested anchor for which `mask` holds left out as one
/// [`Line::Masked`] (and anchors nested in it with it).
///
/// ```
/// use ppo_engine::lesson::anchor::{Line, find_masked};
///
/// let (_, lines) = find_masked("td_target", &|inner| inner == "td_target_formula")
///     .ok_or("no anchor")?;
/// assert!(matches!(&lines[0], Line::Code(c) if c.contains("next_values")));
/// assert!(matches!(&lines[1], Line::Masked { name, indent: 0 } if name == "td_target_formula"));
/// # Ok::<(), &str>(())
/// ```
#[must_use]
pub fn find_masked(name: &str, mask: &dyn Fn(&str) -> bool) -> Option<(String, Vec<Line>)> {
    index()
        .get(name)
        .map(|(_, path, text)| (path.clone(), extract_lines(text, name, mask)))
}

/// The anchors nested in anchor `name`, at any depth, in the order they open.
#[must_use]
pub fn nested(name: &str) -> Vec<String> {
    let Some((_, _, text)) = index().get(name) else {
        return Vec::new();
    };
    let (start, end) = (
        format!("// ANCHOR: {name}"),
        format!("// ANCHOR_END: {name}"),
    );
    text.lines()
        .skip_while(|l| l.trim() != start)
        .skip(1)
        .take_while(|l| l.trim() != end)
        .filter_map(|l| l.trim().strip_prefix("// ANCHOR: "))
        .map(str::to_string)
        .collect()
}

/// Every anchor name defined in the embedded source, sorted, with repeats (a name defined
/// twice appears twice, so a test can catch it).
#[must_use]
pub fn all() -> Vec<String> {
    let mut names = Vec::new();
    let mut stack: Vec<&Dir<'static>> = SOURCES.iter().map(|(_, dir)| dir).collect();
    while let Some(dir) = stack.pop() {
        for file in dir.files() {
            let Some(text) = file.contents_utf8() else {
                continue;
            };
            names.extend(
                text.lines()
                    .filter_map(|l| l.trim().strip_prefix("// ANCHOR: "))
                    .map(str::to_string),
            );
        }
        stack.extend(dir.dirs());
    }
    names.sort();
    names
}
