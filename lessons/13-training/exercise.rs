//! Lesson 13 exercise: smoothing the return curve like `rl_utils.moving_average`.
//!
//! Grade: `ppo-tutor grade moving_average` (or `g` in the tutor).
//! Start over: `ppo-tutor reset moving_average`.

/// The seed's `rl_utils.moving_average(a, window_size)`: `window_size` is odd and at most
/// `a.len() + 1`; the result has exactly one value per input value.
pub fn moving_average(a: &[f64], window_size: usize) -> Vec<f64> {
    // TODO: away from the ends, value i is the mean of the `window_size` values centred on
    // a[i]. Near the ends, where that window does not fit, shrink it symmetrically: the
    // first value averages 1 value, the second 3, the third 5, ... and the same mirrored at
    // the end.
    todo!()
}
