//! Lesson markdown to styled lines: paragraphs, bullets, `code` spans and **bold**.

use ratatui::text::{Line, Span};

use crate::tui::theme::Theme;

/// Joins hard-wrapped source lines into paragraphs and list items, keeping code blocks,
/// tables and headings line by line.
#[must_use]
pub fn reflow(body: &str) -> Vec<String> {
    let mut out: Vec<String> = Vec::new();
    let mut open = false; // whether the last pushed line may take a continuation
    let mut in_code = false;
    for raw in body.lines() {
        let t = raw.trim_start();
        if t.starts_with("```") {
            in_code = !in_code;
            out.push(raw.to_string());
            open = false;
            continue;
        }
        let starts_block = in_code
            || t.is_empty()
            || t.starts_with("- ")
            || t.starts_with("* ")
            || t.starts_with('|')
            || t.starts_with('#')
            || t.split_once(". ")
                .is_some_and(|(n, _)| !n.is_empty() && n.chars().all(|c| c.is_ascii_digit()));
        if !starts_block
            && open
            && let Some(last) = out.last_mut()
        {
            last.push(' ');
            last.push_str(t);
            continue;
        }
        out.push(raw.to_string());
        open = !in_code && !t.is_empty() && !t.starts_with('|') && !t.starts_with('#');
    }
    out
}

/// Converts a step's markdown body into lines for a wrapping paragraph.
#[must_use]
pub fn markdown(body: &str, theme: Theme) -> Vec<Line<'static>> {
    let mut lines = Vec::new();
    let mut in_code = false;
    for raw in reflow(body) {
        let raw = raw.as_str();
        if raw.trim_start().starts_with("```") {
            in_code = !in_code;
            continue;
        }
        if in_code {
            lines.push(Line::styled(format!("  {raw}"), theme.code()));
            continue;
        }
        if let Some(h) = raw.strip_prefix("### ") {
            lines.push(Line::styled(h.to_string(), theme.title()));
            continue;
        }
        let (prefix, rest) = match raw.strip_prefix("- ").or_else(|| raw.strip_prefix("* ")) {
            Some(rest) => ("• ", rest),
            None => ("", raw),
        };
        let mut spans = vec![Span::raw(prefix)];
        spans.extend(inline(rest, theme));
        lines.push(Line::from(spans));
    }
    lines
}

/// Splits a line at backticks and double asterisks.
fn inline(text: &str, theme: Theme) -> Vec<Span<'static>> {
    let mut spans = Vec::new();
    for (i, part) in text.split('`').enumerate() {
        if i % 2 == 1 {
            spans.push(Span::styled(part.to_string(), theme.code()));
            continue;
        }
        for (j, piece) in part.split("**").enumerate() {
            if piece.is_empty() {
                continue;
            }
            if j % 2 == 1 {
                spans.push(Span::styled(piece.to_string(), theme.title()));
            } else {
                spans.push(Span::raw(piece.to_string()));
            }
        }
    }
    spans
}

#[cfg(test)]
mod tests {
    use super::reflow;

    #[test]
    fn paragraphs_join_and_blocks_stay() {
        let body = "one\ntwo\n\n- a\n  b\n- c\n\n| x |\n| y |\n```\ncode\nmore\n```";
        assert_eq!(
            reflow(body),
            vec![
                "one two", "", "- a b", "- c", "", "| x |", "| y |", "```", "code", "more", "```"
            ]
        );
    }
}
