//! The pictures a notebook shows as inline SVG: the cart and pole, the pendulum, the
//! Gaussian policy's map and the clip chart, drawn as the terminal app draws them.

use std::fmt::Write as _;

use super::{Svg, escape};
use crate::ppo::EpochTrace;

/// Where the pole's tip is drawn in [`cartpole_svg`]'s 600x400 picture.
pub(super) fn pole_tip(state: &[f64; 4]) -> (f64, f64) {
    let scale = 600.0 / (2.0 * crate::env::cartpole::X_THRESHOLD);
    let pole_len = scale * 2.0 * crate::env::cartpole::LENGTH;
    let cart_x = state[0] * scale + 300.0;
    (
        cart_x + pole_len * state[2].sin(),
        300.0 - 30.0 / 4.0 - pole_len * state[2].cos(),
    )
}

/// The cart and pole in state `[x, x_dot, theta, theta_dot]`, as Gymnasium renders it
/// (600x400, track at the bottom third, x in `[-2.4, 2.4]`).
#[must_use]
pub fn cartpole_svg(state: &[f64; 4]) -> Svg {
    let (width, height) = (600.0, 400.0);
    let scale = width / (2.0 * crate::env::cartpole::X_THRESHOLD);
    let track_y = 300.0;
    let cart_x = state[0] * scale + width / 2.0;
    let (cart_w, cart_h) = (50.0, 30.0);
    let theta = state[2];
    let (tip_x, tip_y) = pole_tip(state);
    let mut svg = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{width}\" height=\"{height}\" viewBox=\"0 0 {width} {height}\">\n"
    );
    let _ = writeln!(
        svg,
        "<rect width=\"{width}\" height=\"{height}\" fill=\"white\"/>\n\
         <line x1=\"0\" y1=\"{track_y}\" x2=\"{width}\" y2=\"{track_y}\" stroke=\"black\"/>\n\
         <rect x=\"{:.2}\" y=\"{:.2}\" width=\"{cart_w}\" height=\"{cart_h}\" fill=\"black\"/>\n\
         <line x1=\"{cart_x:.2}\" y1=\"{:.2}\" x2=\"{tip_x:.2}\" y2=\"{tip_y:.2}\" stroke=\"#ca9865\" stroke-width=\"10\" stroke-linecap=\"round\"/>\n\
         <circle cx=\"{cart_x:.2}\" cy=\"{:.2}\" r=\"5\" fill=\"#8184cb\"/>",
        cart_x - cart_w / 2.0,
        track_y - cart_h * 0.75,
        track_y - cart_h / 4.0,
        track_y - cart_h / 4.0,
    );
    let _ = writeln!(
        svg,
        "<text x=\"10\" y=\"24\" font-family=\"monospace\" font-size=\"14\">x = {:.4}  θ = {:.4} rad ({:.2}°)</text>\n</svg>",
        state[0],
        theta,
        theta.to_degrees()
    );
    Svg(svg)
}

/// The pendulum as Gymnasium draws Pendulum-v1 (400x400, the pivot at the centre, the rod
/// at angle `theta` from straight up, counter-clockwise positive), with the torque `torque`
/// written below it and drawn as an arc around the pivot (counter-clockwise for u > 0).
#[must_use]
pub fn pendulum_svg(theta: f64, torque: f64) -> Svg {
    let (size, centre, length) = (400.0, 200.0, 140.0);
    let tip_x = centre - length * theta.sin();
    let tip_y = centre - length * theta.cos();
    let u = torque.clamp(
        -crate::env::pendulum::MAX_TORQUE,
        crate::env::pendulum::MAX_TORQUE,
    );
    let sweep = u / crate::env::pendulum::MAX_TORQUE * 1.5 * std::f64::consts::PI;
    let radius = 40.0;
    let mut arc = String::new();
    let n = (sweep.abs() * 12.0).ceil() as usize;
    for k in 0..=n {
        let phi = std::f64::consts::FRAC_PI_2 + sweep * k as f64 / n.max(1) as f64;
        let _ = write!(
            arc,
            "{}{:.2},{:.2}",
            if k == 0 { "" } else { " " },
            centre + radius * phi.cos(),
            centre - radius * phi.sin()
        );
    }
    let mut svg = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{size}\" height=\"{size}\" viewBox=\"0 0 {size} {size}\">\n\
         <rect width=\"{size}\" height=\"{size}\" fill=\"white\"/>\n\
         <line x1=\"{centre}\" y1=\"{centre}\" x2=\"{tip_x:.2}\" y2=\"{tip_y:.2}\" stroke=\"#cc4c4c\" stroke-width=\"16\" stroke-linecap=\"round\"/>\n\
         <circle cx=\"{centre}\" cy=\"{centre}\" r=\"6\" fill=\"black\"/>\n"
    );
    if n > 0 {
        let _ = writeln!(
            svg,
            "<polyline points=\"{arc}\" fill=\"none\" stroke=\"#e0a000\" stroke-width=\"4\"/>"
        );
    }
    let caption = crate::tr!(
        "θ = {theta:.4} rad ({:.1}° from upright)  torque = {torque:.4}",
        "θ = {theta:.4} rad（偏离竖直向上 {:.1}°）  力矩 = {torque:.4}",
        crate::env::pendulum::angle_normalize(theta).to_degrees()
    );
    let _ = writeln!(
        svg,
        "<text x=\"10\" y=\"24\" font-family=\"monospace\" font-size=\"14\">{caption}</text>\n</svg>"
    );
    Svg(svg)
}

