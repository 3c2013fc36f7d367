//! `ppo-tutor reset EXERCISE`: the starter back, without losing the learner's work.
//!
//! Several exercises can share one lesson file (lesson 16's `exercise.rs` holds
//! `td_target_truncation`, `gae_rollout` and `normalize_advantage`). Resetting one of them
//! replaces only that function (from `fn` to its closing brace) with the starter's, and
//! keeps the rest of the file; an exercise alone in its file gets the whole starter back.
//! Either way, a file that changed is first copied beside itself (`exercise.rs.bak`), and
//! the reply says where (`reset gae_rollout` once wiped a passing
//! `td_target_truncation` with no prompt and no backup).

use std::ops::Range;
use std::path::{Path, PathBuf};

use super::error::GradeError;

/// What a reset did.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Restored {
    /// The exercise's file.
    pub path: PathBuf,
    /// Where the file's previous text was copied, when it had any that differed.
    pub backup: Option<PathBuf>,
    /// Only the exercise's function was replaced; the rest of the file was kept.
    pub only_function: bool,
}

/// Restores exercise `name`'s starter `starter` in `path`. `others` are the exercises
/// sharing the file, and `variants` the file's starters in every language (the same code,
/// other comments). When one of the others holds work (its function differs from every
/// variant's), only the function `name` is replaced (when both texts have it); otherwise
/// the whole file is, which also swaps the comments' language.
///
/// # Errors
/// [`GradeError::Write`] when the backup or the file cannot be written.
pub fn restore(
    path: &Path,
    name: &str,
    starter: &str,
    others: &[&str],
    variants: &[&str],
) -> Result<Restored, GradeError> {
    let write_err = |file: &Path| {
        let file = file.to_path_buf();
        move |e: std::io::Error| GradeError::Write {
            file,
            reason: crate::error::reason(&e),
        }
    };
    if let Some(dir) = path.parent() {
        std::fs::create_dir_all(dir).map_err(write_err(path))?;
    }
    let Ok(current) = std::fs::read_to_string(path) else {
        std::fs::write(path, starter).map_err(write_err(path))?;
        return Ok(Restored {
            path: path.to_path_buf(),
            backup: None,
            only_function: false,
        });
    };
    let work_elsewhere = others.iter().any(|other| {
        let Some(mine) = function_span(&current, other) else {
            return false;
        };
        !variants.iter().any(|v| {
            function_span(v, other).is_some_and(|theirs| v[theirs] == current[mine.clone()])
        })
    });
    let spliced = if work_elsewhere {
        splice_function(&current, starter, name)
    } else {
        None
    };
    let only_function = spliced.is_some();
    let text = spliced.unwrap_or_else(|| starter.to_string());
    if text == current {
        return Ok(Restored {
            path: path.to_path_buf(),
            backup: None,
            only_function,
        });
    }
    let backup = crate::lesson::progress::backup_path(path);
    std::fs::write(&backup, &current).map_err(write_err(&backup))?;
    std::fs::write(path, text).map_err(write_err(path))?;
    Ok(Restored {
        path: path.to_path_buf(),
        backup: Some(backup),
        only_function,
    })
}

/// `current` with its function `name` replaced by the one in `starter`; `None` when either
/// text lacks it (or its braces do not balance).
#[must_use]
pub fn splice_function(current: &str, starter: &str, name: &str) -> Option<String> {
    let mine = function_span(current, name)?;
    let theirs = function_span(starter, name)?;
    Some(format!(
        "{}{}{}",
        &current[..mine.start],
        &starter[theirs],
        &current[mine.end..]
    ))
}

