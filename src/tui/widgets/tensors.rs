//! Live tensors as text: the batch's per-step columns side by side, the latest update's
//! per-epoch values side by side (a row per epoch), the run's per-episode curves (a row per
//! episode), grids (the policy maps) with both axes labelled, lists of named rows (`hyper`,
//! `weights`), then scalars.
//!
//! Each column is as wide as its header and its values need, so a header is never cut. When
//! a table's columns do not all fit the pane, it shows those that fit whole from
//! [`Viewport::hscroll`] on, keeps its row labels, and says under it how many columns
//! precede (`←`) and follow (`→`) and that `<` and `>` scroll them. When its rows do not
//! all fit, it shows a window from [`Viewport::scroll`] (never past its last full page, so
//! that `End` shows the last row) and says which rows it shows. Every value of a table can
//! be reached: no series is cut to its latest entries.

use ratatui::style::Style;
use ratatui::text::{Line, Span};

use super::text::{pad_left, width};
use crate::lesson::live::Axes;
use crate::lesson::{Index, Mark, Snapshot, TensorView};
use crate::tr;
use crate::tui::theme::Theme;

/// The part of the live values a pane shows, and the pane's size.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Viewport {
    /// The pane's width, in terminal columns.
    pub width: usize,
    /// The pane's height, in rows.
    pub height: usize,
    /// The first row of each table shown (`J`/`K`, PgDn/PgUp, Home/End scroll it).
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

