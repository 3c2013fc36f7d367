//! The pendulum on a `Canvas`, from an angle `θ` and the torque applied.
//!
//! Drawn as Gymnasium renders Pendulum-v1: the pivot at the centre, the rod of length
//! `l = 1` at angle `θ` from straight up, counter-clockwise positive (its tip at
//! `(−sin θ, cos θ)`), and the torque `u` as an arc around the pivot whose length grows with
//! `|u|` and which turns the way the torque pushes (counter-clockwise for `u > 0`).
//!
//! ```
//! use ratatui::buffer::Buffer;
//! use ratatui::layout::Rect;
//! use ratatui::widgets::{Block, Widget};
//! use ppo_tutor::tui::widgets::pendulum::PendulumView;
//!
//! let area = Rect::new(0, 0, 24, 12);
//! let mut buf = Buffer::empty(area);
//! PendulumView { theta: 0.0, torque: 0.0, block: Block::new(), color: false }.render(area, &mut buf);
//! let top: String = (0..24).map(|x| buf[(x, 1)].symbol().to_string()).collect();
//! assert!(top.trim() != "", "upright: the rod reaches the top rows");
//! ```

use std::f64::consts::FRAC_PI_2;

use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::Color;
use ratatui::widgets::canvas::{Canvas, Circle, Line, Points};
use ratatui::widgets::{Block, Widget};

use crate::env::pendulum::{LENGTH, MAX_TORQUE};

/// How far the canvas reaches from the pivot, in rod lengths.
const REACH: f64 = 1.25;
/// Radius of the torque arc, in rod lengths.
const ARC_RADIUS: f64 = 0.45;
/// The arc's sweep at the largest torque, in radians.
const ARC_SWEEP: f64 = 1.5 * std::f64::consts::PI;

/// The tip of a rod of length `l` at angle `theta` (0 up, counter-clockwise positive), as
/// Gymnasium draws it.
#[must_use]
pub fn rod_tip(theta: f64, l: f64) -> (f64, f64) {
    (-l * theta.sin(), l * theta.cos())
}

/// Points along the torque arc for torque `u`: from straight up, counter-clockwise for
/// `u > 0`, clockwise for `u < 0`, sweeping `|u| / 2` of `ARC_SWEEP` (none for `u = 0`).
#[must_use]
pub fn torque_arc(u: f64) -> Vec<(f64, f64)> {
    let sweep = (u / MAX_TORQUE).clamp(-1.0, 1.0) * ARC_SWEEP;
    let n = (sweep.abs() * 24.0).ceil() as usize;
    if n == 0 {
        return Vec::new();
    }
    (0..=n)
        .map(|k| {
            let phi = FRAC_PI_2 + sweep * k as f64 / n as f64;
            (ARC_RADIUS * phi.cos(), ARC_RADIUS * phi.sin())
        })
        .collect()
}

/// Draws one frame of the pendulum.
pub struct PendulumView<'a> {
    /// The angle `θ` (rad), 0 upright; any value (it is not wrapped).
    pub theta: f64,
    /// The torque applied at this step (N·m); drawn clipped to `[−2, 2]` as the env applies it.
    pub torque: f64,
    /// The surrounding block (title, border).
    pub block: Block<'a>,
    /// Whether to use colours.
    pub color: bool,
}

impl Widget for PendulumView<'_> {
    fn render(self, area: Rect, buf: &mut Buffer) {
        let (rod, pivot, arc) = if self.color {
            (Color::Red, Color::White, Color::Yellow)
        } else {
            (Color::Reset, Color::Reset, Color::Reset)
        };
        let (tip_x, tip_y) = rod_tip(self.theta, LENGTH);
        let arc_points = torque_arc(self.torque);
        Canvas::default()
            .block(self.block)
            .marker(super::marker())
            .x_bounds([-REACH, REACH])
            .y_bounds([-REACH, REACH])
            .paint(move |ctx| {
                ctx.draw(&Line::new(0.0, 0.0, tip_x, tip_y, rod));
                ctx.draw(&Circle {
                    x: tip_x,
                    y: tip_y,
                    radius: 0.06,
                    color: rod,
                });
                ctx.draw(&Points {
                    coords: &arc_points,
                    color: arc,
                });
                ctx.draw(&Circle {
                    x: 0.0,
                    y: 0.0,
                    radius: 0.05,
                    color: pivot,
                });
            })
            .render(area, buf);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The rows and columns of the area that hold a drawn dot.
    fn drawn(theta: f64, torque: f64) -> Vec<(u16, u16)> {
        let area = Rect::new(0, 0, 40, 20);
        let mut buf = Buffer::empty(area);
        PendulumView {
            theta,
            torque,
            block: Block::new(),
            color: false,
        }
        .render(area, &mut buf);
        let mut cells = Vec::new();
        for y in 0..area.height {
            for x in 0..area.width {
                if buf[(x, y)].symbol().trim() != "" {
                    cells.push((x, y));
                }
            }
        }
        cells
    }

    #[test]
    fn the_rod_points_up_down_and_sideways_as_gymnasium_draws_it() {
        let up = drawn(0.0, 0.0);
        assert!(
            up.iter().any(|&(_, y)| y <= 2),
            "upright reaches the top: {up:?}"
        );
        assert!(
            up.iter().all(|&(_, y)| y <= 11),
            "nothing below the pivot: {up:?}"
        );
        let down = drawn(std::f64::consts::PI, 0.0);
        assert!(
            down.iter().any(|&(_, y)| y >= 17),
            "hanging reaches the bottom"
        );
        assert!(
            down.iter().all(|&(_, y)| y >= 8),
            "nothing above the pivot: {down:?}"
        );
        // θ = π/2 is counter-clockwise from up: the rod lies to the left of the pivot.
        let left = drawn(FRAC_PI_2, 0.0);
        assert!(left.iter().any(|&(x, _)| x <= 4), "{left:?}");
        assert!(left.iter().all(|&(x, _)| x <= 21), "{left:?}");
    }

    #[test]
    fn the_torque_arc_turns_with_the_torque() {
        assert!(torque_arc(0.0).is_empty());
        let ccw = torque_arc(1.0);
        let cw = torque_arc(-1.0);
        // Both start straight up; a positive torque turns left (x < 0), a negative right.
        assert!((ccw[0].0).abs() < 1e-12 && (ccw[0].1 - ARC_RADIUS).abs() < 1e-12);
        assert!(ccw[1].0 < 0.0 && cw[1].0 > 0.0);
        // The sweep grows with |u| and stops at the env's clip.
        let end = |u: f64| torque_arc(u).last().map_or(0.0, |&(x, y)| y.atan2(x));
        assert!((end(0.5) - (FRAC_PI_2 + 0.375 * std::f64::consts::PI)).abs() < 1e-9);
        assert_eq!(torque_arc(5.0), torque_arc(2.0));
        assert!(drawn(0.0, 2.0).len() > drawn(0.0, 0.0).len());
    }
}
