//! Markdown tables (`| a | b |` rows, a `|---|` rule under the header) as aligned columns
//! that fit a pane: the header in the title style, a rule under it, columns two spaces
//! apart and measured in display columns (a Chinese cell is twice as wide as its
//! characters). A table wider than the pane wraps its widest cells inside their columns; one
//! too wide even for a word a column is cut at the edge with a `…`.

use ratatui::text::{Line, Span};

use super::inline::inline;
use super::{ZWSP, breakable, cut, width, wrap};
use crate::tui::theme::Theme;

/// Columns between two table columns.
const GAP: usize = 2;

/// A column's alignment, from the rule row (`:--`, `:-:`, `--:`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Align {
    Left,
    Center,
    Right,
}

fn is_row(line: &str) -> bool {
    line.trim_start().starts_with('|')
}

/// A row's cells, trimmed: split at each `|` not escaped as `\|`.
fn cells(row: &str) -> Vec<String> {
    let inner = row.trim();
    let inner = inner.strip_prefix('|').unwrap_or(inner);
    let inner = match inner.strip_suffix('|') {
        Some(rest) if !rest.ends_with('\\') => rest,
        _ => inner,
    };
    let mut out = vec![String::new()];
    let mut escaped = false;
    for c in inner.chars() {
        if c == '|' && !escaped {
            out.push(String::new());
        } else if let Some(cell) = out.last_mut() {
            cell.push(c);
        }
        escaped = c == '\\' && !escaped;
    }
    out.iter().map(|c| c.trim().to_string()).collect()
}

/// A rule cell's alignment, or `None` when the cell is not `-`s between optional colons.
fn alignment(cell: &str) -> Option<Align> {
    let dashes = cell.trim_start_matches(':').trim_end_matches(':');
    if dashes.is_empty() || !dashes.chars().all(|c| c == '-') {
        return None;
    }
    Some(match (cell.starts_with(':'), cell.ends_with(':')) {
        (true, true) => Align::Center,
        (false, true) => Align::Right,
        _ => Align::Left,
    })
}

/// How many of `lines` form a table: a header row, the rule under it and the rows that
/// follow; 0 when `lines` does not start with a table.
pub fn rows<S: AsRef<str>>(lines: &[S]) -> usize {
    match lines {
        [head, rule, rest @ ..]
            if is_row(head.as_ref())
                && is_row(rule.as_ref())
                && cells(rule.as_ref()).iter().all(|c| alignment(c).is_some()) =>
        {
            2 + rest.iter().take_while(|l| is_row(l.as_ref())).count()
        }
        _ => 0,
    }
}

/// The widest piece of `spans` that a row may not break (a word; a Chinese character).
fn longest_word(spans: &[Span<'static>]) -> usize {
    let text: String = breakable(Line::from(spans.to_vec()))
        .spans
        .iter()
        .map(|s| s.content.as_ref())
        .collect();
    text.split(|c: char| c.is_whitespace() || c == ZWSP)
        .map(width)
        .max()
        .unwrap_or(0)
}

/// Column widths for a table whose columns want `natural` (widest cell) and at least
/// `least` (longest word) in `room` columns: all they want when it fits; else the room is
/// filled level by level, so that narrow columns keep their own width and the widest share
/// what is left, none under its longest word (or, when not even the words fit, under two
/// columns: one Chinese character).
fn fit(natural: &[usize], least: &[usize], room: usize) -> Vec<usize> {
    if natural.iter().sum::<usize>() <= room {
        return natural.to_vec();
    }
    let floor: Vec<usize> = if least.iter().sum::<usize>() <= room {
        least.to_vec()
    } else {
        natural.iter().map(|&n| n.min(2)).collect()
    };
    let at = |level: usize| -> Vec<usize> {
        natural
            .iter()
            .zip(&floor)
            .map(|(&n, &f)| level.clamp(f, n.max(f)))
            .collect()
    };
    let top = natural.iter().copied().max().unwrap_or(0);
    let level = (0..=top)
        .take_while(|&l| at(l).iter().sum::<usize>() <= room)
        .last()
        .unwrap_or(0);
    let mut widths = at(level);
    // What the level leaves over goes a column at a time to those still short.
    let mut left = room.saturating_sub(widths.iter().sum());
    for (w, &n) in widths.iter_mut().zip(natural) {
        if left > 0 && *w < n {
            *w += 1;
            left -= 1;
        }
    }
    widths
}

/// `spans` padded to `columns` as `align` says.
fn pad(
    mut spans: Vec<Span<'static>>,
    columns: usize,
    align: Align,
    last: bool,
) -> Vec<Span<'static>> {
    let room = columns.saturating_sub(spans.iter().map(Span::width).sum());
    let (before, after) = match align {
        Align::Left => (0, room),
        Align::Right => (room, 0),
        Align::Center => (room / 2, room - room / 2),
    };
    if before > 0 {
        spans.insert(0, Span::raw(" ".repeat(before)));
    }
    if after > 0 && !last {
        spans.push(Span::raw(" ".repeat(after)));
    }
    spans
}