/// Sub-column names for 4-wide (CartPole's observation), 3-wide (Pendulum's) and 2-wide
/// tensors.
fn sub_names(t: &TensorView) -> Vec<String> {
    let observation = matches!(t.name.as_str(), "states" | "next_states" | "obs");
    match (t.name.as_str(), t.cols()) {
        (_, 1) => vec![t.name.clone()],
        ("probs", 2) => vec!["π(left)".into(), "π(right)".into()],
        (name, 4) => ["x", "ẋ", "θ", "θ̇"]
            .iter()
            .map(|c| format!("{name}.{c}"))
            .collect(),
        (name, 3) if observation => ["cosθ", "sinθ", "θ̇"]
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
/// A list of named rows (`hyper`) is a table without value columns (and without a header).
struct Table {
    /// The row labels' header (`t`, the step; `epoch`; `episode`).
    corner: String,
    rows: Vec<String>,
    columns: Vec<Column>,
}

/// Whether `t` is a batch tensor, one row per step (shown side by side in one table).
fn is_per_step(t: &TensorView) -> bool {
    t.shape.len() == 2 && t.labels.is_empty() && t.axes.is_none()
}

/// Whether `t` is a vector with one entry per `index` (epoch or episode).
fn counts(t: &TensorView, index: Index) -> bool {
    index != Index::None && t.index == index && t.shape.len() == 1 && t.labels.is_empty()
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

    /// Vectors with one entry per `index` side by side, a row per epoch or episode,
    /// numbered from 1; `None` when there are none.
    fn counted(tensors: &[&TensorView], index: Index) -> Option<Self> {
        let n = tensors.iter().map(|t| t.values.len()).max()?;
        let columns = tensors
            .iter()
            .map(|t| {
                let cells = (0..n)
                    .map(|i| {
                        t.values.get(i).map_or((String::new(), Mark::Plain), |&v| {
                            (fmt_in(t, v), t.marks.get(i).copied().unwrap_or_default())
                        })
                    })
                    .collect();
                Column::new(t.name.clone(), cells)
            })
            .collect();
        Some(Self {
            corner: index.name().to_string(),
            rows: (1..=n).map(|row| row.to_string()).collect(),
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

    /// A list of named rows (`gamma = 0.98`), indented under its title.
    fn list(t: &TensorView) -> Self {
        Self {
            corner: String::new(),
            rows: t.labels.iter().map(|l| format!("  {l}")).collect(),
            columns: Vec::new(),
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

    /// The lines besides the rows: the header (none for a list) and the columns marker.
    fn frame_lines(&self, view: Viewport) -> usize {
        let first = view.hscroll.min(self.columns.len().saturating_sub(1));
        let shown = self.fitting(first, view.width);
        let after = self.columns.len().saturating_sub(first + shown);
        usize::from(!self.columns.is_empty()) + usize::from(more_columns(first, after).is_some())
    }

    /// The lines the whole table takes.
    fn natural_height(&self, view: Viewport) -> usize {
        self.frame_lines(view) + self.rows.len()
    }

    /// The fewest lines the table is given: its frame and up to `rows` of its rows (with
    /// the rows line when they are not all).
    fn least_height(&self, view: Viewport, rows: usize) -> usize {
        let n = self.rows.len();
        self.frame_lines(view) + n.min(rows) + usize::from(n > rows)
    }

    /// The table in at most `height` lines: the header, the rows from `view.scroll` (at
    /// most up to the last full page) and the columns from `view.hscroll` that fit, then
    /// where the rest is.
    fn lines(&self, view: Viewport, height: usize, theme: Theme) -> (Vec<Line<'static>>, Rows) {
        let n = self.rows.len();
        let first = view.hscroll.min(self.columns.len().saturating_sub(1));
        let shown = if self.columns.is_empty() {
            0
        } else {
            self.fitting(first, view.width)
        };
        let after = self.columns.len().saturating_sub(first + shown);
        let marker = more_columns(first, after);
        let columns = &self.columns[first.min(self.columns.len())..first + shown];
        let label_width = self.label_width();
        let mut out = Vec::new();
        if !self.columns.is_empty() {
            let mut header = vec![Span::styled(
                pad_left(&self.corner, label_width),
                theme.dim(),
            )];
            for column in columns {
                let text = format!(" {}", pad_left(&column.header, column.width));
                header.push(Span::styled(text, theme.dim()));
            }
            out.push(Line::from(header));
        }
        let mut budget = height.saturating_sub(out.len() + usize::from(marker.is_some()));
        if n > budget {
            // The "rows a–b of n" line below takes a row too.
            budget = budget.saturating_sub(1);
        }
        let budget = budget.max(1);
        let start = view.scroll.min(n.saturating_sub(budget));
        let end = n.min(start + budget);
        for row in start..end {
            let label = if self.columns.is_empty() {
                self.rows[row].clone()
            } else {
                pad_left(&self.rows[row], label_width)
            };
            let mut spans = vec![Span::styled(
                label,
                if self.columns.is_empty() {
                    Style::new()
                } else {
                    theme.dim()
                },
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
        if end - start < n {
            let (a, b) = if self.columns.is_empty() {
                ((start + 1).to_string(), end.to_string())
            } else {
                (
                    self.rows[start].trim().to_string(),
                    self.rows[end - 1].trim().to_string(),
                )
            };
            let long = tr!(
                "     rows {a}–{b} of {n} (J/K, PgDn/PgUp, Home/End)",
                "     第 {a}–{b} 行，共 {n} 行（J/K、PgDn/PgUp、Home/End）"
            );
            let line = if width(&long) <= view.width {
                long
            } else {
                tr!(
                    "  rows {a}–{b} of {n} (J/K)",
                    "  第 {a}–{b} 行，共 {n} 行（J/K）"
                )
            };
            out.push(Line::styled(line, theme.dim()));
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
        let rows = Rows {
            shown: end - start,
            last_start: n.saturating_sub(budget),
        };
        (out, rows)
    }
}

/// How a drawing showed the tables' rows: what the scroll keys need to know.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Rows {
    /// The fewest rows any table with hidden rows showed (a page, for PgDn/PgUp); 0 when
    /// every row showed.
    pub shown: usize,
    /// The largest scroll that still moves a table: its first row when it shows its last.
    pub last_start: usize,
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

/// The title of a table of per-epoch values: what its rows are, and its columns' dtype.
fn epoch_title(tensors: &[&TensorView], theme: Theme) -> Line<'static> {
    let dtype = tensors.first().map_or("", |t| t.dtype);
    Line::from(vec![
        Span::styled(
            crate::i18n::t("each epoch of the latest update", "最近一次更新的每一轮"),
            theme.title(),
        ),
        Span::styled(format!(" {dtype}"), theme.dim()),
    ])
}

/// The tables `tensors` make, in the order they are drawn: the per-step tensors in one,
/// the per-epoch ones in one, the per-episode ones in one, each grid and each list of named
/// rows in its own, each with the title lines that go above it.
fn tables(tensors: &[TensorView], theme: Theme) -> Vec<(Vec<Line<'static>>, Table)> {
    let per_step: Vec<&TensorView> = tensors.iter().filter(|t| is_per_step(t)).collect();
    let mut out = Vec::new();
    if let Some(table) = Table::per_step(&per_step) {
        out.push((per_step.iter().map(|t| title(t, theme)).collect(), table));
    }
    let per_epoch: Vec<&TensorView> = tensors.iter().filter(|t| counts(t, Index::Epoch)).collect();
    if let Some(table) = Table::counted(&per_epoch, Index::Epoch) {
        out.push((vec![epoch_title(&per_epoch, theme)], table));
    }
    let per_episode: Vec<&TensorView> = tensors
        .iter()
        .filter(|t| counts(t, Index::Episode))
        .collect();
    if let Some(table) = Table::counted(&per_episode, Index::Episode) {
        out.push((per_episode.iter().map(|t| title(t, theme)).collect(), table));
    }
    for t in tensors {
        if let Some(axes) = &t.axes {
            out.push((vec![title(t, theme)], Table::grid(t, axes)));
        }
    }
    for t in tensors.iter().filter(|t| !t.labels.is_empty()) {
        let title = Line::from(vec![
            Span::styled(t.name.clone(), theme.title()),
            Span::styled(format!(" {}", t.shape_text()), theme.dim()),
        ]);
        out.push((vec![title], Table::list(t)));
    }
    out
}

/// Whether `t` is drawn as a line of its own (a scalar, a short vector), not in a table.
fn is_line(t: &TensorView) -> bool {
    !is_per_step(t)
        && t.axes.is_none()
        && t.labels.is_empty()
        && !counts(t, Index::Epoch)
        && !counts(t, Index::Episode)
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

/// A scalar or short vector as one line, `name (shape) dtype [values]`, wrapped onto more
/// lines (indented) when it is wider than the pane: nothing is cut.
fn value_lines(t: &TensorView, columns: usize, theme: Theme) -> Vec<Line<'static>> {
    let values: Vec<String> = t.values.iter().map(|&v| fmt_in(t, v)).collect();
    let head = vec![
        Span::styled(t.name.clone(), theme.title()),
        Span::styled(format!(" {} ", t.shape_text()), theme.dim()),
    ];
    let one = format!("[{}]", values.join(", "));
    let head_width: usize = head.iter().map(Span::width).sum();
    if head_width + width(&one) <= columns || values.len() <= 1 {
        let mut spans = head;
        spans.push(Span::raw(one));
        return vec![Line::from(spans)];
    }
    let mut out = vec![Line::from(head)];
    let mut line = String::from("  [");
    for (i, v) in values.iter().enumerate() {
        let piece = if i + 1 < values.len() {
            format!("{v}, ")
        } else {
            format!("{v}]")
        };
        if width(&line) + width(&piece) > columns && line.trim() != "[" {
            out.push(Line::raw(line.trim_end().to_string()));
            line = String::from("   ");
        }
        line.push_str(&piece);
    }
    out.push(Line::raw(line));
    out
}

/// Heights for tables whose whole heights are `natural` and least heights `least`, in
/// `room` lines: every table whole when they fit; otherwise each gets its least height, and
/// what is left goes first to the tables marked `first` (the short lists of named rows,
/// which a step's text names row by row), then to the others from the shortest up, so that
/// a short table (ten epochs) shows whole beside a long one (an episode's steps), which
/// scrolls.
fn share(natural: &[usize], least: &[usize], first: &[bool], room: usize) -> Vec<usize> {
    if natural.iter().sum::<usize>() <= room {
        return natural.to_vec();
    }
    let mut heights: Vec<usize> = least.iter().zip(natural).map(|(&l, &n)| l.min(n)).collect();
    let mut left = room.saturating_sub(heights.iter().sum());
    let mut order: Vec<usize> = (0..natural.len()).collect();
    order.sort_by_key(|&i| (!first[i], natural[i]));
    for i in order {
        let more = natural[i].saturating_sub(heights[i]).min(left);
        heights[i] += more;
        left -= more;
    }
    heights
}

/// Renders `tensors` into at most `view.height` lines, none wider than `view.width` but a
/// title: each table from row `view.scroll` and column `view.hscroll`, then the scalars.
#[must_use]
pub fn lines(tensors: &[TensorView], view: Viewport, theme: Theme) -> Vec<Line<'static>> {
    render(tensors, view, theme).0
}

/// [`lines`], and how the tables' rows were shown (for the scroll keys).
#[must_use]
pub fn render(tensors: &[TensorView], view: Viewport, theme: Theme) -> (Vec<Line<'static>>, Rows) {
    let scalars: Vec<Line<'static>> = tensors
        .iter()
        .filter(|t| is_line(t))
        .flat_map(|t| value_lines(t, view.width, theme))
        .collect();
    let tables = tables(tensors, theme);
    let natural: Vec<usize> = tables
        .iter()
        .map(|(titles, table)| titles.len() + table.natural_height(view))
        .collect();
    // Three rows of each table at least, or one when the pane is too short for three.
    let least_with = |rows: usize| -> Vec<usize> {
        tables
            .iter()
            .map(|(titles, table)| titles.len() + table.least_height(view, rows))
            .collect()
    };
    let room = view.height.saturating_sub(scalars.len());
    let mut least = least_with(3);
    if least.iter().sum::<usize>() > room {
        least = least_with(1);
    }
    let lists: Vec<bool> = tables
        .iter()
        .map(|(_, table)| table.columns.is_empty())
        .collect();
    let heights = share(&natural, &least, &lists, room);
    let mut out = Vec::new();
    let mut all = Rows::default();
    for ((titles, table), height) in tables.into_iter().zip(heights) {
        let room = height.saturating_sub(titles.len());
        out.extend(titles);
        let (lines, rows) = table.lines(view, room, theme);
        out.extend(lines);
        if rows.last_start > 0 {
            all.shown = if all.shown == 0 {
                rows.shown
            } else {
                all.shown.min(rows.shown)
            };
        }
        all.last_start = all.last_start.max(rows.last_start);
    }
    out.extend(scalars);
    (out, all)
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
            index: Index::None,
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

    /// `int64` actions show as integers, floats keep four decimals.
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

    /// A table wider than the pane shows the columns that fit whole
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

    /// With offset k, column k comes first (the step column stays),
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

    /// The marker in Chinese is all Chinese (and keys), and fits.
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

    /// A grid labels its rows `θ̇=…` (not `t`) and its columns `θ=…`,
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

    /// A per-epoch series of `n` values, as the live values make them.
    fn per_epoch(name: &str, values: Vec<f64>) -> TensorView {
        let mut t = view(name, 1, "float32", values);
        t.shape = vec![t.values.len()];
        t.index = Index::Epoch;
        t
    }

    /// Lesson 13 step 1's series: every epoch is a row, numbered from 1, so the first
    /// epoch's `approx_kl` (exactly 0) and ratios (exactly 1) can be read, at 80×24 and at
    /// 160×50, and no line is cut on the right.
    #[test]
    fn every_epoch_of_a_per_epoch_series_is_a_row() -> Result<(), String> {
        let _en = Lang::En.scoped();
        let epochs = 10;
        let kl: Vec<f64> = (0..epochs).map(|e| 1e-4 * e as f64).collect();
        let tensors = [
            per_epoch("approx_kl", kl),
            per_epoch("clip_frac", vec![0.0; epochs]),
            per_epoch(
                "ratio_min",
                (0..epochs).map(|e| 1.0 - 0.01 * e as f64).collect(),
            ),
            per_epoch(
                "ratio_max",
                (0..epochs).map(|e| 1.0 + 0.01 * e as f64).collect(),
            ),
            per_epoch("entropy", vec![0.69; epochs]),
        ];
        for pane in [
            PANE,
            Viewport {
                width: 86,
                height: 28,
                ..PANE
            },
        ] {
            let shown = text(&tensors, pane);
            let header = shown
                .iter()
                .find(|l| l.trim_start().starts_with("epoch "))
                .ok_or(format!("no epoch header: {shown:#?}"))?;
            assert!(header.contains("approx_kl"), "{header}");
            let first = shown
                .iter()
                .find(|l| l.trim_start().starts_with("1 "))
                .ok_or(format!("no row for epoch 1: {shown:#?}"))?;
            assert!(first.contains("0.0000"), "epoch 1's KL: {first}");
            for line in &shown {
                assert!(width(line) <= pane.width, "cut on the right: {line:?}");
            }
            // Every epoch is on screen, or reachable by scrolling the rows.
            let mut seen = std::collections::BTreeSet::new();
            for scroll in 0..epochs {
                for line in text(&tensors, Viewport { scroll, ..pane }) {
                    if let Some(Ok(e)) = line.split_whitespace().next().map(str::parse::<usize>) {
                        seen.insert(e);
                    }
                }
            }
            assert_eq!(seen, (1..=epochs).collect(), "{shown:#?}");
        }
        // At 160×50 the table fits whole: no rows line.
        let wide = text(
            &tensors,
            Viewport {
                width: 86,
                height: 28,
                ..PANE
            },
        );
        assert!(!wide.iter().any(|l| l.contains("rows ")), "{wide:#?}");
        Ok(())
    }

    /// A long per-episode curve (500 returns) is a table too: `End` (the largest scroll)
    /// shows its last row, and the first rows are where it starts.
    #[test]
    fn the_last_row_of_a_long_table_can_be_reached() -> Result<(), String> {
        let _en = Lang::En.scoped();
        let mut returns = view("returns", 1, "float64", (1..=500).map(f64::from).collect());
        returns.shape = vec![500];
        returns.index = Index::Episode;
        let tensors = [returns];
        let top = text(&tensors, PANE);
        assert!(
            top.iter().any(|l| l.trim_start().starts_with("episode ")),
            "{top:#?}"
        );
        let words = |l: &String| l.split_whitespace().collect::<Vec<_>>().join(" ");
        assert!(top.iter().any(|l| words(l) == "1 1.0000"), "{top:#?}");
        let end = text(
            &tensors,
            Viewport {
                scroll: usize::MAX,
                ..PANE
            },
        );
        assert!(end.iter().any(|l| words(l) == "500 500.0000"), "{end:#?}");
        let rows = end
            .iter()
            .find(|l| l.contains("of 500"))
            .ok_or(format!("no rows line: {end:#?}"))?;
        assert!(rows.contains("–500 of 500"), "{rows}");
        Ok(())
    }

    /// A list of named rows (`hyper`, 10 of them) beside a batch table shows every row when
    /// the pane has room, and otherwise scrolls to them; it is never cut after a few.
    #[test]
    fn a_list_of_named_rows_is_shown_whole_or_scrolls() {
        let _en = Lang::En.scoped();
        let mut hyper = view("hyper", 1, "", vec![f64::NAN; 10]);
        hyper.shape = vec![10];
        hyper.labels = (0..10).map(|i| format!("knob{i} = {i}")).collect();
        let mut tensors = vec![hyper];
        tensors.push(view("td_delta", 1, "float32", vec![0.5; 29]));
        let tall = text(&tensors, Viewport { height: 40, ..PANE });
        for i in 0..10 {
            assert!(
                tall.iter().any(|l| l.trim() == format!("knob{i} = {i}")),
                "knob{i}: {tall:#?}"
            );
        }
        let short = text(&tensors, PANE);
        assert!(short.len() <= PANE.height, "{short:#?}");
        let end = text(
            &tensors,
            Viewport {
                scroll: usize::MAX,
                ..PANE
            },
        );
        assert!(end.iter().any(|l| l.trim() == "knob9 = 9"), "{end:#?}");
    }

    /// Pendulum's observation columns are named by what they are: cos θ, sin θ, θ̇.
    #[test]
    fn pendulum_observations_name_their_columns() {
        let t = view("states", 3, "float32", vec![1.0, 0.0, 0.5]);
        assert_eq!(sub_names(&t), ["states.cosθ", "states.sinθ", "states.θ̇"]);
        let other = view("mu", 3, "float32", vec![0.0; 3]);
        assert_eq!(sub_names(&other), ["mu[0]", "mu[1]", "mu[2]"]);
    }

    /// A scalar line wider than the pane wraps; it is not cut.
    #[test]
    fn a_wide_vector_wraps_instead_of_being_cut() {
        let mut t = view(
            "kl",
            1,
            "float32",
            (0..12).map(|i| 0.1234 * f64::from(i)).collect(),
        );
        t.shape = vec![12];
        let shown = text(&[t], PANE);
        assert!(shown.len() > 1, "{shown:#?}");
        assert!(shown.iter().all(|l| width(l) <= PANE.width), "{shown:#?}");
        assert!(shown.iter().any(|l| l.contains("1.3574]")), "{shown:#?}");
    }

    /// The pane's lines go to the short tables whole first (a list of named rows before
    /// anything), the longest table scrolls.
    #[test]
    fn short_tables_show_whole_beside_a_long_one() {
        // An episode's 29 steps (31 lines), ten epochs (12), and a 14-row list (15).
        let natural = [31, 12, 15];
        let least = [6, 6, 5];
        assert_eq!(
            share(&natural, &least, &[false, false, true], 40),
            [13, 12, 15]
        );
        assert_eq!(share(&natural, &least, &[false, false, true], 100), natural);
        assert_eq!(share(&natural, &least, &[false, false, true], 10), least);
    }
}
