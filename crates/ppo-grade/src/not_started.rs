//! Recognising an exercise that has not been started, before anything is built.
//!
//! A starter's function body is `todo!()` and comments. Building and running it only to
//! watch it panic with "not yet implemented" cost seconds for a plain exercise, and for
//! the candle one a first build of candle (over two minutes of every core). The grader
//! therefore reads the learner's file first: when the exercise's function is still
//! `todo!()` (its comments and layout aside, whatever else the file holds, such as a
//! lesson's other exercises), the report says "not started" at once.
//!
//! ```
//! use ppo_grade::not_started::todo_line;
//!
//! let starter = "/// Doc.\npub fn approx_kl(a: &[f32], b: &[f32]) -> f32 {\n    // TODO: your code\n    todo!()\n}\n";
//! assert_eq!(todo_line(starter, "approx_kl"), Some(4));
//! let begun = starter.replace("todo!()", "let n = a.len();\n    todo!()");
//! assert_eq!(todo_line(&begun, "approx_kl"), None);
//! ```

use super::reset::{char_literal_len, function_span, skip_block_comment, string_literal_len};

/// The line (from 1) of the `todo!()` that is the whole body of function `name` in
/// `source`, comments and whitespace aside; `None` when the body holds anything else (or
/// the function is not there).
#[must_use]
pub fn todo_line(source: &str, name: &str) -> Option<usize> {
    let span = function_span(source, name)?;
    let code = blank_comments(&source[span.clone()]);
    let open = code.find('{')?;
    let body: String = code[open + 1..]
        .chars()
        .filter(|c| !c.is_whitespace())
        .collect();
    if body != "todo!()}" && body != "todo!();}" {
        return None;
    }
    let at = span.start + open + code[open..].find("todo!")?;
    Some(source[..at].matches('\n').count() + 1)
}

/// `code` with every comment replaced by spaces (a byte for a byte, newlines kept), so
/// positions in it are positions in `code`; strings and characters are kept.
fn blank_comments(code: &str) -> String {
    let mut out = String::with_capacity(code.len());
    let mut at = 0;
    let blank = |text: &str, out: &mut String| {
        for c in text.chars() {
            if c == '\n' {
                out.push('\n');
            } else {
                out.extend(std::iter::repeat_n(' ', c.len_utf8()));
            }
        }
    };
    while at < code.len() {
        let rest = &code[at..];
        let (len, comment) = if rest.starts_with("//") {
            (rest.find('\n').unwrap_or(rest.len()), true)
        } else if rest.starts_with("/*") {
            (skip_block_comment(rest), true)
        } else if let Some(len) = string_literal_len(rest) {
            (len, false)
        } else if rest.starts_with('\'') {
            (char_literal_len(rest).unwrap_or(1), false)
        } else {
            (rest.chars().next().map_or(1, char::len_utf8), false)
        };
        let len = len.clamp(1, rest.len());
        if comment {
            blank(&rest[..len], &mut out);
        } else {
            out.push_str(&rest[..len]);
        }
        at += len;
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_body_of_todo_and_comments_is_not_started_and_anything_more_is() {
        let src = "pub fn one(x: f32) -> f32 {\n    /* a } in a comment */\n    // todo!() said here does not count\n    todo!();\n}\n\npub fn two() -> u8 {\n    7\n}\n";
        assert_eq!(todo_line(src, "one"), Some(4));
        assert_eq!(todo_line(src, "two"), None);
        assert_eq!(todo_line(src, "three"), None);
        // Code beside the todo!(), a string holding it, or another macro: begun.
        for body in [
            "let y = x;\n    todo!()",
            "println!(\"todo!()\")",
            "unimplemented!()",
        ] {
            let begun = src.replacen("todo!();", body, 1);
            assert_eq!(todo_line(&begun, "one"), None, "{body}");
        }
        // Chinese comments keep the byte positions right.
        let zh = src.replace("a } in a comment", "注释里的 }");
        assert_eq!(todo_line(&zh, "one"), Some(4));
    }

    #[test]
    fn every_embedded_starter_is_not_started_in_every_language() {
        for exercise in crate::exercises() {
            for lang in crate::i18n::Lang::ALL {
                let _lang = lang.scoped();
                let starter = exercise.starter().unwrap_or_default();
                assert!(
                    todo_line(starter, exercise.name()).is_some(),
                    "{} ({lang:?}): its starter is not recognised",
                    exercise.name()
                );
            }
        }
    }
}