/// The byte range of function `name` in `source`: from the start of the line holding
/// `fn name` (so `pub` is included) to just after the `}` that closes its body. Comments,
/// strings and character literals are skipped, so a `}` inside them does not count.
#[must_use]
pub fn function_span(source: &str, name: &str) -> Option<Range<usize>> {
    let bytes = source.as_bytes();
    let mut at = 0;
    let mut depth = 0usize;
    let mut start = None;
    while at < bytes.len() {
        let rest = &source[at..];
        if rest.starts_with("//") {
            at += rest.find('\n').unwrap_or(rest.len());
            continue;
        }
        if rest.starts_with("/*") {
            at += skip_block_comment(rest);
            continue;
        }
        if let Some(len) = string_literal_len(rest) {
            at += len;
            continue;
        }
        if rest.starts_with('\'') {
            at += char_literal_len(rest).unwrap_or(1);
            continue;
        }
        match bytes[at] {
            b'{' => {
                depth += 1;
                at += 1;
            }
            b'}' => {
                depth = depth.checked_sub(1)?;
                at += 1;
                if let Some(s) = start
                    && depth == 0
                {
                    return Some(s..at);
                }
            }
            _ if start.is_none() && depth == 0 && is_fn_named(source, at, name) => {
                start = Some(source[..at].rfind('\n').map_or(0, |i| i + 1));
                at += 2;
            }
            _ => at += rest.chars().next().map_or(1, char::len_utf8),
        }
    }
    None
}

/// Whether `fn name` followed by `(` or `<` starts at byte `at`, as whole words.
fn is_fn_named(source: &str, at: usize, name: &str) -> bool {
    let word_before = source[..at]
        .chars()
        .next_back()
        .is_some_and(|c| c.is_alphanumeric() || c == '_');
    let Some(rest) = source[at..].strip_prefix("fn") else {
        return false;
    };
    let trimmed = rest.trim_start();
    if word_before || trimmed.len() == rest.len() {
        return false;
    }
    trimmed
        .strip_prefix(name)
        .is_some_and(|after| after.trim_start().starts_with(['(', '<']))
}

/// The length of the block comment at the start of `rest` (nested, as Rust's are).
pub(crate) fn skip_block_comment(rest: &str) -> usize {
    let mut depth = 0usize;
    let mut i = 0;
    while i < rest.len() {
        if rest[i..].starts_with("/*") {
            depth += 1;
            i += 2;
        } else if rest[i..].starts_with("*/") {
            depth = depth.saturating_sub(1);
            i += 2;
            if depth == 0 {
                return i;
            }
        } else {
            i += rest[i..].chars().next().map_or(1, char::len_utf8);
        }
    }
    rest.len()
}

/// The length of the string literal at the start of `rest` (`"…"`, `b"…"`, `r#"…"#`), if
/// one starts there.
pub(crate) fn string_literal_len(rest: &str) -> Option<usize> {
    let body = rest.strip_prefix('b').unwrap_or(rest);
    let prefix = rest.len() - body.len();
    if let Some(raw) = body.strip_prefix('r') {
        let hashes = raw.len() - raw.trim_start_matches('#').len();
        if raw[hashes..].starts_with('"') {
            let close = format!("\"{}", "#".repeat(hashes));
            let from = prefix + 1 + hashes + 1;
            return Some(
                rest[from..]
                    .find(&close)
                    .map_or(rest.len(), |i| from + i + close.len()),
            );
        }
        return None;
    }
    if !body.starts_with('"') {
        return None;
    }
    let mut chars = body.char_indices().skip(1);
    while let Some((i, c)) = chars.next() {
        match c {
            '\\' => {
                chars.next();
            }
            '"' => return Some(prefix + i + 1),
            _ => {}
        }
    }
    Some(rest.len())
}

/// The length of the character literal at the start of `rest` (`'{'`, `'\''`, `'\u{7d}'`);
/// `None` for a lifetime or label (`'a`).
pub(crate) fn char_literal_len(rest: &str) -> Option<usize> {
    let body = &rest[1..];
    let mut chars = body.char_indices();
    let (_, first) = chars.next()?;
    let end = if first == '\\' {
        body.find('\'').filter(|&i| i > 0).and_then(|i| {
            // `'\''`: the quote right after the backslash is escaped.
            if i == 1 {
                body[2..].find('\'').map(|j| j + 2)
            } else {
                Some(i)
            }
        })?
    } else {
        let (i, c) = chars.next()?;
        (c == '\'').then_some(i)?
    };
    Some(1 + end + 1)
}

#[cfg(test)]
mod tests {
    use super::*;

