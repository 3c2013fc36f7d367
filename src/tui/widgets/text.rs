//! Lesson markdown to styled lines ([`markdown`]: paragraphs, bullets, code, tables,
//! emphasis); and the width-correct text helpers every pane uses (CJK characters take two
//! columns, and Chinese lines break between characters, not only at spaces).

mod inline;
mod markdown;
mod table;

use ratatui::style::Style;
use ratatui::text::{Line, Span};

pub use inline::inline;
pub use markdown::{markdown, reflow};

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

/// `line` cut to at most `columns` display columns; when anything is cut, its last column
/// shows `mark` (a dim `…`) so that a reader sees the line goes on. A line that fits comes
/// back as it is.
#[must_use]
pub fn cut(line: Line<'_>, columns: usize, mark: Span<'static>) -> Line<'static> {
    let (style, alignment) = (line.style, line.alignment);
    if line.width() <= columns {
        let spans: Vec<Span<'static>> = line
            .spans
            .into_iter()
            .map(|s| Span::styled(s.content.into_owned(), s.style))
            .collect();
        let mut out = Line::from(spans).style(style);
        out.alignment = alignment;
        return out;
    }
    let room = columns.saturating_sub(mark.width());
    let mut used = 0;
    let mut spans: Vec<Span<'static>> = Vec::new();
    for span in &line.spans {
        let kept = truncate(&span.content, room - used);
        used += width(&kept);
        let whole = kept.len() == span.content.len();
        spans.push(Span::styled(kept, span.style));
        if !whole {
            break;
        }
    }
    // A wide glyph that would end past the cut leaves a gap before the mark.
    if used < room {
        spans.push(Span::raw(" ".repeat(room - used)));
    }
    if columns >= mark.width() {
        spans.push(mark);
    }
    let mut out = Line::from(spans).style(style);
    out.alignment = alignment;
    out
}

/// A step's markdown body as plain text wrapped to `columns`: what the terminal app shows
/// (no emphasis markers, tables as columns), without styles, for `ppo-tutor show`.
#[must_use]
pub fn plain(body: &str, columns: u16) -> String {
    let theme = crate::tui::theme::Theme { color: false };
    let lines = wrap(markdown(body, theme, usize::from(columns)), columns);
    let rows: Vec<String> = lines
        .iter()
        .map(|l| {
            let row: String = l.spans.iter().map(|s| s.content.as_ref()).collect();
            row.trim_end().to_string()
        })
        .collect();
    rows.join("\n")
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

/// [`wrap`], with each line's later rows indented under its text: under the first word
/// after its leading spaces, or, for a `label:` line (a grader report's `hint:     …`),
/// under the value after the label. A wrapped paragraph keeps its left edge.
#[must_use]
pub fn wrap_hanging<'a>(
    lines: impl IntoIterator<Item = Line<'a>>,
    columns: u16,
) -> Vec<Line<'static>> {
    let mut out = Vec::new();
    for line in lines {
        let plain: String = line.spans.iter().map(|s| s.content.as_ref()).collect();
        let indent = hang(&plain);
        let room = usize::from(columns).saturating_sub(indent);
        if line.width() <= usize::from(columns) || room < 16 {
            out.extend(wrap([line], columns));
            continue;
        }
        // The line's first `indent` columns stay on its first row; the rest wraps in the
        // room beside them.
        let (head, rest) = split_at_width(&line, indent);
        out.extend(hanging(head, rest.style(line.style), columns));
    }
    out
}

/// `line` wrapped to `columns` after `prefix`, its later rows indented by the prefix's
/// width, so that a wrapped paragraph keeps its left edge (a quiz choice's rows under its
/// words, not under its letter).
#[must_use]
pub fn hanging(
    prefix: Vec<Span<'static>>,
    line: Line<'static>,
    columns: u16,
) -> Vec<Line<'static>> {
    let indent: usize = prefix.iter().map(Span::width).sum();
    let room = usize::from(columns).saturating_sub(indent).max(8);
    let style = line.style;
    let pad = " ".repeat(indent);
    wrap([line], u16::try_from(room).unwrap_or(u16::MAX))
        .into_iter()
        .enumerate()
        .map(|(i, row)| {
            let mut spans = if i == 0 {
                prefix.clone()
            } else {
                vec![Span::raw(pad.clone())]
            };
            spans.extend(row.spans);
            Line::from(spans).style(style)
        })
        .collect()
}

