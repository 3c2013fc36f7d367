//! Live tensors as text: the batch's per-step columns side by side, grids (the policy maps)
//! with both axes labelled, then scalars and series.
//!
//! Each column is as wide as its header and its values need, so a header is never cut. When
//! a table's columns do not all fit the pane, it shows those that fit whole from
//! [`Viewport::hscroll`] on, keeps its row labels, and says under it how many columns
//! precede (`←`) and follow (`→`) and that `<` and `>` scroll them.

use ratatui::style::Style;
use ratatui::text::{Line, Span};

use super::text::{pad_left, width};
use crate::lesson::live::Axes;
use crate::lesson::{Mark, Snapshot, TensorView};
use crate::tr;
use crate::tui::theme::Theme;

/// The part of the live values a pane shows, and the pane's size.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Viewport {
    /// The pane's width, in terminal columns.
    pub width: usize,
    /// The pane's height, in rows.
    pub height: usize,
    /// The first row of each table shown (`J`/`K` scroll it).
    pub scroll: usize,
    /// The first value column of each table shown after its row labels (`<`/`>` scroll it).
    pub hscroll: usize,
}

fn style_of(mark: Mark, theme: Theme) -> Style {
    match mark {
        Mark::Plain => Style::new(),
        Mark::Clipped => theme.clipped(),
        Mark::Done => theme.done(),
        Mark::Positive => theme.positive(),
        Mark::Negative => theme.negative(),
    }
}

fn fmt(v: f64) -> String {
    if v.is_nan() {
        "nan".into()
    } else if v != 0.0 && (v.abs() >= 1e5 || v.abs() < 1e-3) {
        format!("{v:.3e}")
    } else {
        format!("{v:.4}")
    }
}

/// One value of `t` as a cell: integers (`int64` actions) as integers, as PyTorch prints
/// them, not `1.0000`; booleans (`clipped`) as `True`/`False`, as PyTorch prints them.
fn fmt_in(t: &TensorView, v: f64) -> String {
    if t.dtype == "bool" && (v == 0.0 || v == 1.0) {
        if v == 1.0 { "True" } else { "False" }.to_string()
    } else if t.dtype.starts_with("int") && v.is_finite() && v.fract() == 0.0 {
        format!("{v:.0}")
    } else {
        fmt(v)
    }
}

/// Sub-column names for 4-wide and 2-wide tensors.
fn sub_names(t: &TensorView) -> Vec<String> {
    match (t.name.as_str(), t.cols()) {
        (_, 1) => vec![t.name.clone()],
        ("probs", 2) => vec!["π(left)".into(), "π(right)".into()],
        (name, 4) => ["x", "ẋ", "θ", "θ̇"]
            .iter()
            .map(|c| format!("{name}.{c}"))
            .collect(),
        (name, n) => (0..n).map(|i| format!("{name}[{i}]")).collect(),
    }
}

/// A value column: its header and one cell per row, as wide as the widest of them.
struct Column {
    header: String,
    cells: Vec<(String, Mark)>,
    width: usize,
}

impl Column {
    fn new(header: String, cells: Vec<(String, Mark)>) -> Self {
        let widest = cells.iter().map(|(c, _)| width(c)).max().unwrap_or(0);
        Self {
            width: widest.max(width(&header)),
            header,
            cells,
        }
    }
}

/// A table: a column of row labels (it stays when the columns scroll), then value columns.
struct Table {
    /// The row labels' header (`t`, the step).
    corner: String,
    rows: Vec<String>,
    columns: Vec<Column>,
}

/// Whether `t` is a batch tensor, one row per step (shown side by side in one table).
fn is_per_step(t: &TensorView) -> bool {
    t.shape.len() == 2 && t.labels.is_empty() && t.axes.is_none()
}

