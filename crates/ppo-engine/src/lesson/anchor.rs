//! Code pulled from the crate's own source by anchor, so a lesson cannot drift from the code.
//!
//! Source files mark regions with `// ANCHOR: name` and `// ANCHOR_END: name` (the
//! mdBook convention). The whole `src/` tree is embedded at compile time, so what the
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

static SRC: Dir<'static> = include_dir!("$CARGO_MANIFEST_DIR/src");

/// Every anchor in the embedded `src/`, indexed once: name → (path, code).
fn index() -> &'static BTreeMap<String, (String, String)> {
    static INDEX: OnceLock<BTreeMap<String, (String, String)>> = OnceLock::new();
    INDEX.get_or_init(|| {
        let mut map = BTreeMap::new();
        let mut stack = vec![&SRC];
        while let Some(dir) = stack.pop() {
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
                        .or_insert_with(|| (path.clone(), extract(text, name)));
                }
            }
            stack.extend(dir.dirs());
        }
        map
    })
}

/// The code between `// ANCHOR: name` and `// ANCHOR_END: name` in `text`, de-indented,
/// without nested anchor lines.
fn extract(text: &str, name: &str) -> String {
    let start = format!("// ANCHOR: {name}");
    let end = format!("// ANCHOR_END: {name}");
    let body: Vec<&str> = text
        .lines()
        .skip_while(|l| l.trim() != start)
        .skip(1)
        .take_while(|l| l.trim() != end)
        .filter(|l| !l.trim_start().starts_with("// ANCHOR"))
        .collect();
    dedent(&body)
}

/// Finds anchor `name` in the embedded `src/`: the file's path (relative to `src/`) and
/// the code between the markers, de-indented, without nested anchor lines.
#[must_use]
pub fn find(name: &str) -> Option<(String, String)> {
    index().get(name).cloned()
}

/// Every anchor name defined in the embedded source, sorted, with repeats (a name defined
/// twice appears twice, so a test can catch it).
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
