//! Return curves, as the seed plots them: raw returns per episode and their moving average.
//!
//! - [`terminal`]: the curve drawn with characters, for `ppo-tutor train`'s summary (one
//!   seed's curve, or several seeds' mean over their band).
//! - [`file`](mod@file): the seed's matplotlib figure drawn with plotters, to PNG or SVG.
//!
//! - [`file::clip_chart_svg`]: the clip chart (`L^CLIP` against the ratio) as SVG.
//! - [`labels`]: every word they show, in English or Chinese (the current
//!   [`Lang`](crate::i18n::Lang)); Chinese figures are set in a bundled subset of Noto Sans
//!   CJK SC (`assets/fonts/`).
//!
//! Both take the returns and the smoothed curve from
//! [`moving_average`](crate::ppo::moving_average()): over the seed's 9 episodes
//! ([`SMOOTHING_WINDOW`]) for the seed's run, over about a fiftieth of a longer one
//! ([`window`](mod@window)), the window said in the legend.

pub mod file;
pub mod labels;
pub mod terminal;
pub mod window;

pub use crate::ppo::moving_average::{SMOOTHING_WINDOW, smoothed_returns};
pub use file::{
    PlotError, XAxis, clip_chart_svg, lab_plot_svg, return_plot_svg, save_band_plot, save_lab_plot,
    save_return_plot, save_return_plot_over,
};
pub use terminal::{ascii_band_plot, ascii_return_plot, ascii_versus_plot, display_width};

/// `L^CLIP(r)` for advantage `a`: `min(r·a, clip(r, 1−ε, 1+ε)·a)`, one row of the seed's
/// `torch.min(surr1, surr2)`.
#[must_use]
pub fn l_clip(r: f64, a: f64, eps: f64) -> f64 {
    (r * a).min(r.clamp(1.0 - eps, 1.0 + eps) * a)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn short_runs_still_smooth() {
        for n in 0..20 {
            let r: Vec<f64> = (0..n).map(f64::from).collect();
            assert_eq!(smoothed_returns(&r).len(), r.len(), "n = {n}");
        }
    }
}
