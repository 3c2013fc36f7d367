//! The clip chart: `L^CLIP` against the ratio for `A > 0` and `A < 0`, with the batch on it.
//!
//! For a unit advantage, `L(r) = min(r·A, clip(r, 1−ε, 1+ε)·A)`: flat above `1+ε` when
//! `A > 0` (no reward for pushing further) and flat below `1−ε` when `A < 0`. Each
//! transition of the latest batch is drawn at `(ratio, min(surr1, surr2) / |A|)`.

use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::symbols::Marker;
use ratatui::text::Span;
use ratatui::widgets::{Axis, Block, Chart, Dataset, GraphType, Widget};

use crate::i18n::t;
use crate::ppo::EpochTrace;
use crate::tui::theme::Theme;

pub use crate::plot::l_clip;

/// The chart widget.
pub struct ClipChart<'a> {
    /// The clip range ε.
    pub eps: f64,
    /// The latest epoch of the latest update, if any.
    pub epoch: Option<&'a EpochTrace>,
    /// The advantages of that update.
    pub advantage: &'a [f32],
    /// The surrounding block.
    pub block: Block<'a>,
    /// Styles.
    pub theme: Theme,
}

impl Widget for ClipChart<'_> {
    fn render(self, area: Rect, buf: &mut Buffer) {
        let eps = self.eps;
        let curve = |a: f64| -> Vec<(f64, f64)> {
            (0..=80)
                .map(|i| {
                    let r = f64::from(i) / 40.0;
                    (r, l_clip(r, a, eps))
                })
                .collect()
        };
        let pos = curve(1.0);
        let neg = curve(-1.0);
        let band = [(1.0 - eps, -2.0), (1.0 - eps, 2.0)];
        let band_hi = [(1.0 + eps, -2.0), (1.0 + eps, 2.0)];
        let (mut plus, mut minus) = (Vec::new(), Vec::new());
        if let Some(e) = self.epoch {
            for (i, &r) in e.ratio.iter().enumerate() {
                let a = f64::from(self.advantage.get(i).copied().unwrap_or(0.0));
                if a == 0.0 {
                    continue;
                }
                let p = (
                    f64::from(r).clamp(0.0, 2.0),
                    l_clip(f64::from(r), a.signum(), eps),
                );
                if a > 0.0 { plus.push(p) } else { minus.push(p) }
            }
        }
        let datasets = vec![
            Dataset::default()
                .name("A > 0")
                .marker(super::marker())
                .graph_type(GraphType::Line)
                .style(self.theme.positive())
                .data(&pos),
            Dataset::default()
                .name("A < 0")
                .marker(super::marker())
                .graph_type(GraphType::Line)
                .style(self.theme.negative())
                .data(&neg),
            Dataset::default()
                .name(format!("1 − ε = {:.2}", 1.0 - eps))
                .marker(Marker::Dot)
                .graph_type(GraphType::Line)
                .style(self.theme.dim())
                .data(&band),
            Dataset::default()
                .name(format!("1 + ε = {:.2}", 1.0 + eps))
                .marker(Marker::Dot)
                .graph_type(GraphType::Line)
                .style(self.theme.dim())
                .data(&band_hi),
            Dataset::default()
                .name(t("batch, A > 0", "批次，A > 0"))
                .marker(Marker::Block)
                .graph_type(GraphType::Scatter)
                .style(self.theme.positive())
                .data(&plus),
            Dataset::default()
                .name(t("batch, A < 0", "批次，A < 0"))
                .marker(Marker::Block)
                .graph_type(GraphType::Scatter)
                .style(self.theme.negative())
                .data(&minus),
        ];
        Chart::new(datasets)
            .block(self.block)
            .x_axis(
                Axis::default()
                    .title(t("ratio r", "比率 r"))
                    .bounds([0.0, 2.0])
                    .labels([Span::raw("0"), Span::raw("1"), Span::raw("2")])
                    .style(self.theme.dim()),
            )
            .y_axis(
                Axis::default()
                    .title("L/|A|")
                    .bounds([-2.0, 2.0])
                    .labels([Span::raw("-2"), Span::raw("0"), Span::raw("2")])
                    .style(self.theme.dim()),
            )
            .render(area, buf);
    }
}

#[cfg(test)]
mod tests {
    use super::l_clip;

    #[test]
    fn clip_is_flat_where_the_seed_says() {
        // A > 0: no gain beyond 1 + ε.
        assert!((l_clip(1.5, 1.0, 0.2) - 1.2).abs() < 1e-12);
        assert!((l_clip(0.5, 1.0, 0.2) - 0.5).abs() < 1e-12);
        // A < 0: no gain below 1 − ε, full penalty above.
        assert!((l_clip(0.5, -1.0, 0.2) + 0.8).abs() < 1e-12);
        assert!((l_clip(1.5, -1.0, 0.2) + 1.5).abs() < 1e-12);
    }
}
