//! Lesson markdown to styled lines: paragraphs, bullets, `code` spans and **bold**; and
//! the width-correct text helpers every pane uses (CJK characters take two columns, and
//! Chinese lines break between characters, not only at spaces).

use ratatui::style::Style;
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

/// Converts a step's markdown body into lines for a wrapping paragraph `width` columns
/// wide. A table that fits the width is drawn with its columns aligned by display width (a
/// Chinese cell is twice as wide as its characters); a wider one is left as written.
#[must_use]
pub fn markdown(body: &str, theme: Theme, width: usize) -> Vec<Line<'static>> {
    let mut lines = Vec::new();
    let mut in_code = false;
    let mut table: Vec<String> = Vec::new();
    for raw in reflow(body) {
        let raw = raw.as_str();
        if !in_code && raw.trim_start().starts_with('|') {
            table.push(raw.trim().to_string());
            continue;
        }
        if !table.is_empty() {
            lines.extend(markdown_table(&std::mem::take(&mut table), theme, width));
        }
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
    if !table.is_empty() {
        lines.extend(markdown_table(&table, theme, width));
    }
    lines
}

/// Whether a table row is the `|---|:--:|` line under the header.
fn is_rule(cells: &[String]) -> bool {
    !cells.is_empty()
        && cells
            .iter()
            .all(|c| !c.is_empty() && c.chars().all(|ch| matches!(ch, '-' | ':' | ' ')))
}

