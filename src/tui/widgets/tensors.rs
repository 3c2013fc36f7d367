//! Live tensors as text: per-step columns side by side, then scalars and series.

use ratatui::style::Style;
use ratatui::text::{Line, Span};

use super::text::{pad_left, truncate};
use crate::lesson::{Mark, TensorView};
use crate::tr;
use crate::tui::theme::Theme;

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
/// them, not `1.0000`.
fn fmt_in(t: &TensorView, v: f64) -> String {
    if t.dtype.starts_with("int") && v.is_finite() && v.fract() == 0.0 {
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

/// Renders `tensors` into at most `height` lines, rows from `scroll`.
#[must_use]
pub fn lines(
    tensors: &[TensorView],
    scroll: usize,
    height: usize,
    theme: Theme,
) -> Vec<Line<'static>> {
    let rows_of = |t: &TensorView| t.values.len() / t.cols();
    let per_step: Vec<&TensorView> = tensors
        .iter()
        .filter(|t| t.shape.len() == 2 && t.labels.is_empty())
        .collect();
    let others: Vec<&TensorView> = tensors
        .iter()
        .filter(|t| !(t.shape.len() == 2 && t.labels.is_empty()))
        .collect();
    let mut out = Vec::new();
    for t in &per_step {
        let stats = t.stats().map_or(String::new(), |(lo, hi, mean)| {
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
        out.push(Line::from(vec![
            Span::styled(t.name.clone(), theme.title()),
            Span::styled(format!(" {}", t.shape_text()), theme.dim()),
            Span::raw(stats),
            Span::styled(marks, theme.dim()),
        ]));
    }
    if let Some(n) = per_step.iter().map(|t| rows_of(t)).max() {
        let mut header = vec![Span::styled(format!("{:>4}", "t"), theme.dim())];
        for t in &per_step {
            for name in sub_names(t) {
                // Padded and cut by columns: `obs.θ̇` has a combining mark.
                let name = pad_left(&truncate(&name, 11), 11);
                header.push(Span::styled(format!(" {name}"), theme.dim()));
            }
        }
        out.push(Line::from(header));
        // Rows the other values take below the table: one each, or a title and its labels.
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
        let mut budget = height.saturating_sub(out.len() + below.min(8));
        if n > budget {
            // The "rows a–b of n" line below takes a row too.
            budget = budget.saturating_sub(1);
        }
        let start = scroll.min(n.saturating_sub(1));
        for row in start..n.min(start + budget.max(1)) {
            let mut spans = vec![Span::styled(format!("{row:>4}"), theme.dim())];
            for t in &per_step {
                let c = t.cols();
                for k in 0..c {
                    let i = row * c + k;
                    let (text, mark) = t.values.get(i).map_or((String::new(), Mark::Plain), |&v| {
                        (fmt_in(t, v), t.marks.get(i).copied().unwrap_or_default())
                    });
                    spans.push(Span::styled(format!(" {text:>11}"), style_of(mark, theme)));
                }
            }
            out.push(Line::from(spans));
        }
        if n > budget {
            out.push(Line::styled(
                tr!(
                    "     rows {}–{} of {n} (J/K scroll)",
                    "     第 {}–{} 行，共 {n} 行（J/K 滚动）",
                    start,
                    (start + budget).min(n).saturating_sub(1)
                ),
                theme.dim(),
            ));
        }
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

    /// Issue 25: `int64` actions show as integers, floats keep four decimals.
    #[test]
    fn integers_show_as_integers() {
        let view = |dtype: &'static str| TensorView {
            name: "actions".into(),
            shape: vec![2, 1],
            dtype,
            labels: Vec::new(),
            values: vec![0.0, 1.0],
            marks: vec![Mark::Plain; 2],
        };
        let ints = view("int64");
        let text = |t: &TensorView| -> String {
            lines(std::slice::from_ref(t), 0, 20, Theme { color: false })
                .iter()
                .map(ToString::to_string)
                .collect::<Vec<_>>()
                .join("\n")
        };
        let shown = text(&ints);
        assert!(
            !shown.contains("1.0000") && shown.contains("  1"),
            "{shown}"
        );
        let shown = text(&view("float32"));
        assert!(shown.contains("1.0000"), "{shown}");
    }
}