impl Table {
    /// The per-step tensors side by side, a row per step `t`; `None` when there are none.
    fn per_step(tensors: &[&TensorView]) -> Option<Self> {
        let n = tensors.iter().map(|t| t.values.len() / t.cols()).max()?;
        let mut columns = Vec::new();
        for t in tensors {
            let c = t.cols();
            for (k, name) in sub_names(t).into_iter().enumerate() {
                let cells = (0..n)
                    .map(|row| {
                        let i = row * c + k;
                        t.values.get(i).map_or((String::new(), Mark::Plain), |&v| {
                            (fmt_in(t, v), t.marks.get(i).copied().unwrap_or_default())
                        })
                    })
                    .collect();
                columns.push(Column::new(name, cells));
            }
        }
        Some(Self {
            corner: "t".into(),
            rows: (0..n).map(|row| row.to_string()).collect(),
            columns,
        })
    }

    /// A grid with its axes: `θ̇=8` … down the rows, `θ=-π` … across the columns.
    fn grid(t: &TensorView, axes: &Axes) -> Self {
        let c = t.cols();
        let n = t.values.len() / c;
        let label = |axis: &crate::lesson::live::Axis, i: usize| {
            let tick = axis
                .ticks
                .get(i)
                .map_or_else(|| i.to_string(), Clone::clone);
            format!("{}={tick}", axis.name)
        };
        let columns = (0..c)
            .map(|k| {
                let cells = (0..n)
                    .map(|row| {
                        let i = row * c + k;
                        let v = t.values.get(i).copied().unwrap_or(f64::NAN);
                        (fmt_in(t, v), t.marks.get(i).copied().unwrap_or_default())
                    })
                    .collect();
                Column::new(label(&axes.columns, k), cells)
            })
            .collect();
        Self {
            corner: String::new(),
            rows: (0..n).map(|row| label(&axes.rows, row)).collect(),
            columns,
        }
    }

    fn label_width(&self) -> usize {
        self.rows
            .iter()
            .map(|r| width(r))
            .chain([width(&self.corner)])
            .max()
            .unwrap_or(0)
    }

    /// How many columns from `first` fit whole in `room` columns after the row labels (at
    /// least one, cut at the edge, when not even one fits).
    fn fitting(&self, first: usize, room: usize) -> usize {
        let room = room.saturating_sub(self.label_width());
        let mut used = 0;
        let mut count = 0;
        for column in self.columns.iter().skip(first) {
            if used + 1 + column.width > room {
                break;
            }
            used += 1 + column.width;
            count += 1;
        }
        count.max(1).min(self.columns.len().saturating_sub(first))
    }

    /// The table in at most `height` lines: the header, the rows from `view.scroll` and
    /// the columns from `view.hscroll` that fit, then where the rest is.
    fn lines(&self, view: Viewport, height: usize, theme: Theme) -> Vec<Line<'static>> {
        let n = self.rows.len();
        let first = view.hscroll.min(self.columns.len().saturating_sub(1));
        let shown = self.fitting(first, view.width);
        let after = self.columns.len().saturating_sub(first + shown);
        let marker = more_columns(first, after);
        let columns = &self.columns[first..first + shown];
        let label_width = self.label_width();
        let mut header = vec![Span::styled(
            pad_left(&self.corner, label_width),
            theme.dim(),
        )];
        for column in columns {
            let text = format!(" {}", pad_left(&column.header, column.width));
            header.push(Span::styled(text, theme.dim()));
        }
        let mut out = vec![Line::from(header)];
        let mut budget = height.saturating_sub(1 + usize::from(marker.is_some()));
        if n > budget {
            // The "rows a–b of n" line below takes a row too.
            budget = budget.saturating_sub(1);
        }
        let start = view.scroll.min(n.saturating_sub(1));
        let end = n.min(start + budget.max(1));
        for row in start..end {
            let mut spans = vec![Span::styled(
                pad_left(&self.rows[row], label_width),
                theme.dim(),
            )];
            for column in columns {
                let (text, mark) = column
                    .cells
                    .get(row)
                    .map_or(("", Mark::Plain), |(t, m)| (t.as_str(), *m));
                spans.push(Span::styled(
                    format!(" {}", pad_left(text, column.width)),
                    style_of(mark, theme),
                ));
            }
            out.push(Line::from(spans));
        }
        if n > budget {
            out.push(Line::styled(
                tr!(
                    "     rows {}–{} of {n} (J/K scroll)",
                    "     第 {}–{} 行，共 {n} 行（J/K 滚动）",
                    start,
                    end.saturating_sub(1)
                ),
                theme.dim(),
            ));
        }
        if let Some(marker) = marker {
            // Under the row labels' column when there is room, as the rows line.
            let indent = if width(&marker) + 5 <= view.width {
                "     "
            } else {
                ""
            };
            out.push(Line::styled(format!("{indent}{marker}"), theme.dim()));
        }
        out
    }
}

