//! Rich output for the Jupyter notebooks (`notebooks/`, evcxr Rust kernel).
//!
//! evcxr shows the last expression of a cell by calling its `evcxr_display` method when it
//! has one: the method prints `EVCXR_BEGIN_CONTENT <mime>` ... `EVCXR_END_CONTENT` blocks on
//! stdout, at most one per mime type. This module gives the library's types that method
//! (live tensors as HTML tables, grading reports, figures as inline SVG) and the figures
//! themselves, so the notebooks use the same values and pictures as the terminal app.
//!
//! Everything here is ordinary library code: outside a notebook, [`Html::as_str`],
//! [`Svg::as_str`] and the `*_html` functions return the markup.
//!
//! ```
//! use ppo_tutor::notebook::cartpole_svg;
//!
//! let picture = cartpole_svg(&[0.1, 0.0, 0.05, 0.0]);
//! assert!(picture.as_str().starts_with("<svg"));
//! ```
//!
//! The notebooks themselves are generated: [`build`] makes a lesson's cells from its
//! `lesson.md` and recipe, [`ipynb`] writes them as a notebook file, and `kernel` (feature
//! `notebook-runner`) executes them on evcxr (`ppo-tutor dev notebooks`,
//! `tests/notebooks.rs`).

#[cfg(feature = "app")]
pub mod build;
#[cfg(feature = "app")]
pub mod check;
#[cfg(feature = "app")]
pub mod ipynb;
#[cfg(feature = "notebook-runner")]
pub mod kernel;
#[cfg(feature = "app")]
pub mod native;

use std::fmt::Write as _;

#[cfg(feature = "exercises")]
use crate::grade::{CheckStatus, Report};
use crate::lesson::{Mark, RunConfig, Session, Snapshot, TensorView};
use crate::plot::{PlotError, return_plot_svg};
use crate::ppo::lab::{Experiment, LabResult};
use crate::ppo::{EpochTrace, PpoConfig};

/// Rows of a tensor shown before the table is cut (the rest is summarised).
pub const MAX_ROWS: usize = 12;

/// One evcxr rich-output block.
fn block(mime: &str, content: &str) -> String {
    // A line equal to the end marker would end the block early: indent it.
    let body = content.replace("\nEVCXR_END_CONTENT", "\n EVCXR_END_CONTENT");
    format!("EVCXR_BEGIN_CONTENT {mime}\n{body}\nEVCXR_END_CONTENT")
}

/// Prints one evcxr rich-output block.
fn emit(mime: &str, content: &str) {
    println!("{}", block(mime, content));
}

/// What a notebook cell shows for a value of the library: its rich outputs, as
/// `(mime type, content)` pairs in the order evcxr receives them. Each type's
/// `evcxr_display` prints exactly these; the default test tier reads them directly
/// (`tests/notebook_code.rs` runs every notebook's code without evcxr).
pub trait Rich {
    /// The outputs, at most one per mime type.
    fn rich(&self) -> Vec<(&'static str, String)>;
}

/// Prints a value's rich outputs as evcxr's blocks (what `evcxr_display` does).
fn emit_rich(value: &impl Rich) {
    for (mime, content) in value.rich() {
        emit(mime, &content);
    }
}

/// An HTML fragment with a plain-text fallback; a notebook shows the HTML.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Html {
    html: String,
    text: String,
}

impl Html {
    /// The markup.
    #[must_use]
    pub fn as_str(&self) -> &str {
        &self.html
    }

    /// The plain-text version (what a terminal or a text-only viewer shows).
    #[must_use]
    pub fn text(&self) -> &str {
        &self.text
    }

    /// evcxr's display hook: the HTML and its text fallback.
    pub fn evcxr_display(&self) {
        emit_rich(self);
    }
}

impl Rich for Html {
    fn rich(&self) -> Vec<(&'static str, String)> {
        vec![
            ("text/plain", self.text.clone()),
            ("text/html", self.html.clone()),
        ]
    }
}

/// An SVG picture; a notebook shows it inline.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Svg(String);

impl Svg {
    /// The SVG document.
    #[must_use]
    pub fn as_str(&self) -> &str {
        &self.0
    }

    /// evcxr's display hook.
    pub fn evcxr_display(&self) {
        emit_rich(self);
    }
}

impl Rich for Svg {
    fn rich(&self) -> Vec<(&'static str, String)> {
        vec![("image/svg+xml", self.0.clone())]
    }
}