/// `μ(θ, θ̇)` of a [`PolicyMap`](crate::lesson::PolicyMap) as a picture: one square per grid
/// point, red for a positive torque (counter-clockwise), blue for a negative one, the
/// stronger the colour the nearer |μ| is to 2; θ from −π (left) to π (right), θ̇ from 8
/// (top) to −8 (bottom), the value written in each square.
#[must_use]
pub fn policy_map_svg(map: &crate::lesson::PolicyMap) -> Svg {
    let (rows, cols) = (map.theta_dots.len(), map.thetas.len());
    let (cell, left, top) = (52.0, 70.0, 40.0);
    let width = left + cell * cols as f64 + 20.0;
    let height = top + cell * rows as f64 + 50.0;
    let heading = crate::i18n::t(
        "μ(θ, θ̇): red pushes counter-clockwise, blue clockwise",
        "μ(θ, θ̇)：红色向逆时针推，蓝色向顺时针推",
    );
    let mut svg = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{width}\" height=\"{height}\" viewBox=\"0 0 {width} {height}\" font-family=\"monospace\" font-size=\"12\">\n\
         <rect width=\"{width}\" height=\"{height}\" fill=\"white\"/>\n\
         <text x=\"{left}\" y=\"24\" font-size=\"14\">{heading}</text>\n"
    );
    for (i, dot) in map.theta_dots.iter().enumerate() {
        let y = top + cell * i as f64;
        let _ = writeln!(
            svg,
            "<text x=\"8\" y=\"{:.1}\">θ̇ {dot:+.0}</text>",
            y + cell / 2.0 + 4.0
        );
        for (j, _) in map.thetas.iter().enumerate() {
            let mu = f64::from(map.mu.get(i * cols + j).copied().unwrap_or(0.0));
            let strength = (mu.abs() / 2.0).clamp(0.0, 1.0);
            let fade = (255.0 * (1.0 - strength)).round();
            let colour = if mu >= 0.0 {
                format!("rgb(255,{fade},{fade})")
            } else {
                format!("rgb({fade},{fade},255)")
            };
            let x = left + cell * j as f64;
            let _ = writeln!(
                svg,
                "<rect x=\"{x:.1}\" y=\"{y:.1}\" width=\"{cell}\" height=\"{cell}\" fill=\"{colour}\" stroke=\"#888\"/>\n\
                 <text x=\"{:.1}\" y=\"{:.1}\" text-anchor=\"middle\">{mu:+.2}</text>",
                x + cell / 2.0,
                y + cell / 2.0 + 4.0
            );
        }
    }
    let axis_y = top + cell * rows as f64 + 20.0;
    for (j, theta) in map.thetas.iter().enumerate() {
        let _ = writeln!(
            svg,
            "<text x=\"{:.1}\" y=\"{axis_y:.1}\" text-anchor=\"middle\">{:+.0}°</text>",
            left + cell * j as f64 + cell / 2.0,
            f64::from(*theta).to_degrees()
        );
    }
    let axis = crate::i18n::t(
        "θ from −180° to 180° (0° upright)",
        "θ 从 −180° 到 180°（0° 为竖直向上）",
    );
    let _ = writeln!(
        svg,
        "<text x=\"{left}\" y=\"{:.1}\">{axis}</text>\n</svg>",
        axis_y + 20.0
    );
    Svg(svg)
}

/// The clip chart of `epoch` (the terminal app's, drawn with plotters): `L^CLIP(r)` for a
/// unit advantage of each sign, the band `[1 − ε, 1 + ε]`, and each row of the epoch at
/// `(ratio, min(surr1, surr2) / |A|)`. A drawing failure gives a picture that says so.
#[must_use]
pub fn clip_chart_svg(eps: f64, epoch: Option<&EpochTrace>, advantage: &[f32]) -> Svg {
    let rows: Vec<(f64, f64)> = epoch.map_or_else(Vec::new, |e| {
        e.ratio
            .iter()
            .zip(advantage)
            .map(|(&r, &a)| (f64::from(r), f64::from(a)))
            .collect()
    });
    Svg(crate::plot::clip_chart_svg(eps, &rows).unwrap_or_else(|e| {
        format!(
            "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"640\" height=\"40\"><text x=\"10\" y=\"24\">{}</text></svg>",
            escape(&e.to_string())
        )
    }))
}