/// Where a table's other columns are, and the keys that scroll to them: `before` columns
/// precede the first one shown, `after` follow the last; `None` when all are shown.
fn more_columns(before: usize, after: usize) -> Option<String> {
    Some(match (before, after) {
        (0, 0) => return None,
        (0, 1) => tr!("→ 1 more column: > scrolls", "→ 还有 1 列：按 > 滚动"),
        (0, n) => tr!("→ {n} more columns: > scrolls", "→ 还有 {n} 列：按 > 滚动"),
        (1, 0) => tr!(
            "← 1 column before: < scrolls back",
            "← 前面还有 1 列：按 < 滚回"
        ),
        (n, 0) => tr!(
            "← {n} columns before: < scrolls back",
            "← 前面还有 {n} 列：按 < 滚回"
        ),
        (b, a) => tr!(
            "← {b} before · {a} more columns → (< >)",
            "← 前面 {b} 列 · 还有 {a} 列 →（按 < >）"
        ),
    })
}

/// A tensor's title line: its name, shape and dtype, its range and what is marked in it.
fn title(t: &TensorView, theme: Theme) -> Line<'static> {
    let stats = t.stats().map_or(String::new(), |(lo, hi, mean)| {
        if t.dtype == "bool" {
            let n = t.values.len();
            // The mean of 0/1 values times their count: how many are True.
            let k = (mean * n as f64).round();
            return tr!("  True in {k} of {n}", "  {n} 个中 {k} 个为 True");
        }
        tr!(
            "  min {}  max {}  mean {}",
            "  最小 {}  最大 {}  均值 {}",
            fmt_in(t, lo),
            fmt_in(t, hi),
            fmt(mean)
        )
    });
    let marks = match (
        t.count(Mark::Clipped),
        t.count(Mark::Done),
        t.count(Mark::Positive),
        t.count(Mark::Negative),
    ) {
        (c, _, _, _) if c > 0 => tr!("  clipped {c}", "  被截断 {c}"),
        (_, d, _, _) if d > 0 => tr!("  done {d}", "  结束 {d}"),
        (_, _, p, n) if p + n > 0 => format!("  A>0 {p}  A<0 {n}"),
        _ => String::new(),
    };
    Line::from(vec![
        Span::styled(t.name.clone(), theme.title()),
        Span::styled(format!(" {}", t.shape_text()), theme.dim()),
        Span::raw(stats),
        Span::styled(marks, theme.dim()),
    ])
}

/// The tables `tensors` make: the per-step tensors in one, each grid in its own, each with
/// the title lines that go above it.
fn tables(tensors: &[TensorView], theme: Theme) -> Vec<(Vec<Line<'static>>, Table)> {
    let per_step: Vec<&TensorView> = tensors.iter().filter(|t| is_per_step(t)).collect();
    let mut out = Vec::new();
    if let Some(table) = Table::per_step(&per_step) {
        out.push((per_step.iter().map(|t| title(t, theme)).collect(), table));
    }
    for t in tensors {
        if let Some(axes) = &t.axes {
            out.push((vec![title(t, theme)], Table::grid(t, axes)));
        }
    }
    out
}