fn escape(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

/// Background colour of a marked entry (the terminal app's colours, light).
fn mark_style(mark: Mark) -> &'static str {
    match mark {
        Mark::Plain => "",
        Mark::Clipped => " style=\"background:#ffd8a8\" title=\"clipped: outside 1 ± ε\"",
        Mark::Done => " style=\"background:#dee2e6\" title=\"done: V(s') is dropped\"",
        Mark::Positive => " style=\"background:#d3f9d8\" title=\"positive advantage\"",
        Mark::Negative => " style=\"background:#ffe3e3\" title=\"negative advantage\"",
    }
}

/// The rows shown: all when there are few, else the first and last few.
fn shown_rows(rows: usize) -> Vec<Option<usize>> {
    if rows <= MAX_ROWS {
        return (0..rows).map(Some).collect();
    }
    let head = MAX_ROWS - 3;
    let mut out: Vec<Option<usize>> = (0..head).map(Some).collect();
    out.push(None);
    out.extend((rows - 2..rows).map(Some));
    out
}

fn number(v: f64, dtype: &str) -> String {
    if dtype == "int64" || dtype == "bool" {
        format!("{v:.0}")
    } else {
        format!("{v:.6}")
    }
}

/// The caption of a tensor, one line: name, shape, dtype, statistics and marks.
fn caption(t: &TensorView) -> String {
    let (head, stats, marks) = caption_parts(t);
    format!("{head}{stats}{marks}")
}

/// The caption of a tensor in HTML: the name on the first line, the rest below, unwrapped.
fn caption_html(t: &TensorView) -> String {
    let (head, stats, marks) = caption_parts(t);
    let small = |text: &str| {
        let text = text.trim_start_matches(" · ");
        if text.is_empty() {
            String::new()
        } else {
            format!(
                "<br><small style=\"white-space:nowrap\">{}</small>",
                escape(text)
            )
        }
    };
    format!("<b>{}</b>{}{}", escape(&head), small(&stats), small(&marks))
}

fn caption_parts(t: &TensorView) -> (String, String, String) {
    let stats = t.stats().map_or(String::new(), |(lo, hi, mean)| {
        format!(" · min {lo:.6} · max {hi:.6} · mean {mean:.6}")
    });
    let mut marks = String::new();
    for (mark, what) in [
        (Mark::Clipped, "clipped"),
        (Mark::Done, "done"),
        (Mark::Positive, "positive"),
        (Mark::Negative, "negative"),
    ] {
        let n = t.count(mark);
        if n > 0 {
            let _ = write!(marks, " · {n} {what}");
        }
    }
    let head = format!("{} {}", t.name, t.shape_text().trim_end());
    (head, stats, marks)
}

/// One tensor as an HTML table (row index, values; marked entries coloured), and as text.
#[must_use]
pub fn tensor_html(t: &TensorView) -> Html {
    let cap = caption(t);
    let mut html = format!(
        "<table class=\"ppo-tensor\" style=\"font-family:monospace;font-size:12px\">\n<caption style=\"text-align:left\">{}</caption>\n",
        caption_html(t)
    );
    let mut text = format!("{cap}\n");
    if !t.labels.is_empty() {
        for label in &t.labels {
            let (k, v) = label.split_once('=').unwrap_or((label, ""));
            let _ = writeln!(
                html,
                "<tr><td>{}</td><td style=\"text-align:right\">{}</td></tr>",
                escape(k.trim()),
                escape(v.trim())
            );
            let _ = writeln!(text, "  {label}");
        }
        html.push_str("</table>");
        return Html { html, text };
    }
    let cols = t.cols();
    let rows = t.values.len().div_ceil(cols);
    for row in shown_rows(rows) {
        let Some(row) = row else {
            let _ = writeln!(
                html,
                "<tr><td>…</td><td colspan=\"{cols}\">{}</td></tr>",
                more_rows(rows - (MAX_ROWS - 1))
            );
            let _ = writeln!(text, "  ... {}", more_rows(rows - (MAX_ROWS - 1)));
            continue;
        };
        let _ = write!(html, "<tr><td style=\"color:#868e96\">{row}</td>");
        let mut line = format!("  [{row}]");
        for c in 0..cols {
            let i = row * cols + c;
            let (Some(&v), mark) = (t.values.get(i), t.marks.get(i).copied().unwrap_or_default())
            else {
                continue;
            };
            let _ = write!(
                html,
                "<td style=\"text-align:right\"{}>{}</td>",
                mark_style(mark),
                number(v, t.dtype)
            );
            let _ = write!(line, " {}", number(v, t.dtype));
        }
        html.push_str("</tr>\n");
        let _ = writeln!(text, "{line}");
    }
    html.push_str("</table>");
    Html { html, text }
}