    const STARTER: &str = "//! Lesson 16.\n\n/// One.\npub fn one(x: f32) -> f32 {\n    todo!()\n}\n\n/// Two.\npub fn two(v: &[f32]) -> Vec<f32> {\n    todo!()\n}\n";

    #[test]
    fn only_the_named_function_is_replaced() -> Result<(), String> {
        let mine = "//! Lesson 16.\n\n/// One.\npub fn one(x: f32) -> f32 {\n    // a } in a comment, \"}\" in a string, '}' a char\n    let s = \"{\\\"}\";\n    let _ = (s, '}', r#\"}\"#);\n    /* nested /* } */ */\n    x * 2.0\n}\n\n/// Two.\npub fn two(v: &[f32]) -> Vec<f32> {\n    v.iter().map(|x| { x + 1.0 }).collect()\n}\n";
        let out = splice_function(mine, STARTER, "two").ok_or("not spliced")?;
        assert!(
            out.contains("x * 2.0"),
            "the other function was lost:\n{out}"
        );
        assert!(!out.contains("x + 1.0"), "two was not reset:\n{out}");
        assert_eq!(out.matches("todo!()").count(), 1, "{out}");
        let out = splice_function(mine, STARTER, "one").ok_or("not spliced")?;
        assert!(out.contains("x + 1.0") && !out.contains("x * 2.0"), "{out}");
        Ok(())
    }

    #[test]
    fn a_missing_or_unbalanced_function_is_not_spliced() {
        assert_eq!(splice_function("pub fn one() {", STARTER, "one"), None);
        assert_eq!(splice_function("pub fn three() {}", STARTER, "one"), None);
        // `fn one_more` and `fn_one` are other names.
        assert_eq!(function_span("fn one_more() {}\nfn_one", "one"), None);
        assert_eq!(function_span("fn one<T>(t: T) {}", "one"), Some(0..18));
        // A lifetime is not a character literal.
        let src = "pub fn one<'a>(s: &'a str) -> &'a str {\n    s\n}\n";
        assert_eq!(function_span(src, "one"), Some(0..src.len() - 1));
    }

    #[test]
    fn a_changed_file_is_backed_up_and_an_unchanged_one_is_not() -> Result<(), String> {
        let dir = tempfile::tempdir().map_err(|e| e.to_string())?;
        let path = dir.path().join("exercise.rs");
        let done = STARTER.replacen("todo!()", "x * 2.0", 1);
        std::fs::write(&path, &done).map_err(|e| e.to_string())?;
        let variants = [STARTER];
        let r = restore(&path, "two", STARTER, &["one"], &variants).map_err(|e| e.to_string())?;
        assert!(r.only_function, "one holds work");
        // `two` was still the starter's: nothing changed, no backup.
        assert_eq!(r.backup, None);
        let r = restore(&path, "one", STARTER, &["two"], &variants).map_err(|e| e.to_string())?;
        assert!(!r.only_function, "two holds no work: the whole starter");
        let backup = r.backup.ok_or("no backup")?;
        assert_eq!(backup, dir.path().join("exercise.rs.bak"));
        assert_eq!(
            std::fs::read_to_string(&backup).map_err(|e| e.to_string())?,
            done
        );
        assert_eq!(
            std::fs::read_to_string(&path).map_err(|e| e.to_string())?,
            STARTER
        );
        // The other language's starter, untouched, is replaced whole (its comments swap).
        let other_language = STARTER.replace("/// One.", "/// 一。");
        std::fs::write(&path, &other_language).map_err(|e| e.to_string())?;
        let r = restore(&path, "two", STARTER, &["one"], &[STARTER, &other_language])
            .map_err(|e| e.to_string())?;
        assert!(!r.only_function && r.backup.is_some());
        assert_eq!(
            std::fs::read_to_string(&path).map_err(|e| e.to_string())?,
            STARTER
        );
        // Alone in its file: the whole starter, and a missing file is simply written.
        std::fs::remove_file(&path).map_err(|e| e.to_string())?;
        let r = restore(&path, "one", STARTER, &[], &variants).map_err(|e| e.to_string())?;
        assert_eq!((r.backup, r.only_function), (None, false));
        Ok(())
    }
}
