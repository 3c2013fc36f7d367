//! Lesson 17 exercise: the log-probability of a whole action when the action has several
//! dimensions, the `log π(a|s)` that PPO's ratio is made of.
//!
//! Grade: `ppo-tutor grade diag_gaussian_log_prob` (or `g` in the tutor).
//! Start over: `ppo-tutor reset diag_gaussian_log_prob` (restores this whole file).

/// How likely a Gaussian policy was to take each action, on a log scale, when an action is
/// not one torque but a vector of `dim` numbers (a robot arm with several joints, say),
/// CleanRL's `ppo_continuous_action.py` policy.
///
/// - The batch has `N` rows, one per step. `actions` and `mu` are `N × dim`, row-major:
///   dimension `d` of row `i` is at `[i * dim + d]`. `mu` is the policy's mean for that row.
/// - The policy draws each dimension from its own Normal, independently of the others. The
///   spread does not depend on the state: `log_std[d]` (length `dim`) is the *log* of the
///   standard deviation of dimension `d`, shared by every row, one learned number per
///   dimension as in CleanRL.
/// - `dim` is at least 1; `N` may be 0. Return one value per row (`N` values, not
///   `N × dim`): the log-density of the row's whole action, in f32. PPO builds one ratio
///   per step from it.
/// - A log-density can be above 0 (a narrow Normal is denser than 1 near its mean) and very
///   negative for an action many standard deviations away from the mean.
///
/// Pass bar: every row within 1e-4 absolute plus 1e-5 relative of the reference, on 16 seeded
/// random batches (1 to 30 rows of 1 to 6 dimensions), one-dimensional cases, CleanRL's
/// initial `log σ = 0`, a single row of six dimensions, actions many σ from the mean, nine
/// rows recorded from PyTorch's `Normal.log_prob` (summed over each row's dimensions), and a
/// batch with no rows.
///
/// Taught in lesson 17 (continuous-actions), step 3 "The log-density of a Normal", for one
/// dimension; the step's last paragraph says what changes with several.
pub fn diag_gaussian_log_prob(
    actions: &[f32],
    mu: &[f32],
    log_std: &[f32],
    dim: usize,
) -> Vec<f32> {
    // TODO: the dimensions are independent. What does that make the density of the whole
    // action, and what does the log do to it?
    todo!()
}