/// A markdown table's rows (`| a | b |` lines), aligned by display width when it fits in
/// `width` columns; otherwise as written.
fn markdown_table(rows: &[String], theme: Theme, width: usize) -> Vec<Line<'static>> {
    let cells: Vec<Vec<String>> = rows
        .iter()
        .map(|row| {
            let inner = row.trim().trim_start_matches('|');
            let inner = inner.strip_suffix('|').unwrap_or(inner);
            inner.split('|').map(|c| c.trim().to_string()).collect()
        })
        .collect();
    let columns = cells.iter().map(Vec::len).max().unwrap_or(0);
    // Each cell's spans (inline code and bold drawn as in the text) and their width.
    let spans: Vec<Vec<Vec<Span<'static>>>> = cells
        .iter()
        .map(|row| row.iter().map(|c| inline(c, theme)).collect())
        .collect();
    let cell_width = |s: &[Span<'_>]| s.iter().map(Span::width).sum::<usize>();
    let mut widths = vec![0; columns];
    for (row, row_spans) in cells.iter().zip(&spans) {
        if is_rule(row) {
            continue;
        }
        for (k, s) in row_spans.iter().enumerate() {
            widths[k] = widths[k].max(cell_width(s));
        }
    }
    let total = widths.iter().map(|w| w + 3).sum::<usize>() + 1;
    if columns == 0 || total > width {
        return rows.iter().map(|r| Line::from(inline(r, theme))).collect();
    }
    let mut lines = Vec::new();
    for (i, (row, row_spans)) in cells.iter().zip(spans).enumerate() {
        if is_rule(row) {
            let rule: Vec<String> = widths.iter().map(|w| "-".repeat(w + 2)).collect();
            lines.push(Line::styled(format!("|{}|", rule.join("|")), theme.dim()));
            continue;
        }
        let header = i == 0 && cells.get(1).is_some_and(|r| is_rule(r));
        let mut out = vec![Span::styled("| ", theme.dim())];
        for (k, w) in widths.iter().enumerate() {
            let cell = row_spans.get(k).cloned().unwrap_or_default();
            let pad = w.saturating_sub(cell_width(&cell));
            if header {
                out.extend(cell.into_iter().map(|s| s.patch_style(theme.title())));
            } else {
                out.extend(cell);
            }
            out.push(Span::raw(" ".repeat(pad)));
            out.push(Span::styled(
                if k + 1 == columns { " |" } else { " | " },
                theme.dim(),
            ));
        }
        lines.push(Line::from(out));
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

pub use crate::i18n::{pad_left, pad_right, width};

/// `s` cut to at most `columns` display columns, never through a wide character.
#[must_use]
pub fn truncate(s: &str, columns: usize) -> String {
    let mut out = String::new();
    let mut used = 0;
    for c in s.chars() {
        let w = width(c.encode_utf8(&mut [0; 4]));
        if used + w > columns {
            break;
        }
        used += w;
        out.push(c);
    }
    out
}

/// The zero-width space: a break opportunity ratatui's word wrapper honours and never draws.
const ZWSP: char = '\u{200B}';

/// Characters a line must not start with (closing punctuation, in CJK text).
fn no_line_start(c: char) -> bool {
    "，。、；：？！）」』》〉】〕”’…—·％,.;:!?)]}%".contains(c)
}

/// Characters a line must not end with (opening punctuation, in CJK text).
fn no_line_end(c: char) -> bool {
    "（「『《〈【〔“‘([{".contains(c)
}

/// A character of a CJK script or full-width punctuation: two columns wide.
fn is_wide(c: char) -> bool {
    width(c.encode_utf8(&mut [0; 4])) >= 2
}

/// Whether a line may break between `a` and `b` without a space: next to a wide (CJK)
/// character, unless punctuation forbids it.
fn may_break_between(a: char, b: char) -> bool {
    (is_wide(a) || is_wide(b))
        && !a.is_whitespace()
        && !b.is_whitespace()
        && !no_line_start(b)
        && !no_line_end(a)
}

/// `line` with a break opportunity (a zero-width space) wherever Chinese text may wrap
/// between two characters, so that a wrapping `Paragraph` breaks Chinese lines at the edge
/// instead of only at spaces. Lines without wide characters come back unchanged.
#[must_use]
pub fn breakable(line: Line<'_>) -> Line<'static> {
    let Line {
        style,
        alignment,
        spans,
    } = line;
    let mut previous: Option<char> = None;
    let spans = spans
        .into_iter()
        .map(|span| {
            let mut content = String::with_capacity(span.content.len());
            for c in span.content.chars() {
                if previous.is_some_and(|p| may_break_between(p, c)) {
                    content.push(ZWSP);
                }
                content.push(c);
                previous = Some(c);
            }
            Span::styled(content, span.style)
        })
        .collect::<Vec<_>>();
    let mut out = Line::from(spans).style(style);
    out.alignment = alignment;
    out
}

/// [`breakable`] on every line.
#[must_use]
pub fn breakable_lines<'a>(lines: impl IntoIterator<Item = Line<'a>>) -> Vec<Line<'static>> {
    lines.into_iter().map(breakable).collect()
}

/// `lines` wrapped to `columns` display columns, as a wrapping `Paragraph` would draw
/// them but never wider than `columns`: breaks at spaces, and between Chinese characters
/// ([`breakable`]'s opportunities); a word wider than a row is cut at the edge, never
/// through a wide glyph. Indentation is kept on a line's first row; the spaces at a break
/// are dropped. Draw the result without `Paragraph::wrap`.
#[must_use]
pub fn wrap<'a>(lines: impl IntoIterator<Item = Line<'a>>, columns: u16) -> Vec<Line<'static>> {
    let columns = usize::from(columns.max(2));
    let mut out = Vec::new();
    for line in lines {
        let line = breakable(line);
        let (style, alignment) = (line.style, line.alignment);
        let mut rows: Vec<Vec<(String, Style)>> = Vec::new();
        let mut row: Vec<(String, Style)> = Vec::new();
        let mut used = 0;
        let mut gap: Vec<(String, Style)> = Vec::new();
        let mut word: Vec<(String, Style)> = Vec::new();
        let graphemes: Vec<(String, Style)> = line
            .spans
            .iter()
            .flat_map(|span| {
                span.styled_graphemes(Style::default())
                    .map(|g| (g.symbol.to_string(), g.style))
                    .collect::<Vec<_>>()
            })
            .collect();
        let place = |row: &mut Vec<(String, Style)>,
                     used: &mut usize,
                     rows: &mut Vec<Vec<(String, Style)>>,
                     gap: &mut Vec<(String, Style)>,
                     word: &mut Vec<(String, Style)>| {
            let w_gap: usize = gap.iter().map(|(g, _)| width(g)).sum();
            let w_word: usize = word.iter().map(|(g, _)| width(g)).sum();
            let at_start = row.is_empty() && rows.is_empty();
            if *used + w_gap + w_word <= columns && (*used > 0 || at_start) {
                row.append(gap);
                row.append(word);
                *used += w_gap + w_word;
                return;
            }
            gap.clear();
            if *used > 0 {
                rows.push(std::mem::take(row));
                *used = 0;
            }
            // A word wider than a row: cut at the edge, glyph by glyph.
            for (g, st) in word.drain(..) {
                let w = width(&g);
                if *used + w > columns {
                    rows.push(std::mem::take(row));
                    *used = 0;
                }
                *used += w;
                row.push((g, st));
            }
        };
        for (g, st) in graphemes {
            let zwsp = g.starts_with(ZWSP);
            if zwsp || g.chars().all(char::is_whitespace) {
                if !word.is_empty() {
                    place(&mut row, &mut used, &mut rows, &mut gap, &mut word);
                }
                if !zwsp {
                    gap.push((g, st));
                }
            } else {
                word.push((g, st));
            }
        }
        place(&mut row, &mut used, &mut rows, &mut gap, &mut word);
        rows.push(row);
        for r in rows {
            // Consecutive graphemes of one style become one span.
            let mut spans: Vec<Span<'static>> = Vec::new();
            for (g, st) in r {
                match spans.last_mut() {
                    Some(last) if last.style == st => last.content.to_mut().push_str(&g),
                    _ => spans.push(Span::styled(g, st)),
                }
            }
            let mut l = Line::from(spans).style(style);
            l.alignment = alignment;
            out.push(l);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::{breakable, pad_left, pad_right, reflow, truncate, width, wrap};
    use ratatui::text::Line;

    #[test]
    fn tables_align_by_display_width_when_they_fit() {
        let theme = crate::tui::theme::Theme { color: false };
        let body = "| 序号 | 含义 |\n|---|---|\n| 0 | 小车位置 |\n| 1 | `x` |";
        let text: Vec<String> = super::markdown(body, theme, 40)
            .iter()
            .map(|l| l.spans.iter().map(|s| s.content.as_ref()).collect())
            .collect();
        assert_eq!(
            text,
            [
                "| 序号 | 含义     |",
                "|------|----------|",
                "| 0    | 小车位置 |",
                "| 1    | x        |"
            ]
        );
        // Too wide for the pane: as written (the wrapping paragraph breaks it).
        let narrow = super::markdown(body, theme, 10);
        assert_eq!(narrow.len(), 4);
        assert_eq!(narrow[2].width(), width("| 0 | 小车位置 |"));
    }

    #[test]
    fn widths_count_columns_not_characters() {
        assert_eq!(width("截断"), 4);
        assert_eq!(width("obs.θ̇"), 5);
        assert_eq!(pad_right("已完成", 8), "已完成  ");
        assert_eq!(pad_left("θ̇", 3), "  θ̇");
        assert_eq!(truncate("第一课", 5), "第一");
        assert_eq!(truncate("abc", 5), "abc");
    }

    #[test]
    fn chinese_breaks_between_characters_but_not_before_a_comma() {
        let line = breakable(Line::raw("按 s 打开沙盒，再试。"));
        let text: String = line.spans.iter().map(|s| s.content.as_ref()).collect();
        assert_eq!(
            text,
            "按 s 打\u{200B}开\u{200B}沙\u{200B}盒，\u{200B}再\u{200B}试。"
        );
        assert_eq!(line.width(), width("按 s 打开沙盒，再试。"));
        // English is left alone.
        let english = breakable(Line::raw("press s, then Enter"));
        assert_eq!(english.spans[0].content, "press s, then Enter");
        // A long Chinese sentence fills each row instead of jumping to the next one.
        let long = breakable(Line::raw(
            "按 e 训练一个回合，或按 t 连续训练：策略网络和价值网络每个回合之后都会更新一次。",
        ));
        let rows = wrap([long], 20);
        let text: Vec<String> = rows
            .iter()
            .map(|l| l.spans.iter().map(|s| s.content.as_ref()).collect())
            .collect();
        assert_eq!(
            text,
            [
                "按 e 训练一个回合，",
                "或按 t 连续训练：策",
                "略网络和价值网络每个",
                // 次 moves down with 。: a line never starts with a full stop.
                "回合之后都会更新一",
                "次。"
            ]
        );
        // Never wider than the row, even when a wide glyph would end at its last column + 1.
        for columns in 5..30 {
            for row in wrap([Line::raw("价值网络 V(s) 估计回报：γ·V(s′)。")], columns)
            {
                assert!(row.width() <= usize::from(columns), "{columns}: {row:?}");
            }
        }
        // English wraps at spaces, a word too long for a row is cut, indentation stays.
        let english: Vec<String> = wrap([Line::raw("  one two three supercalifragilistic")], 10)
            .iter()
            .map(|l| l.spans.iter().map(|s| s.content.as_ref()).collect())
            .collect();
        assert_eq!(english, ["  one two", "three", "supercalif", "ragilistic"]);
        assert_eq!(wrap([Line::raw("")], 10).len(), 1);
    }

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
