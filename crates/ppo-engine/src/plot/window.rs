//! How many episodes a run's moving average spans in its figures and character plots
//! (`ppo-tutor train`): the seed's 9 for the seed's 500-episode run, and about a fiftieth
//! of a longer run, so that the average of Pendulum-v1's 2000 episodes is smooth.
//!
//! ```text
//! window(n) = max(9, the largest odd number ≤ n / 50)      (then at most what n allows)
//! n:        500   549   550   1000   2000   5000
//! window:     9     9    11     19     39     99
//! ```
//!
//! Up to 549 episodes the curve is the seed's `rl_utils.moving_average(return_list, 9)`,
//! which the parity tests and the lessons quote. Runs shorter than 8 episodes shrink the
//! window to the largest odd number that fits, as [`smoothed_returns`] does.
//!
//! ```
//! use ppo_engine::plot::window::{smoothed, window};
//!
//! assert_eq!(window(500), 9);
//! assert_eq!(window(2000), 39);
//! let returns: Vec<f64> = (0..2000).map(f64::from).collect();
//! let (w, average) = smoothed(&returns);
//! assert_eq!((w, average.len()), (39, 2000));
//! ```

use crate::ppo::moving_average::{SMOOTHING_WINDOW, moving_average, smoothed_returns};

/// One window step per this many episodes.
pub const EPISODES_PER_STEP: usize = 50;

/// The moving-average window of a run of `episodes` episodes (the module's rule).
#[must_use]
pub fn window(episodes: usize) -> usize {
    let scaled = episodes / EPISODES_PER_STEP;
    let odd = if scaled % 2 == 1 {
        scaled
    } else {
        scaled.saturating_sub(1)
    };
    let fits = if (episodes + 1) % 2 == 1 {
        episodes + 1
    } else {
        episodes
    };
    odd.max(SMOOTHING_WINDOW).min(fits.max(1))
}

/// `returns`' moving average over [`window`] of their length: the window and the curve (as
/// long as `returns`). Up to 549 episodes, [`smoothed_returns`] exactly.
#[must_use]
pub fn smoothed(returns: &[f64]) -> (usize, Vec<f64>) {
    let w = window(returns.len());
    if w <= SMOOTHING_WINDOW {
        return (w, smoothed_returns(returns));
    }
    let curve = moving_average(returns, w).unwrap_or_else(|_| returns.to_vec());
    (w, curve)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The table of the module doc, and the seed's 9 for every run up to 549 episodes.
    #[test]
    fn the_window_grows_with_the_run_and_keeps_the_seed_s_nine() {
        for (n, w) in [
            (500, 9),
            (549, 9),
            (550, 11),
            (1000, 19),
            (2000, 39),
            (5000, 99),
        ] {
            assert_eq!(window(n), w, "{n} episodes");
        }
        for n in 8..550 {
            assert_eq!(window(n), SMOOTHING_WINDOW, "{n} episodes");
        }
        for n in 0..8 {
            let w = window(n);
            assert!(w % 2 == 1 && w <= n + 1, "{n} episodes: {w}");
        }
        for n in 550..6000 {
            let w = window(n);
            assert!(w % 2 == 1 && w <= n / EPISODES_PER_STEP, "{n}: {w}");
        }
    }

    #[test]
    fn the_seed_s_run_is_smoothed_as_the_seed_smooths() -> Result<(), crate::ppo::PpoError> {
        let returns: Vec<f64> = (0..500).map(|i| f64::from(i % 37)).collect();
        assert_eq!(smoothed(&returns), (9, moving_average(&returns, 9)?));
        for n in 0..12 {
            let short: Vec<f64> = (0..n).map(f64::from).collect();
            assert_eq!(smoothed(&short).1, smoothed_returns(&short), "{n}");
        }
        let long: Vec<f64> = (0..2000).map(|i| f64::from(i % 37)).collect();
        assert_eq!(smoothed(&long), (39, moving_average(&long, 39)?));
        Ok(())
    }
}