/// One table row as lines: each cell wrapped to its column, the row as tall as its tallest
/// cell.
fn row_lines(row: &[Vec<Span<'static>>], widths: &[usize], aligns: &[Align]) -> Vec<Line<'static>> {
    let wrapped: Vec<Vec<Line<'static>>> = widths
        .iter()
        .enumerate()
        .map(|(k, &w)| {
            let cell = row.get(k).cloned().unwrap_or_default();
            wrap([Line::from(cell)], u16::try_from(w).unwrap_or(u16::MAX))
        })
        .collect();
    let height = wrapped.iter().map(Vec::len).max().unwrap_or(1);
    (0..height)
        .map(|r| {
            let mut spans = Vec::new();
            for (k, &w) in widths.iter().enumerate() {
                if k > 0 {
                    spans.push(Span::raw(" ".repeat(GAP)));
                }
                let part = wrapped[k]
                    .get(r)
                    .map(|l| l.spans.clone())
                    .unwrap_or_default();
                let align = aligns.get(k).copied().unwrap_or(Align::Left);
                spans.extend(pad(part, w, align, k + 1 == widths.len()));
            }
            // No trailing blanks after a column that ends early.
            while spans.last().is_some_and(|s| s.content.trim().is_empty()) {
                spans.pop();
            }
            Line::from(spans)
        })
        .collect()
}

/// A table's rows (as [`rows`] counts them) as lines at most `width` columns wide.
pub fn render<S: AsRef<str>>(rows: &[S], theme: Theme, width: usize) -> Vec<Line<'static>> {
    let Some((head, rest)) = rows.split_first() else {
        return Vec::new();
    };
    let aligns: Vec<Align> = rest.first().map_or_else(Vec::new, |rule| {
        cells(rule.as_ref())
            .iter()
            .map(|c| alignment(c).unwrap_or(Align::Left))
            .collect()
    });
    let header: Vec<Vec<Span<'static>>> = cells(head.as_ref())
        .iter()
        .map(|c| {
            inline(c, theme)
                .into_iter()
                .map(|s| s.patch_style(theme.title()))
                .collect()
        })
        .collect();
    let body: Vec<Vec<Vec<Span<'static>>>> = rest
        .iter()
        .skip(1)
        .map(|r| cells(r.as_ref()).iter().map(|c| inline(c, theme)).collect())
        .collect();
    let columns = body
        .iter()
        .map(Vec::len)
        .chain([header.len()])
        .max()
        .unwrap_or(0);
    let mut natural = vec![0; columns];
    let mut least = vec![0; columns];
    for row in body.iter().chain([&header]) {
        for (k, cell) in row.iter().enumerate() {
            natural[k] = natural[k].max(cell.iter().map(Span::width).sum());
            least[k] = least[k].max(longest_word(cell));
        }
    }
    let room = width.saturating_sub(GAP * columns.saturating_sub(1));
    let widths = fit(&natural, &least, room);
    let mut lines = row_lines(&header, &widths, &aligns);
    let rule: Vec<String> = widths.iter().map(|&w| "─".repeat(w)).collect();
    lines.push(Line::styled(rule.join(&" ".repeat(GAP)), theme.dim()));
    for row in &body {
        lines.extend(row_lines(row, &widths, &aligns));
    }
    lines
        .into_iter()
        .map(|l| cut(l, width, Span::styled("…", theme.dim())))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::{fit, render, rows};
    use crate::tui::theme::Theme;
    use crate::tui::widgets::text::width;

    fn text(body: &str, columns: usize) -> Vec<String> {
        let lines: Vec<&str> = body.lines().collect();
        assert_eq!(rows(&lines), lines.len(), "{body}");
        render(&lines, Theme { color: false }, columns)
            .iter()
            .map(|l| l.spans.iter().map(|s| s.content.as_ref()).collect())
            .collect()
    }

    /// A table is drawn as columns, not as its source's pipes.
    #[test]
    fn a_table_that_fits_is_aligned_by_display_width() {
        let body = "| 序号 | 含义 | unit |\n|---|---|--:|\n| 0 | 小车位置 | m |\n| 1 | `x` **速度** | m/s |";
        assert_eq!(
            text(body, 40),
            [
                "序号  含义      unit",
                "────  ────────  ────",
                "0     小车位置     m",
                "1     x 速度     m/s",
            ]
        );
    }

    /// A table wider than the pane wraps its widest column inside the column, and no row
    /// is wider than the pane.
    #[test]
    fn a_narrow_table_wraps_its_cells_and_fits() {
        let body = "| index | meaning | unit |\n|---|---|---|\n| 2 | pole angle from vertical (positive = leaning right) | radians |\n| 3 | 杆的角速度，单位是弧度每秒 | rad/s |";
        let rows = text(body, 34);
        assert_eq!(
            rows,
            [
                "index  meaning             unit",
                "─────  ──────────────────  ───────",
                "2      pole angle from     radians",
                "       vertical (positive",
                "       = leaning right)",
                "3      杆的角速度，单位是  rad/s",
                "       弧度每秒",
            ]
        );
        for columns in 3..60 {
            for row in text(body, columns) {
                assert!(width(&row) <= columns, "{columns}: {row:?}");
                assert!(!row.contains('|'), "{columns}: {row:?}");
            }
        }
        // Narrower than a word a column: words break inside their column, nothing is lost.
        let narrow = text(body, 12);
        assert_eq!(narrow[..2], ["ind  mea  un", "ex   nin  it"]);
        // Narrower than two columns a column (one Chinese character): cut, with a mark.
        let cut = text(body, 8);
        assert!(cut.iter().any(|r| r.ends_with('…')), "{cut:#?}");
    }

    #[test]
    fn columns_share_what_room_there_is() {
        assert_eq!(fit(&[5, 51, 7], &[5, 9, 7], 70), [5, 51, 7]);
        assert_eq!(fit(&[5, 51, 7], &[5, 9, 7], 30), [5, 18, 7]);
        assert_eq!(fit(&[5, 51, 7], &[5, 9, 7], 12), [4, 4, 4]);
        assert_eq!(fit(&[0, 10], &[0, 10], 4), [0, 4]);
        // Short Chinese headers keep their width: the long column gives.
        assert_eq!(fit(&[4, 4, 36, 5], &[2, 2, 4, 5], 28), [4, 4, 15, 5]);
    }

    #[test]
    fn only_a_header_with_its_rule_makes_a_table() {
        assert_eq!(rows(&["| a | b |", "|---|:-:|", "| 1 | 2 |", "after"]), 3);
        assert_eq!(rows(&["|r − 1| is large", "and more"]), 0);
        assert_eq!(rows(&["| a |", "| b |"]), 0);
    }
}
