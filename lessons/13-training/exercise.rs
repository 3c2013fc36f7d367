//! Lesson 13 exercise: smoothing the return curve like `rl_utils.moving_average`.
//!
//! Grade: `ppo-tutor grade moving_average` (or `g` in the tutor).
//! Start over: `ppo-tutor reset moving_average`.

/// Smooths the return curve for plotting, as the seed's
/// `rl_utils.moving_average(a, window_size)` does.
///
/// Each point is replaced by the average of the returns in a window centred on it, so the
/// scatter between neighbouring episodes fades and the trend stays. A centred window does not
/// lag behind the data, and the smoothed curve keeps one point per episode, so it can share an
/// x axis with the raw one.
///
/// - `a` holds the returns, one per episode, in order (at least one value).
/// - `window_size` is the width of the full window: odd (9 in the seed), and at most
///   `a.len() + 1`.
///
/// Return exactly one value per input value, in the same order. Near both ends a full window
/// does not fit; the seed still keeps every window centred there, and so must you. A check that
/// always holds: the first value equals the first return, and the last the last. The grader
/// compares with numpy's results to 1e-9, and also tries a single value and windows as long
/// as the input or one longer.
///
/// Taught in lesson 13 (training), step 3 "Why smooth, and how much", step 4 "The middle: a
/// sum that slides" and step 5 "The edges: shrinking odd windows".
pub fn moving_average(a: &[f64], window_size: usize) -> Vec<f64> {
    // TODO: your code here; `h` in the tutor reveals hints one by one.
    // How many returns lie to the left of index 2? How wide can a window centred there be?
    todo!()
}
