//! The return curve and its moving average as a ratatui `Chart`.

use ratatui::buffer::Buffer;
use ratatui::layout::{Constraint, Rect};
use ratatui::symbols::Marker;
use ratatui::text::Span;
use ratatui::widgets::{Axis, Block, Chart, Dataset, GraphType, Widget};

use crate::i18n::t;
use crate::tui::theme::Theme;

/// The return plot: this run's returns and moving average, and optionally a previous run.
pub struct ReturnPlot<'a> {
    /// This run's returns.
    pub returns: &'a [f64],
    /// Their moving average (may be empty while fewer than 8 episodes are done).
    pub average: &'a [f64],
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
        let mut datasets = Vec::new();
        if let Some((label, p)) = &prev {
            datasets.push(
                Dataset::default()
                    .name(label.to_string())
                    .marker(Marker::Dot)
                    .graph_type(GraphType::Line)
                    .style(self.theme.previous())
                    .data(p),
            );
        }
        datasets.push(
            Dataset::default()
                .name(t("returns", "回报"))
                .marker(super::marker())
                .graph_type(GraphType::Scatter)
                .style(self.theme.curve())
                .data(&raw),
        );
        if !avg.is_empty() {
            datasets.push(
                Dataset::default()
                    .name(t("moving average (9)", "移动平均 (9)"))
                    .marker(super::marker())
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
        Chart::new(datasets)
            .block(self.block)
            // Keep the legend (it names the overlaid previous run) unless it would cover half the plot.
            .hidden_legend_constraints((Constraint::Ratio(1, 2), Constraint::Ratio(1, 2)))
            .x_axis(
                Axis::default()
                    .title(t("Episodes", "回合"))
                    .bounds([0.0, episodes])
                    .labels([Span::raw("0"), Span::raw(format!("{episodes:.0}"))])
                    .style(self.theme.dim()),
            )
            .y_axis(
                Axis::default()
                    .title(t("Returns", "回报"))
                    .bounds([y_bottom, y_top])
                    .labels([
                        Span::raw(format!("{y_bottom:.0}")),
                        Span::raw(format!("{:.0}", (y_bottom + y_top) / 2.0)),
                        Span::raw(format!("{y_top:.0}")),
                    ])
                    .style(self.theme.dim()),
            )
            .render(area, buf);
    }
}
