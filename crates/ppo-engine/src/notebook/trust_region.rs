//! The trust-region probe in a notebook (lesson 10): its table and its chart.
//!
//! A [`TrustRegionProbe`] as a cell's last expression shows both: the table
//! ([`trust_region_table`], as `ppo-tutor trust-region` prints it: each step `α` with the
//! mean KL, the surrogate's predicted change in `J_γ`, the true change and the score's, each
//! ± one standard error) and the chart
//! ([`trust_region_svg`]: predicted and true change against the mean KL, on a log scale).
//!
//! ```
//! use ppo_engine::notebook::{Rich, trust_region_svg, trust_region_table};
//! use ppo_engine::ppo::trust_region::{ProbePoint, TrustRegionProbe};
//!
//! let point = |step: f32, kl: f64, predicted: f64, truth: f64| ProbePoint {
//!     step, kl, kl_max: 2.0 * kl, predicted, predicted_se: 0.01, truth, truth_se: 0.02,
//!     return_change: truth * 2.0, return_change_se: 0.05,
//! };
//! let probe = TrustRegionProbe {
//!     points: vec![point(0.0, 0.0, 0.0, 0.0), point(0.1, 1e-3, 0.05, 0.04), point(1.6, 0.4, 0.9, -0.5)],
//!     old_return: 20.0, old_score: 25.0, episodes: 150, states: 3750, gradient_norm: 2.5,
//! };
//! // what was probed, a blank line, the header, 3 steps, a blank line, the legend
//! assert_eq!(trust_region_table(&probe).len(), 2 + 1 + 3 + 2);
//! let chart = trust_region_svg(&probe);
//! // The predicted points at KL > 0 are circles (α = 0 is left out), and so is its legend's.
//! assert_eq!(chart.as_str().matches("<circle").count(), 2 + 1);
//! assert_eq!(probe.rich().len(), 2); // the table as text, the chart as SVG
//! ```

use std::fmt::Write as _;

use super::{Rich, Svg, escape};
use crate::i18n::{pad_left, t};
use crate::ppo::PpoConfig;
use crate::ppo::trust_region::{ProbePoint, TrustRegionProbe};
use crate::tr;

/// The probe as lines of text, as `ppo-tutor trust-region` prints it: what was stepped
/// along and where `π_old` stands, a blank line, a header, one row per step (`α`, the mean
/// KL over `π_old`'s held-out states, the predicted and the true change in `J_γ`, and the
/// change in the score, each ± one standard error over the held-out episodes), a blank
/// line and what the columns mean.
#[must_use]
pub fn trust_region_table(probe: &TrustRegionProbe) -> Vec<String> {
    let (norm, episodes, states) = (probe.gradient_norm, probe.episodes, probe.states);
    let (score, old_return) = (probe.old_score, probe.old_return);
    let mut lines = vec![
        tr!(
            "θ_α = θ_old + α · g/‖g‖ with g the batch's surrogate gradient (‖g‖ = {norm:.4}); {episodes} held-out episodes of π_old (mean score {score:.1}, mean J_γ {old_return:.2}), {states} states",
            "θ_α = θ_old + α · g/‖g‖，g 是这一批替代目标的梯度（‖g‖ = {norm:.4}）；π_old 另跑 {episodes} 个回合（平均得分 {score:.1}，平均 J_γ {old_return:.2}），共 {states} 个状态"
        ),
        String::new(),
    ];
    let headers = [
        t("α", "步长 α"),
        t("mean KL", "平均 KL"),
        t("predicted ΔJ_γ", "预测的 ΔJ_γ"),
        t("true ΔJ_γ", "真实的 ΔJ_γ"),
        t("score change", "得分变化"),
    ];
    let widths = [7, 11, 18, 18, 16];
    let row = |cells: [String; 5]| {
        cells
            .iter()
            .zip(widths)
            .map(|(c, w)| pad_left(c, w))
            .collect::<Vec<_>>()
            .join("  ")
    };
    lines.push(row(headers.map(String::from)));
    for p in &probe.points {
        lines.push(row([
            format!("{:.3}", p.step),
            format!("{:.2e}", p.kl),
            format!("{:+.3} ± {:.3}", p.predicted, p.predicted_se),
            format!("{:+.3} ± {:.3}", p.truth, p.truth_se),
            format!("{:+.1} ± {:.1}", p.return_change, p.return_change_se),
        ]));
    }
    lines.push(String::new());
    lines.push(
        t(
            "predicted: the surrogate Σ_t γ^t (r_t − 1) Â_t on π_old's held-out episodes; true: fresh episodes of π_θα from the same seeds, minus π_old's; ± one standard error over the episodes.",
            "预测：替代目标在 π_old 另跑的回合上的 Σ_t γ^t (r_t − 1) Â_t；真实：π_θα 用同样的随机种子重新跑的回合，减去 π_old 的；± 为各回合间的一个标准误。",
        )
        .to_string(),
    );
    lines
}