impl TensorView {
    /// evcxr's display hook: the tensor as an HTML table.
    pub fn evcxr_display(&self) {
        emit_rich(self);
    }
}

impl Rich for TensorView {
    fn rich(&self) -> Vec<(&'static str, String)> {
        tensor_html(self).rich()
    }
}

impl Snapshot {
    /// The live values `names` side by side, as the terminal app shows them on a step;
    /// a name with nothing computed yet says so.
    #[must_use]
    pub fn show(&self, names: &[&str]) -> Html {
        let mut html = String::from(
            "<div style=\"display:flex;flex-wrap:wrap;gap:16px;align-items:flex-start\">\n",
        );
        let mut text = String::new();
        for name in names {
            let part = self.tensor(name).map_or_else(
                || {
                    let msg = crate::tr!(
                        "{name}: not available yet (train an episode first)",
                        "{name}：还没有数值（请先训练一个回合）"
                    );
                    Html {
                        html: format!("<p>{}</p>", escape(&msg)),
                        text: format!("{msg}\n"),
                    }
                },
                |t| tensor_html(&t),
            );
            let _ = writeln!(html, "<div>{}</div>", part.html);
            text.push_str(&part.text);
        }
        html.push_str("</div>");
        Html { html, text }
    }

    /// The return curve and its moving average, as the seed's figure.
    ///
    /// # Errors
    /// [`PlotError::Draw`] if plotters fails.
    pub fn return_plot(&self, title: &str) -> Result<Svg, PlotError> {
        return_plot_svg(title, &self.returns, &self.moving_average).map(Svg)
    }

    /// The cart and pole where the latest episode ended (a blank track before any episode).
    #[must_use]
    pub fn cartpole(&self) -> Svg {
        let last = self
            .trace
            .as_ref()
            .and_then(|t| t.next_states.last())
            .copied()
            .unwrap_or_default();
        cartpole_svg(&last.map(f64::from))
    }

    /// The pendulum at the latest episode's first state, with the torque drawn there (a
    /// hanging rod before any episode).
    #[must_use]
    pub fn pendulum(&self) -> Svg {
        let (theta, torque) = self
            .pendulum_frame(0)
            .unwrap_or((std::f64::consts::PI, 0.0));
        pendulum_svg(theta, torque)
    }

    /// The clip chart of the latest update's last epoch (see [`clip_chart_svg`]).
    #[must_use]
    pub fn clip_chart(&self) -> Svg {
        let trace = self.trace.as_ref();
        clip_chart_svg(
            f64::from(self.eps),
            trace.and_then(|t| t.epochs.last()),
            trace.map_or(&[][..], |t| &t.advantage),
        )
    }
}

/// Trains `episodes` episodes of the seed's PPO (or, given a
/// [`PpoContinuousConfig`](crate::ppo::PpoContinuousConfig), the book's `PPOContinuous` on
/// Pendulum) with `config` and `seed` in a live
/// [`Session`], and returns what the terminal app would show after them: the latest batch
/// and every intermediate of its update, the probabilities, the weights, the return curve
/// and its moving average.
///
/// # Errors
/// Invalid settings, or a diverged run.
pub fn snapshot(
    config: impl Into<RunConfig>,
    seed: u64,
    episodes: usize,
) -> anyhow::Result<Snapshot> {
    hint_candle_threads();
    Ok(Session::run(config, seed, episodes)?)
}

/// Runs the clip-lab experiment called `name` (`eps`, `epochs`, `actor-lr`, `target-kl`,
/// `reinforce`: see [`crate::ppo::lab::Experiment`]) with the seed's settings, `episodes`
/// per run, once per seed of `seeds`, on every core: what `ppo-tutor lab NAME` and the
/// terminal app's `x` run. Shown in a notebook as its table and its figure.
///
/// # Errors
/// An unknown name, or a run that stopped.
pub fn lab(name: &str, seeds: &[u64], episodes: usize) -> anyhow::Result<LabResult> {
    hint_candle_threads();
    let experiment = Experiment::from_name(name).ok_or_else(|| {
        let names: Vec<&str> = Experiment::ALL.iter().map(|e| e.name()).collect();
        anyhow::anyhow!(crate::tr!(
            "unknown experiment '{name}': choose one of {}",
            "没有名为 '{name}' 的实验：请从 {} 中选择",
            names.join(", ")
        ))
    })?;
    let base = PpoConfig {
        num_episodes: episodes,
        ..PpoConfig::default()
    };
    let threads = std::thread::available_parallelism().map_or(1, usize::from);
    Ok(crate::ppo::lab::run(
        experiment,
        &base,
        seeds,
        threads,
        |_, _| {},
    )?)
}

