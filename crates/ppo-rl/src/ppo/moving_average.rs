//! `rl_utils.moving_average(a, window_size)`: the smoothed return curve the seed plots.
//!
//! A centred mean over `w` (odd) values, with shrinking odd windows at both ends so the
//! output is as long as the input:
//!
//! ```text
//! middle_i = (c_{i+w} - c_i) / w,  c = cumsum([0] ++ a)           (n - w + 1 values)
//! begin_j  = cumsum(a[..w-1])_{2j} / (2j + 1)                      (windows 1, 3, 5, ...)
//! end      = the same from the right end, reversed
//! ```
//!
//! Computed in f64 with numpy's sequential `cumsum`, so results equal numpy's.
//!
//! ```
//! use ppo_rl::ppo::moving_average;
//!
//! let smooth = moving_average(&[1.0, 2.0, 3.0, 4.0, 5.0], 3)?;
//! assert_eq!(smooth, vec![1.0, 2.0, 3.0, 4.0, 5.0]);
//! # Ok::<(), ppo_rl::ppo::PpoError>(())
//! ```

use super::PpoError;

// ANCHOR: moving_average
/// `rl_utils.moving_average(a, window)`: `window` must be odd and at most `a.len() + 1`
/// (numpy raises a broadcast error otherwise).
///
/// # Errors
/// [`PpoError::InvalidWindow`] for an even window or a series shorter than `window - 1`.
pub fn moving_average(a: &[f64], window: usize) -> Result<Vec<f64>, PpoError> {
    // ANCHOR: moving_average_body
    let n = a.len();
    if window.is_multiple_of(2) || n + 1 < window {
        return Err(PpoError::InvalidWindow { window, len: n });
    }
    let cumsum = |xs: &mut dyn Iterator<Item = f64>| -> Vec<f64> {
        let mut total = 0.0;
        xs.map(|x| {
            total += x;
            total
        })
        .collect()
    };
    let c = cumsum(&mut std::iter::once(0.0).chain(a.iter().copied()));
    let w = window as f64;
    let middle = (0..=n.saturating_sub(window)).filter(|_| n >= window);
    let middle = middle.map(|i| (c[i + window] - c[i]) / w);
    let r = (1..window - 1).step_by(2).map(|k| k as f64);
    let begin_sums = cumsum(&mut a[..window - 1].iter().copied());
    let begin = begin_sums
        .iter()
        .step_by(2)
        .zip(r.clone())
        .map(|(s, r)| s / r);
    let end_sums = cumsum(&mut a[n + 1 - window..].iter().rev().copied());
    let mut end: Vec<f64> = end_sums
        .iter()
        .step_by(2)
        .zip(r)
        .map(|(s, r)| s / r)
        .collect();
    end.reverse();
    Ok(begin.chain(middle).chain(end).collect())
    // ANCHOR_END: moving_average_body
}
// ANCHOR_END: moving_average

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
    moving_average(returns, window.max(1)).unwrap_or_else(|_| returns.to_vec())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shapes_match_numpy() -> Result<(), PpoError> {
        let a: Vec<f64> = (0..20).map(f64::from).collect();
        assert_eq!(moving_average(&a, 9)?.len(), 20);
        assert_eq!(moving_average(&a[..8], 9)?.len(), 8);
        assert_eq!(moving_average(&a[..1], 1)?, vec![0.0]);
        assert!(moving_average(&a, 4).is_err());
        assert!(moving_average(&a[..7], 9).is_err());
        Ok(())
    }
}