/// A round step for about five ticks over `range` (1, 2 or 5 times a power of ten).
fn tick_step(range: f64) -> f64 {
    let raw = range / 5.0;
    let magnitude = 10f64.powf(raw.log10().floor());
    let norm = raw / magnitude;
    let nice = if norm <= 1.0 {
        1.0
    } else if norm <= 2.0 {
        2.0
    } else if norm <= 5.0 {
        5.0
    } else {
        10.0
    };
    nice * magnitude
}

/// The plot area of [`trust_region_svg`]: left, right, top, bottom, in pixels.
const AREA: (f64, f64, f64, f64) = (90.0, 690.0, 84.0, 390.0);

/// The chart of the probe (720x460): the surrogate's predicted change in `J_γ` (blue
/// circles) and the true change (orange squares), each with a bar of ± one standard error,
/// against the mean KL on a log scale; the steps with a KL of 0 (`α = 0`, where both are 0)
/// are left out. A dashed vertical line marks the KL target δ of the penalty and the line
/// search (`kl_delta`, 0.01), and a grey line the change 0.
#[must_use]
pub fn trust_region_svg(probe: &TrustRegionProbe) -> Svg {
    let (left, right, top, bottom) = AREA;
    let (width, height) = (720.0, 460.0);
    let points: Vec<_> = probe
        .points
        .iter()
        .filter(|p| p.kl > 0.0 && p.kl.is_finite())
        .collect();
    let delta = PpoConfig::default().kl_delta;
    // x: decades of the KL, δ included.
    let kls = points.iter().map(|p| p.kl).chain(std::iter::once(delta));
    let lo = kls.clone().fold(f64::INFINITY, f64::min).log10().floor();
    let hi = kls.fold(f64::NEG_INFINITY, f64::max).log10().ceil();
    let hi = if hi > lo { hi } else { lo + 1.0 };
    let x = |kl: f64| left + (kl.log10() - lo) / (hi - lo) * (right - left);
    // y: every bar, and 0.
    let ends = points.iter().flat_map(|p| {
        [
            p.predicted - p.predicted_se,
            p.predicted + p.predicted_se,
            p.truth - p.truth_se,
            p.truth + p.truth_se,
        ]
    });
    let (y_lo, y_hi) = ends
        .filter(|v| v.is_finite())
        .fold((0.0_f64, 0.0_f64), |(a, b), v| (a.min(v), b.max(v)));
    let pad = ((y_hi - y_lo) * 0.08).max(1e-3);
    let (y_lo, y_hi) = (y_lo - pad, y_hi + pad);
    let y = |v: f64| bottom - (v - y_lo) / (y_hi - y_lo) * (bottom - top);

    let title = t(
        "Stepping along the surrogate's gradient: predicted and true change in J_γ",
        "沿替代目标的梯度走一步：J_γ 的预测变化与真实变化",
    );
    let mut svg = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{width}\" height=\"{height}\" viewBox=\"0 0 {width} {height}\" font-family=\"sans-serif\" font-size=\"13\">\n\
         <rect width=\"{width}\" height=\"{height}\" fill=\"white\"/>\n\
         <text x=\"{:.1}\" y=\"30\" font-size=\"16\" text-anchor=\"middle\">{}</text>\n\
         <rect x=\"{left}\" y=\"{top}\" width=\"{:.1}\" height=\"{:.1}\" fill=\"none\" stroke=\"#888\"/>\n",
        (left + right) / 2.0,
        escape(title),
        right - left,
        bottom - top
    );
    // Axes: decades along x, round steps along y.
    let decades = (hi - lo).round() as i32;
    for k in 0..=decades {
        let e = lo as i32 + k;
        let px = x(10f64.powi(e));
        let _ = writeln!(
            svg,
            "<line x1=\"{px:.1}\" y1=\"{top}\" x2=\"{px:.1}\" y2=\"{bottom}\" stroke=\"#eee\"/>\n\
             <text x=\"{px:.1}\" y=\"{:.1}\" text-anchor=\"middle\">1e{e}</text>",
            bottom + 18.0
        );
    }
    let step = tick_step(y_hi - y_lo);
    let decimals = (-step.log10().floor()).max(0.0) as usize;
    let mut v = (y_lo / step).ceil() * step;
    while v <= y_hi {
        let py = y(v);
        let _ = writeln!(
            svg,
            "<line x1=\"{left}\" y1=\"{py:.1}\" x2=\"{right}\" y2=\"{py:.1}\" stroke=\"#eee\"/>\n\
             <text x=\"{:.1}\" y=\"{:.1}\" text-anchor=\"end\">{v:.decimals$}</text>",
            left - 6.0,
            py + 4.0
        );
        v += step;
    }
    let zero = y(0.0);
    let dx = x(delta);
    let _ = writeln!(
        svg,
        "<line x1=\"{left}\" y1=\"{zero:.1}\" x2=\"{right}\" y2=\"{zero:.1}\" stroke=\"#888\"/>\n\
         <line x1=\"{dx:.1}\" y1=\"{top}\" x2=\"{dx:.1}\" y2=\"{bottom}\" stroke=\"#555\" stroke-dasharray=\"5,4\"/>\n\
         <text x=\"{:.1}\" y=\"{:.1}\">δ = {delta}</text>\n\
         <text x=\"{:.1}\" y=\"{:.1}\" text-anchor=\"middle\">{}</text>\n\
         <text x=\"20\" y=\"{:.1}\" text-anchor=\"middle\" transform=\"rotate(-90 20 {:.1})\">{}</text>",
        dx + 4.0,
        top + 14.0,
        (left + right) / 2.0,
        bottom + 44.0,
        escape(t(
            "mean KL(π_old ‖ π_θ) over π_old's held-out states (log scale)",
            "π_old 另跑回合中各状态上的平均 KL(π_old ‖ π_θ)（对数刻度）"
        )),
        (top + bottom) / 2.0,
        (top + bottom) / 2.0,
        escape(t(
            "change in the discounted return J_γ",
            "折扣回报 J_γ 的变化"
        )),
    );
    // The two series: a line through the means, a bar of ± one SE, a marker at each mean.
    let blue = "#1f77b4";
    let orange = "#ff7f0e";
    let predicted: fn(&ProbePoint) -> (f64, f64) = |p| (p.predicted, p.predicted_se);
    let truth: fn(&ProbePoint) -> (f64, f64) = |p| (p.truth, p.truth_se);
    for (colour, circle, value) in [(blue, true, predicted), (orange, false, truth)] {
        let line: Vec<String> = points
            .iter()
            .map(|p| format!("{:.1},{:.1}", x(p.kl), y(value(p).0)))
            .collect();
        let _ = writeln!(
            svg,
            "<polyline points=\"{}\" fill=\"none\" stroke=\"{colour}\" stroke-width=\"2\"/>",
            line.join(" ")
        );
        for p in &points {
            let (mean, se) = value(p);
            let (px, py) = (x(p.kl), y(mean));
            let _ = writeln!(
                svg,
                "<line x1=\"{px:.1}\" y1=\"{:.1}\" x2=\"{px:.1}\" y2=\"{:.1}\" stroke=\"{colour}\" stroke-width=\"1.5\"/>",
                y(mean - se),
                y(mean + se)
            );
            let _ = writeln!(svg, "{}", marker(circle, px, py, colour));
        }
    }
    // The legend, under the title.
    let legend = [
        (
            blue,
            true,
            t(
                "predicted: the surrogate on π_old's episodes",
                "预测：在 π_old 的回合上算替代目标",
            ),
        ),
        (
            orange,
            false,
            t(
                "true: fresh episodes of π_θ (same seeds)",
                "真实：π_θ 新跑的回合（相同的随机种子）",
            ),
        ),
    ];
    for (k, (colour, circle, label)) in legend.into_iter().enumerate() {
        let ly = 52.0 + 18.0 * k as f64;
        let _ = writeln!(
            svg,
            "{}\n<text x=\"{:.1}\" y=\"{:.1}\">{}</text>",
            marker(circle, left + 16.0, ly - 4.0, colour),
            left + 28.0,
            ly,
            escape(label)
        );
    }
    svg.push_str("</svg>");
    Svg(svg)
}