impl LabResult {
    /// The settings' bands and means in one figure.
    ///
    /// # Errors
    /// [`PlotError::Draw`] if plotters fails.
    pub fn plot(&self) -> Result<Svg, PlotError> {
        let arms: Vec<(&str, &crate::ppo::seeds::Band)> = self
            .arms
            .iter()
            .map(|a| (a.label.as_str(), &a.band))
            .collect();
        let title = crate::plot::labels::lab_title(self.experiment.name(), self.seeds.len());
        crate::plot::lab_plot_svg(&title, &arms, self.seeds.len()).map(Svg)
    }

    /// evcxr's display hook: the table, then the figure.
    pub fn evcxr_display(&self) {
        emit_rich(self);
    }
}

impl Rich for LabResult {
    fn rich(&self) -> Vec<(&'static str, String)> {
        let mut out = vec![("text/plain", self.table().join("\n"))];
        if let Ok(svg) = self.plot() {
            out.push(("image/svg+xml", svg.0));
        }
        out
    }
}

/// Once per kernel, when `RAYON_NUM_THREADS` is unset: says how to make training twice as
/// fast. (The library cannot set the variable itself: `set_var` is `unsafe`, which this
/// crate forbids, and a kernel runs other threads.)
fn hint_candle_threads() {
    static ONCE: std::sync::Once = std::sync::Once::new();
    ONCE.call_once(|| {
        if std::env::var_os("RAYON_NUM_THREADS").is_none() {
            println!(
                "{}",
                crate::i18n::t(CANDLE_THREADS_HINT, CANDLE_THREADS_HINT_ZH)
            );
        }
    });
}

/// What [`snapshot`] prints once when candle would use every core.
const CANDLE_THREADS_HINT: &str = "note: RAYON_NUM_THREADS is unset, so candle uses every \
    core, which makes these small networks train about 2x slower. Start Jupyter with \
    `RAYON_NUM_THREADS=1 jupyter lab notebooks/` (the kernel inherits it).";
const CANDLE_THREADS_HINT_ZH: &str = "注意：没有设置 RAYON_NUM_THREADS，candle 会用上所有 CPU \
    核，这些小网络反而会训练得慢约 2 倍。请这样启动 Jupyter：\
    `RAYON_NUM_THREADS=1 jupyter lab notebooks/`（内核会继承这个设置）。";

/// "N more rows" under a cut table.
fn more_rows(n: usize) -> String {
    crate::tr!("{n} more rows", "还有 {n} 行")
}

/// A grading report as in `ppo-tutor grade`: the same text, with its marks coloured.
#[cfg(feature = "exercises")]
#[must_use]
pub fn report_html(report: &Report) -> Html {
    let text = report.render();
    let colour = |line: &str| {
        let t = line.trim_start();
        if t.starts_with('✓') {
            "#2b8a3e"
        } else if t.starts_with('✗') {
            "#c92a2a"
        } else if t.starts_with("hint:") || t.starts_with("提示") {
            "#1864ab"
        } else {
            ""
        }
    };
    let mut html = String::from("<pre style=\"font-size:12px\">");
    for line in text.lines() {
        let c = colour(line);
        if c.is_empty() {
            let _ = writeln!(html, "{}", escape(line));
        } else {
            let _ = writeln!(html, "<span style=\"color:{c}\">{}</span>", escape(line));
        }
    }
    let passed = report
        .checks
        .iter()
        .all(|c| matches!(c.status, CheckStatus::Passed));
    let verdict = if passed && report.compile_error.is_none() {
        crate::i18n::t(
            "<b style=\"color:#2b8a3e\">All checks pass.</b>",
            "<b style=\"color:#2b8a3e\">全部检查通过。</b>",
        )
    } else {
        crate::i18n::t(
            "<b style=\"color:#c92a2a\">Not yet: fix the first ✗ and run the cell again.</b>",
            "<b style=\"color:#c92a2a\">还没有通过：先修正第一个 ✗，再运行这个单元格。</b>",
        )
    };
    let _ = write!(html, "</pre>{verdict}");
    Html { html, text }
}

