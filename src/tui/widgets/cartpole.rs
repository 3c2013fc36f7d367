//! The cart and pole on a `Canvas`, from an observation `(x, ẋ, θ, θ̇)`.

use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::Color;
use ratatui::widgets::canvas::{Canvas, Line, Rectangle};
use ratatui::widgets::{Block, Widget};

use crate::env::cartpole::{LENGTH, X_THRESHOLD};

/// Draws one frame of the cart and pole.
pub struct CartPoleView<'a> {
    /// The observation to draw.
    pub obs: [f32; 4],
    /// The surrounding block (title, border).
    pub block: Block<'a>,
    /// Whether to use colours.
    pub color: bool,
}

impl Widget for CartPoleView<'_> {
    fn render(self, area: Rect, buf: &mut Buffer) {
        let [x, _, theta, _] = self.obs.map(f64::from);
        let (cart, pole, track) = if self.color {
            (Color::Cyan, Color::Yellow, Color::DarkGray)
        } else {
            (Color::Reset, Color::Reset, Color::Reset)
        };
        Canvas::default()
            .block(self.block)
            .marker(super::marker())
            .x_bounds([-X_THRESHOLD * 1.1, X_THRESHOLD * 1.1])
            .y_bounds([-0.3, 1.4])
            .paint(move |ctx| {
                ctx.draw(&Line::new(-X_THRESHOLD, 0.0, X_THRESHOLD, 0.0, track));
                for edge in [-X_THRESHOLD, X_THRESHOLD] {
                    ctx.draw(&Line::new(edge, -0.2, edge, 0.2, track));
                }
                ctx.draw(&Rectangle {
                    x: x - 0.25,
                    y: 0.0,
                    width: 0.5,
                    height: 0.2,
                    color: cart,
                });
                let top = 0.2;
                let len = 2.0 * LENGTH;
                ctx.draw(&Line::new(
                    x,
                    top,
                    x + len * theta.sin(),
                    top + len * theta.cos(),
                    pole,
                ));
            })
            .render(area, buf);
    }
}
