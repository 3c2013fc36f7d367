//! The return curve and its moving average as a ratatui `Chart`, and the legend every chart
//! here draws on rows of its own (`draw_chart`).

use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::Style;
use ratatui::symbols::Marker;
use ratatui::text::{Line, Span};
use ratatui::widgets::{Axis, Block, Chart, Dataset, GraphType, Paragraph, Widget};

use super::text;
use crate::i18n::t;
use crate::tui::theme::Theme;

/// The return plot: this run's returns and moving average, and optionally a previous run.
pub struct ReturnPlot<'a> {
    /// This run's returns.
    pub returns: &'a [f64],
    /// Their moving average (may be empty while fewer than 8 episodes are done).
    pub average: &'a [f64],
    /// The moving average's window, in episodes (the legend says it).
    pub window: usize,
    /// A previous run to overlay: label and returns' moving average or raw returns.
    pub previous: Option<(&'a str, &'a [f64])>,
    /// The y-axis top: the time limit for CartPole (500 for v1), 0 for Pendulum.
    pub max_return: f64,
    /// The y-axis bottom: 0 for CartPole, a poor return for Pendulum (whose returns are
    /// negative).
    pub min_return: f64,
    /// The surrounding block.
    pub block: Block<'a>,
    /// Styles.
    pub theme: Theme,
}

/// Columns between two legend entries.
const LEGEND_GAP: usize = 3;

/// The legend's rows for a chart `width` columns wide: each named series in its style,
/// packed into as few rows as the width allows, right-aligned; the axis title at the left
/// of the first row when there is room for it. An entry wider than a row is cut with a `…`.
fn legend_rows(
    legend: &[(String, Style)],
    y_title: Option<Span<'static>>,
    width: usize,
    theme: Theme,
) -> Vec<Line<'static>> {
    let mut rows: Vec<Vec<Span<'static>>> = Vec::new();
    let mut used = 0;
    for (name, style) in legend {
        let w = text::width(name);
        match rows.last_mut() {
            Some(row) if used + LEGEND_GAP + w <= width => {
                row.push(Span::raw(" ".repeat(LEGEND_GAP)));
                used += LEGEND_GAP + w;
                row.push(Span::styled(name.clone(), *style));
            }
            _ => {
                rows.push(vec![Span::styled(name.clone(), *style)]);
                used = w;
            }
        }
    }
    let mut lines: Vec<Line<'static>> = rows
        .into_iter()
        .map(|row| {
            let line = text::cut(Line::from(row), width, Span::styled("…", theme.dim()));
            let pad = width.saturating_sub(line.width());
            let mut spans = vec![Span::raw(" ".repeat(pad))];
            spans.extend(line.spans);
            Line::from(spans)
        })
        .collect();
    if let Some(title) = y_title {
        match lines.first_mut() {
            // The first row starts with its padding: the title takes its place.
            Some(first) if first.spans[0].width() > title.width() + 1 => {
                let pad = first.spans[0].width() - title.width();
                first.spans[0] = Span::raw(" ".repeat(pad));
                first.spans.insert(0, title);
            }
            Some(_) => {}
            None => lines.push(Line::from(title)),
        }
    }
    lines
}

/// Draws `chart` in `area` inside `block`, with `legend` (the named series and their
/// styles) and the y axis's title on rows of their own above the graph and the x axis's
/// title in the block's bottom border, so that no data is ever drawn under them (ratatui's
/// own legend and axis titles sit inside the graph, where a trained curve runs through
/// them). The legend is left out when the graph would keep fewer than
/// four rows.
pub(super) fn draw_chart(
    chart: Chart<'_>,
    block: Block<'_>,
    legend: &[(String, Style)],
    titles: (Option<&str>, Option<&str>),
    theme: Theme,
    area: Rect,
    buf: &mut Buffer,
) {
    let (x_title, y_title) = titles;
    let block = match x_title {
        Some(title) => {
            block.title_bottom(Line::styled(format!(" {title} "), theme.dim()).right_aligned())
        }
        None => block,
    };
    let inner = block.inner(area);
    block.render(area, buf);
    let y_title = y_title.map(|t| Span::styled(t.to_string(), theme.dim()));
    let rows = legend_rows(legend, y_title, usize::from(inner.width), theme);
    let height = u16::try_from(rows.len()).unwrap_or(u16::MAX);
    let chart_area = if inner.height >= height + 4 {
        Paragraph::new(rows).render(Rect { height, ..inner }, buf);
        Rect {
            y: inner.y + height,
            height: inner.height - height,
            ..inner
        }
    } else {
        inner
    };
    chart.legend_position(None).render(chart_area, buf);
}

/// The moving average's marker: heavier than the returns' dots, so that the curve to read
/// stands out of them (half blocks over Braille dots; full blocks over the `•` of
/// `PPO_TUTOR_ASCII`).
fn average_marker() -> Marker {
    match super::marker() {
        Marker::Braille => Marker::HalfBlock,
        _ => Marker::Block,
    }
}

/// `(episode, value)` pairs for a chart.
pub(super) fn points(values: &[f64]) -> Vec<(f64, f64)> {
    values
        .iter()
        .enumerate()
        .map(|(i, &v)| (i as f64, v))
        .collect()
}