#[cfg(feature = "exercises")]
impl Report {
    /// evcxr's display hook: the report, marks coloured.
    pub fn evcxr_display(&self) {
        emit_rich(self);
    }
}

#[cfg(feature = "exercises")]
impl Rich for Report {
    fn rich(&self) -> Vec<(&'static str, String)> {
        report_html(self).rich()
    }
}

/// Where the pole's tip is drawn in [`cartpole_svg`]'s 600x400 picture.
fn pole_tip(state: &[f64; 4]) -> (f64, f64) {
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn long_tensors_are_cut_and_say_how_many_rows_are_hidden() {
        let rows = 30;
        let rendered = shown_rows(rows);
        assert_eq!(rendered.len(), MAX_ROWS);
        assert_eq!(rendered.last(), Some(&Some(rows - 1)));
        assert!(rendered.contains(&None));
        assert_eq!(shown_rows(5), (0..5).map(Some).collect::<Vec<_>>());
    }

    #[test]
    fn a_block_cannot_be_closed_early_by_its_content() {
        let b = block("text/plain", "a\nEVCXR_END_CONTENT\nb");
        assert_eq!(b.matches("\nEVCXR_END_CONTENT").count(), 1);
        assert!(b.ends_with("\nEVCXR_END_CONTENT"));
        assert_eq!(escape("<b>&</b>"), "&lt;b&gt;&amp;&lt;/b&gt;");
    }

    /// The text inside every `<text>` element of `svg` (a raw `<` there breaks the picture).
    fn texts(svg: &str) -> Vec<&str> {
        svg.split("<text")
            .skip(1)
            .filter_map(|t| {
                t.split_once('>')
                    .and_then(|(_, rest)| rest.split_once("</text>"))
            })
            .map(|(inner, _)| inner)
            .collect()
    }

    #[test]
    fn svg_text_is_escaped() {
        let epoch = EpochTrace {
            ratio: vec![0.5, 1.0, 1.5],
            ..EpochTrace::default()
        };
        for svg in [
            clip_chart_svg(0.2, Some(&epoch), &[1.0, -1.0, 2.0]),
            cartpole_svg(&[0.1, 0.0, -0.1, 0.0]),
        ] {
            let inner = texts(svg.as_str());
            assert!(!inner.is_empty());
            for t in inner {
                assert!(!t.contains('<'), "unescaped '<' in {t:?}");
                assert!(
                    t.split('&').skip(1).all(|e| e.starts_with("lt;")
                        || e.starts_with("gt;")
                        || e.starts_with("amp;")),
                    "unescaped '&' in {t:?}"
                );
            }
        }
    }

    #[test]
    fn the_clip_chart_draws_one_point_per_row_with_an_advantage() {
        let epoch = EpochTrace {
            ratio: vec![0.5, 1.0, 1.5, 1.1],
            ..EpochTrace::default()
        };
        let svg = clip_chart_svg(f64::from(0.2_f32), Some(&epoch), &[1.0, -1.0, 2.0, 0.0]);
        assert_eq!(svg.as_str().matches("<circle").count(), 3);
        assert!(svg.as_str().contains("ε = 0.2;"), "{}", svg.as_str());
        let empty = clip_chart_svg(0.2, None, &[]);
        assert_eq!(empty.as_str().matches("<circle").count(), 0);
    }

    #[test]
    fn the_pole_leans_the_way_theta_says() {
        let (upright, _) = pole_tip(&[0.0, 0.0, 0.0, 0.0]);
        assert!((upright - 300.0).abs() < 1e-9);
        assert!(pole_tip(&[0.0, 0.0, 0.2, 0.0]).0 > 300.0);
        assert!(pole_tip(&[0.0, 0.0, -0.2, 0.0]).0 < 300.0);
        assert!(
            pole_tip(&[1.0, 0.0, 0.0, 0.0]).0 > 300.0,
            "the cart moves right with x"
        );
        let svg = cartpole_svg(&[0.0, 0.0, 0.2, 0.0]);
        let (x, y) = pole_tip(&[0.0, 0.0, 0.2, 0.0]);
        assert!(
            svg.as_str()
                .contains(&format!("x2=\"{x:.2}\" y2=\"{y:.2}\""))
        );
    }
}
