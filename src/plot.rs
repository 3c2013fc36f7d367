//! Return curves, as the seed plots them: raw returns per episode and their moving average.
//!
//! - [`terminal`]: the curve drawn with characters, for `ppo-tutor train`'s summary.
//! - [`file`](mod@file): the seed's matplotlib figure drawn with plotters, to PNG or SVG.
//!
//! Both take the returns and the smoothed curve from
//! [`moving_average`](crate::ppo::moving_average()) (window [`SMOOTHING_WINDOW`], the seed's 9).

pub mod file;
pub mod terminal;

pub use file::{PlotError, save_return_plot};
pub use terminal::ascii_return_plot;

/// The seed's `moving_average(return_list, 9)`.
pub const SMOOTHING_WINDOW: usize = 9;

/// The moving average the seed plots, with the window shrunk (to the largest odd size that
/// fits) for runs shorter than 8 episodes.
#[must_use]
pub fn smoothed_returns(returns: &[f64]) -> Vec<f64> {
    let fits = (returns.len() + 1) | 1;
    let window = SMOOTHING_WINDOW.min(if fits > returns.len() + 1 {
        fits - 2
    } else {
        fits
    });
    crate::ppo::moving_average(returns, window.max(1)).unwrap_or_else(|_| returns.to_vec())
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