/// Where a line's later rows start: after its leading spaces, and after a short `label:`
/// and the spaces that follow it.
fn hang(text: &str) -> usize {
    let lead = text.len() - text.trim_start().len();
    let rest = &text[lead..];
    let label = rest
        .find(": ")
        .filter(|&i| i > 0 && i <= 16 && !rest[..i].contains(' '))
        .map_or(0, |i| {
            let after = &rest[i + 1..];
            i + 1 + (after.len() - after.trim_start().len())
        });
    width(&text[..lead]) + width(&rest[..label])
}

/// `line` split after `columns` display columns: the spans before, and the rest as a line.
fn split_at_width(line: &Line<'_>, columns: usize) -> (Vec<Span<'static>>, Line<'static>) {
    let mut head = Vec::new();
    let mut tail = Vec::new();
    let mut used = 0;
    for span in &line.spans {
        if used >= columns {
            tail.push(Span::styled(span.content.to_string(), span.style));
            continue;
        }
        let kept = truncate(&span.content, columns - used);
        used += width(&kept);
        let rest = span.content[kept.len()..].to_string();
        head.push(Span::styled(kept, span.style));
        if !rest.is_empty() {
            tail.push(Span::styled(rest, span.style));
        }
    }
    (head, Line::from(tail))
}

#[cfg(test)]
mod tests {
    use super::{breakable, cut, pad_left, pad_right, truncate, width, wrap};
    use ratatui::text::{Line, Span};

    /// A line cut at a pane's edge ends in a mark, and never in half a
    /// wide glyph.
    #[test]
    fn a_cut_line_shows_that_it_goes_on() {
        let text =
            |l: &Line<'_>| -> String { l.spans.iter().map(|s| s.content.as_ref()).collect() };
        let mark = || Span::raw("…");
        let line = Line::from(vec![Span::raw("let x = "), Span::raw("compute(1, 2);")]);
        assert_eq!(text(&cut(line.clone(), 12, mark())), "let x = com…");
        assert_eq!(
            text(&cut(line.clone(), 22, mark())),
            "let x = compute(1, 2);"
        );
        assert_eq!(text(&cut(line, 1, mark())), "…");
        let chinese = cut(Line::raw("# 计算优势"), 6, mark());
        assert_eq!(text(&chinese), "# 计 …");
        assert_eq!(chinese.width(), 6);
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

    /// A report line that wraps keeps its value column; an indented line its indent.
    #[test]
    fn hanging_rows_stay_under_the_text() {
        let rows: Vec<String> = super::wrap_hanging(
            [Line::raw(
                "        hint:     each advantage sums the TD errors of the steps after it, so the loop",
            )],
            40,
        )
        .iter()
        .map(ToString::to_string)
        .collect();
        assert!(rows.len() > 1, "{rows:#?}");
        assert!(rows[0].starts_with("        hint:     each"), "{rows:#?}");
        for row in &rows[1..] {
            assert!(row.starts_with(&" ".repeat(18)), "{rows:#?}");
            assert!(!row[18..].starts_with(' '), "{rows:#?}");
        }
        assert!(rows.iter().all(|r| width(r) <= 40), "{rows:#?}");
        let plain: Vec<String> = super::wrap_hanging(
            [Line::raw(
                "   one two three four five six seven eight nine ten eleven",
            )],
            20,
        )
        .iter()
        .map(ToString::to_string)
        .collect();
        assert!(
            plain[1..]
                .iter()
                .all(|r| r.starts_with("   ") && !r.starts_with("    "))
        );
    }
}
