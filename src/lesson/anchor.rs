//! Code pulled from the crate's own source by anchor, so a lesson cannot drift from the code.
//!
//! Source files mark regions with `// ANCHOR: name` and `// ANCHOR_END: name` (the
//! mdBook convention). The whole `src/` tree is embedded at compile time, so what the
//! tutor shows is exactly the code that was compiled into it.
//!
//! ```
//! let (path, code) = ppo_tutor::lesson::anchor::find("physics").ok_or("no anchor")?;
//! assert!(path.ends_with("cartpole.rs"));
//! assert!(code.contains("fn physics"));
//! # Ok::<(), &str>(())
//! ```

use include_dir::{Dir, include_dir};

static SRC: Dir<'static> = include_dir!("$CARGO_MANIFEST_DIR/src");

/// Finds anchor `name` in the embedded `src/`: the file's path (relative to `src/`) and
/// the code between the markers, de-indented, without nested anchor lines.
#[must_use]
pub fn find(name: &str) -> Option<(String, String)> {
    let start = format!("// ANCHOR: {name}");
    let end = format!("// ANCHOR_END: {name}");
    let mut stack = vec![&SRC];
    while let Some(dir) = stack.pop() {
        for file in dir.files() {
            let Some(text) = file.contents_utf8() else {
                continue;
            };
            let mut lines = text.lines().skip_while(|l| l.trim() != start);
            if lines.next().is_none() {
                continue;
            }
            let body: Vec<&str> = lines
                .take_while(|l| l.trim() != end)
                .filter(|l| !l.trim_start().starts_with("// ANCHOR"))
                .collect();
            return Some((file.path().display().to_string(), dedent(&body)));
        }
        stack.extend(dir.dirs());
    }
    None
}

/// Every anchor name defined in the embedded source, sorted.
#[must_use]
pub fn all() -> Vec<String> {
    let mut names = Vec::new();
    let mut stack = vec![&SRC];
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

fn dedent(lines: &[&str]) -> String {
    let indent = lines
        .iter()
        .filter(|l| !l.trim().is_empty())
        .map(|l| l.len() - l.trim_start().len())
        .min()
        .unwrap_or(0);
    lines
        .iter()
        .map(|l| l.get(indent..).unwrap_or("").trim_end())
        .collect::<Vec<_>>()
        .join("\n")
}