/// The largest useful [`Viewport::hscroll`] on a step showing `show` (live value names):
/// the one that shows the last column of its widest table first; 0 before any values.
#[must_use]
pub fn max_hscroll(snapshot: &Snapshot, show: &[String]) -> usize {
    let shown: Vec<TensorView> = show.iter().filter_map(|n| snapshot.tensor(n)).collect();
    tables(&shown, Theme { color: false })
        .iter()
        .map(|(_, table)| table.columns.len().saturating_sub(1))
        .max()
        .unwrap_or(0)
}

/// Renders `tensors` into at most `view.height` lines, none wider than `view.width` but a
/// title: each table from row `view.scroll` and column `view.hscroll`, then the scalars,
/// series and key/value lists.
#[must_use]
pub fn lines(tensors: &[TensorView], view: Viewport, theme: Theme) -> Vec<Line<'static>> {
    let others: Vec<&TensorView> = tensors
        .iter()
        .filter(|t| !is_per_step(t) && t.axes.is_none())
        .collect();
    // Rows the other values take below the tables: one each, or a title and its labels.
    let below: usize = others
        .iter()
        .map(|t| {
            if t.labels.is_empty() {
                1
            } else {
                1 + t.labels.len()
            }
        })
        .sum();
    let tables = tables(tensors, theme);
    let count = tables.len();
    let mut out = Vec::new();
    for (i, (titles, table)) in tables.into_iter().enumerate() {
        out.extend(titles);
        // Each later table keeps room for its title, its header and a row.
        let later = 3 * (count - i - 1);
        let room = view.height.saturating_sub(out.len() + below.min(8) + later);
        out.extend(table.lines(view, room, theme));
    }
    for t in others {
        if !t.labels.is_empty() {
            out.push(Line::styled(
                format!("{} {}", t.name, t.shape_text()),
                theme.title(),
            ));
            out.extend(t.labels.iter().map(|l| Line::raw(format!("  {l}"))));
            continue;
        }
        let mut spans = vec![
            Span::styled(t.name.clone(), theme.title()),
            Span::styled(format!(" {} ", t.shape_text()), theme.dim()),
        ];
        // Long series (returns) show their latest values.
        let skip = t.values.len().saturating_sub(8);
        let shown: Vec<String> = t.values[skip..].iter().map(|&v| fmt_in(t, v)).collect();
        let more = if skip > 0 { "…, " } else { "" };
        spans.push(Span::raw(format!("[{more}{}]", shown.join(", "))));
        out.push(Line::from(spans));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::i18n::Lang;
    use crate::lesson::live::Axis;

    fn view(name: &str, cols: usize, dtype: &'static str, values: Vec<f64>) -> TensorView {
        TensorView {
            name: name.into(),
            shape: vec![values.len() / cols, cols],
            dtype,
            labels: Vec::new(),
            marks: vec![Mark::Plain; values.len()],
            values,
            axes: None,
        }
    }

    fn text(tensors: &[TensorView], view: Viewport) -> Vec<String> {
        lines(tensors, view, Theme { color: false })
            .iter()
            .map(ToString::to_string)
            .collect()
    }

    /// Lesson 3's last step: `states`, `actions`, `rewards`, `next_states`, `dones`, 11
    /// columns in all, far wider than the pane at 80×24 (40 columns inside).
    fn episode() -> Vec<TensorView> {
        let rows = 29;
        let obs: Vec<f64> = (0..rows * 4).map(|i| -0.1521 + 0.001 * i as f64).collect();
        vec![
            view("states", 4, "float32", obs.clone()),
            view(
                "actions",
                1,
                "int64",
                (0..rows).map(|i| (i % 2) as f64).collect(),
            ),
            view("rewards", 1, "float32", vec![1.0; rows]),
            view("next_states", 4, "float32", obs),
            view("dones", 1, "float32", vec![0.0; rows]),
        ]
    }

    const PANE: Viewport = Viewport {
        width: 40,
        height: 14,
        scroll: 0,
        hscroll: 0,
    };

    /// The header row: the line that starts with the step column's `t`.
    fn header_row(lines: &[String]) -> Result<&String, &'static str> {
        lines
            .iter()
            .find(|l| l.trim_start().starts_with("t "))
            .ok_or("no header row")
    }

    /// Issue 25: `int64` actions show as integers, floats keep four decimals.
    #[test]
    fn integers_show_as_integers() {
        let values = vec![0.0, 1.0];
        let shown = text(&[view("actions", 1, "int64", values.clone())], PANE).join("\n");
        assert!(
            !shown.contains("1.0000") && shown.contains("  1"),
            "{shown}"
        );
        let shown = text(&[view("actions", 1, "float32", values)], PANE).join("\n");
        assert!(shown.contains("1.0000"), "{shown}");
    }

    /// Booleans (`clipped`) show as PyTorch prints them, `True`/`False`, not `1.0000`.
    #[test]
    fn booleans_show_as_true_and_false() {
        let _en = Lang::En.scoped();
        let shown = text(&[view("clipped", 1, "bool", vec![0.0, 1.0])], PANE).join("\n");
        assert!(shown.contains("False") && shown.contains("True"), "{shown}");
        assert!(
            !shown.contains("1.0000") && !shown.contains("0.0000"),
            "{shown}"
        );
        assert!(shown.contains("True in 1 of 2"), "{shown}");
    }

    /// Issue 25, section 2: a table wider than the pane shows the columns that fit whole
    /// (no `actio`), never a line wider than the pane, and says how many follow and which
    /// key scrolls to them.
    #[test]
    fn a_table_wider_than_the_pane_shows_whole_columns_and_the_way_to_the_rest()
    -> Result<(), &'static str> {
        let _en = Lang::En.scoped();
        let tensors = episode();
        let names: Vec<String> = tensors.iter().flat_map(sub_names).collect();
        let shown = text(&tensors, PANE);
        let header = header_row(&shown)?;
        let cells: Vec<&str> = header.split_whitespace().skip(1).collect();
        assert!(!cells.is_empty(), "{shown:#?}");
        for cell in &cells {
            assert!(
                names.iter().any(|n| n == cell),
                "cut header {cell:?}: {shown:#?}"
            );
        }
        assert_eq!(cells[0], "states.x", "the first column first");
        for line in shown.iter().skip(tensors.len()) {
            assert!(width(line) <= PANE.width, "wider than the pane: {line:?}");
        }
        let more = names.len() - cells.len();
        let marker = format!("→ {more} more columns: > scrolls");
        assert!(shown.iter().any(|l| l.contains(&marker)), "{shown:#?}");
        // Wide enough for every column: no marker.
        let wide = text(&tensors, Viewport { width: 160, ..PANE });
        assert_eq!(
            header_row(&wide)?.split_whitespace().count(),
            names.len() + 1
        );
        assert!(!wide.iter().any(|l| l.contains('→')), "{wide:#?}");
        Ok(())
    }

    /// Issue 25, section 2: with offset k, column k comes first (the step column stays),
    /// the marker says that columns precede, and every column can be reached.
    #[test]
    fn the_horizontal_offset_picks_the_first_column_shown() -> Result<(), &'static str> {
        let _en = Lang::En.scoped();
        let tensors = episode();
        let names: Vec<String> = tensors.iter().flat_map(sub_names).collect();
        for (k, name) in names.iter().enumerate() {
            let shown = text(&tensors, Viewport { hscroll: k, ..PANE });
            let cells: Vec<&str> = header_row(&shown)?.split_whitespace().collect();
            assert_eq!(cells.first(), Some(&"t"), "{shown:#?}");
            assert_eq!(cells.get(1), Some(&name.as_str()), "{shown:#?}");
            let marker = shown.last().ok_or("no lines")?;
            if k > 0 {
                assert!(marker.contains(&format!("← {k} ")), "{marker}");
                assert!(marker.contains('<'), "{marker}");
            }
        }
        // Past the last column: the last one first.
        let shown = text(
            &tensors,
            Viewport {
                hscroll: 99,
                ..PANE
            },
        );
        assert_eq!(header_row(&shown)?.split_whitespace().nth(1), Some("dones"));
        let marker = format!("← {} columns before: < scrolls back", names.len() - 1);
        assert!(shown.iter().any(|l| l.contains(&marker)), "{shown:#?}");
        Ok(())
    }

    /// Issue 25, section 2: the marker in Chinese is all Chinese (and keys), and fits.
    #[test]
    fn the_marker_speaks_the_screen_s_language() -> Result<(), &'static str> {
        let _zh = Lang::Zh.scoped();
        let tensors = episode();
        for hscroll in [0, 3, 10] {
            let shown = text(&tensors, Viewport { hscroll, ..PANE });
            let marker = shown.last().ok_or("no lines")?;
            assert!(marker.contains('列') && marker.contains('按'), "{marker}");
            assert!(!marker.chars().any(|c| c.is_ascii_alphabetic()), "{marker}");
            assert!(width(marker) <= PANE.width, "{marker}");
        }
        let shown = text(&tensors, PANE);
        let more = tensors.iter().map(TensorView::cols).sum::<usize>() - 4;
        let marker = format!("→ 还有 {more} 列：按 > 滚动");
        assert!(shown.iter().any(|l| l.contains(&marker)), "{shown:#?}");
        Ok(())
    }

    /// Issue 25, section 2: a grid labels its rows `θ̇=…` (not `t`) and its columns `θ=…`,
    /// and its columns scroll like a table's.
    #[test]
    fn a_grid_labels_both_axes_and_scrolls() -> Result<(), &'static str> {
        let _en = Lang::En.scoped();
        let thetas = [
            "-π", "-3π/4", "-π/2", "-π/4", "0", "π/4", "π/2", "3π/4", "π",
        ];
        let dots = ["8", "6", "4", "2", "0", "-2", "-4", "-6", "-8"];
        let mut map = view("mu_map", 9, "float32", vec![-0.9872; 81]);
        map.axes = Some(Axes {
            rows: Axis {
                name: "θ̇",
                ticks: dots.iter().map(ToString::to_string).collect(),
            },
            columns: Axis {
                name: "θ",
                ticks: thetas.iter().map(ToString::to_string).collect(),
            },
        });
        let tensors = [map];
        let shown = text(&tensors, PANE);
        let header = shown.get(1).ok_or("no header")?;
        assert!(header.trim_start().starts_with("θ=-π "), "{shown:#?}");
        assert!(!header.contains("mu_map["), "{header}");
        assert!(shown[2].trim_start().starts_with("θ̇=8 "), "{shown:#?}");
        assert!(shown.iter().any(|l| l.trim_start().starts_with("θ̇=-8 ")));
        assert!(
            !shown
                .iter()
                .skip(1)
                .any(|l| l.trim_start().starts_with("t "))
        );
        let cells = header.split_whitespace().count();
        let marker = format!("→ {} more columns: > scrolls", 9 - cells);
        assert!(shown.iter().any(|l| l.contains(&marker)), "{shown:#?}");
        let last = text(&tensors, Viewport { hscroll: 8, ..PANE });
        assert!(last[1].trim_start().starts_with("θ=π"), "{last:#?}");
        assert!(last[2].trim_start().starts_with("θ̇=8 "), "{last:#?}");
        Ok(())
    }
}