/// A circle (predicted) or a square (true) at `(x, y)`.
fn marker(circle: bool, x: f64, y: f64, colour: &str) -> String {
    if circle {
        format!("<circle cx=\"{x:.1}\" cy=\"{y:.1}\" r=\"4\" fill=\"{colour}\"/>")
    } else {
        format!(
            "<rect x=\"{:.1}\" y=\"{:.1}\" width=\"8\" height=\"8\" fill=\"{colour}\"/>",
            x - 4.0,
            y - 4.0
        )
    }
}

/// The table, then the chart.
impl Rich for TrustRegionProbe {
    fn rich(&self) -> Vec<(&'static str, String)> {
        vec![
            ("text/plain", trust_region_table(self).join("\n")),
            ("image/svg+xml", trust_region_svg(self).as_str().to_string()),
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::i18n::Lang;

    fn point(step: f32, kl: f64, predicted: f64, truth: f64) -> ProbePoint {
        ProbePoint {
            step,
            kl,
            kl_max: 3.0 * kl,
            predicted,
            predicted_se: 0.01,
            truth,
            truth_se: 0.02,
            return_change: 2.0 * truth,
            return_change_se: 0.05,
        }
    }

    fn probe() -> TrustRegionProbe {
        TrustRegionProbe {
            points: vec![
                point(0.0, 0.0, 0.0, 0.0),
                point(0.05, 2e-4, 0.01, 0.012),
                point(0.4, 0.02, 0.3, 0.2),
                point(3.2, 0.6, 1.5, -2.0),
            ],
            old_return: 21.5,
            old_score: 24.0,
            episodes: 150,
            states: 3600,
            gradient_norm: 1.25,
        }
    }

    #[test]
    fn the_table_has_a_line_per_step_in_both_languages() {
        for lang in Lang::ALL {
            let _lang = lang.scoped();
            let lines = trust_region_table(&probe());
            // what was probed, a blank, the header, four steps, a blank, the legend
            assert_eq!(lines.len(), 2 + 1 + 4 + 2, "{lines:?}");
            let widths: Vec<usize> = lines[2..7].iter().map(|l| crate::i18n::width(l)).collect();
            assert!(widths.iter().all(|&w| w == widths[0]), "{lines:#?}");
            assert!(lines[6].contains("-2.000 ± 0.020"), "{}", lines[6]);
            assert!(lines[0].contains("150") && lines[0].contains("3600"));
        }
        let en = trust_region_table(&probe());
        let zh = {
            let _zh = Lang::Zh.scoped();
            trust_region_table(&probe())
        };
        assert_ne!(en[2], zh[2], "the header is translated");
        assert_eq!(
            en[3..7],
            zh[3..7],
            "the numbers do not depend on the language"
        );
    }

    /// The text inside every `<text>` element of `svg`.
    fn texts(svg: &str) -> Vec<&str> {
        svg.split("<text")
            .skip(1)
            .filter_map(|t| t.split_once('>').and_then(|(_, r)| r.split_once("</text>")))
            .map(|(inner, _)| inner)
            .collect()
    }

    #[test]
    fn the_chart_draws_each_step_with_a_kl_once_per_series() {
        let svg = trust_region_svg(&probe());
        let svg = svg.as_str();
        // Three steps with a KL > 0, a circle each and one in the legend; squares likewise
        // (plus the frame's rectangles: the background and the plot area).
        assert_eq!(svg.matches("<circle").count(), 3 + 1);
        assert_eq!(svg.matches("<rect").count(), 3 + 1 + 2);
        assert_eq!(svg.matches("<polyline").count(), 2);
        // Decades from 1e-4 to 1e0 on the x axis, δ marked.
        for label in ["1e-4", "1e-3", "1e-2", "1e-1", "1e0", "δ = 0.01"] {
            assert!(
                texts(svg).contains(&label),
                "{label} missing: {:?}",
                texts(svg)
            );
        }
        for text in texts(svg) {
            assert!(!text.contains('<'), "unescaped '<' in {text:?}");
        }
        assert!(svg.starts_with("<svg") && svg.ends_with("</svg>"));
    }

    #[test]
    fn a_probe_with_only_zero_steps_still_draws() {
        let mut p = probe();
        p.points.truncate(1);
        let svg = trust_region_svg(&p);
        assert_eq!(
            svg.as_str().matches("<circle").count(),
            1,
            "the legend's only"
        );
        assert!(!svg.as_str().contains("NaN"));
    }

    #[test]
    fn ticks_are_round() {
        assert!((tick_step(1.0) - 0.2).abs() < 1e-12);
        assert!((tick_step(3.0) - 1.0).abs() < 1e-12);
        assert!((tick_step(40.0) - 10.0).abs() < 1e-12);
        assert!((tick_step(0.07) - 0.02).abs() < 1e-12);
    }
}