impl Widget for ReturnPlot<'_> {
    fn render(self, area: Rect, buf: &mut Buffer) {
        let raw = points(self.returns);
        let avg = points(self.average);
        let prev = self.previous.map(|(label, v)| (label, points(v)));
        let episodes = self
            .returns
            .len()
            .max(self.previous.map_or(0, |(_, v)| v.len()))
            .max(10) as f64;
        let theme = self.theme;
        let mut legend: Vec<(String, Style)> = Vec::new();
        let mut datasets = Vec::new();
        if let Some((label, p)) = &prev {
            legend.push((label.to_string(), theme.previous()));
            datasets.push(
                Dataset::default()
                    .marker(Marker::Dot)
                    .graph_type(GraphType::Line)
                    .style(self.theme.previous())
                    .data(p),
            );
        }
        legend.push((t("returns", "回报").to_string(), theme.curve()));
        datasets.push(
            Dataset::default()
                .marker(super::marker())
                .graph_type(GraphType::Scatter)
                .style(self.theme.curve())
                .data(&raw),
        );
        if !avg.is_empty() {
            legend.push((
                crate::tr!("moving average ({})", "移动平均（{}）", self.window),
                theme.average(),
            ));
            datasets.push(
                Dataset::default()
                    .marker(average_marker())
                    .graph_type(GraphType::Line)
                    .style(self.theme.average())
                    .data(&avg),
            );
        }
        let y_bottom = self.min_return;
        let y_top = if y_bottom < 0.0 {
            self.max_return
        } else {
            self.max_return.max(10.0)
        };
        let chart = Chart::new(datasets)
            .x_axis(
                Axis::default()
                    .bounds([0.0, episodes])
                    .labels([Span::raw("0"), Span::raw(format!("{episodes:.0}"))])
                    .style(self.theme.dim()),
            )
            .y_axis(
                Axis::default()
                    .bounds([y_bottom, y_top])
                    .labels([
                        Span::raw(format!("{y_bottom:.0}")),
                        Span::raw(format!("{:.0}", (y_bottom + y_top) / 2.0)),
                        Span::raw(format!("{y_top:.0}")),
                    ])
                    .style(self.theme.dim()),
            );
        draw_chart(
            chart,
            self.block,
            &legend,
            (Some(t("Episodes", "回合")), Some(t("Returns", "回报"))),
            self.theme,
            area,
            buf,
        );
    }
}

#[cfg(test)]
mod tests {
    use super::ReturnPlot;
    use crate::tui::theme::Theme;
    use ratatui::buffer::Buffer;
    use ratatui::layout::Rect;
    use ratatui::widgets::{Block, Widget};

    fn is_data(c: char) -> bool {
        ('\u{2800}'..='\u{28FF}').contains(&c) || ['•', '▀', '▄', '█'].contains(&c)
    }

    /// The plot of `returns` and `average` (and `previous`) drawn `width`×`height`, as
    /// rows of text, on the CartPole scale (0 to 500, the seed's window of 9).
    fn drawn(
        returns: &[f64],
        average: &[f64],
        previous: Option<(&str, &[f64])>,
        (width, height): (u16, u16),
    ) -> Vec<String> {
        let area = Rect::new(0, 0, width, height);
        let mut buf = Buffer::empty(area);
        ReturnPlot {
            returns,
            average,
            window: 9,
            previous,
            max_return: 500.0,
            min_return: 0.0,
            block: Block::bordered(),
            theme: Theme { color: false },
        }
        .render(area, &mut buf);
        (0..height)
            .map(|y| (0..width).map(|x| buf[(x, y)].symbol()).collect())
            .collect()
    }

    /// A trained curve runs along the top right, where ratatui drew its
    /// legend; the legend now has rows of its own, and its names stay whole.
    #[test]
    fn the_legend_stays_whole_over_a_trained_curve() {
        // A climb, then returns between 420 and 500 with their average near 470.
        let returns: Vec<f64> = (0..200_u32)
            .map(|i| {
                if i < 60 {
                    f64::from(10 + 8 * i)
                } else {
                    f64::from(420 + (i % 6) * 16)
                }
            })
            .collect();
        let average: Vec<f64> = returns.iter().map(|r| r.min(470.0)).collect();
        let previous: Vec<f64> = returns.iter().map(|r| r * 0.9).collect();
        for (width, height) in [(44, 14), (72, 24)] {
            let rows = drawn(
                &returns,
                &average,
                Some(("ε = 0.1", &previous)),
                (width, height),
            );
            let screen = rows.join("\n");
            let names = ["ε = 0.1", "returns", "moving average (9)"];
            for name in names {
                let row = rows
                    .iter()
                    .position(|r| r.contains(name))
                    .unwrap_or_else(|| panic!("{name} missing:\n{screen}"));
                assert!(
                    !rows[row].chars().any(is_data),
                    "data on the legend's row:\n{screen}"
                );
                // The curve runs just below it, where ratatui's legend box was.
                let below = &rows[row + 1];
                assert!(
                    below.chars().any(is_data),
                    "no data below {name}:\n{screen}"
                );
            }
            assert!(screen.contains("Episodes"), "{screen}");
            // The axis title shares the legend's row where there is room.
            assert_eq!(screen.contains("Returns"), width > 60, "{screen}");
        }
    }

    /// The moving average is drawn in half blocks, heavier than the returns' Braille dots.
    #[test]
    fn the_average_is_heavier_than_the_returns() {
        let returns: Vec<f64> = (0..100_u32).map(|i| f64::from(i % 7) * 60.0).collect();
        let average = vec![200.0; returns.len()];
        let width = 60;
        let rows = drawn(&returns, &average, None, (width, 16));
        let screen = rows.join("\n");
        // The flat average at 200 is one row of half blocks across the graph.
        let blocks = |r: &String| r.chars().filter(|c| ['▀', '▄', '█'].contains(c)).count();
        let row = rows.iter().max_by_key(|r| blocks(r)).map_or(0, blocks);
        assert!(row > usize::from(width) / 2, "{screen}");
        assert!(
            screen
                .chars()
                .any(|c| ('\u{2801}'..='\u{28FF}').contains(&c)),
            "{screen}"
        );
    }
}
