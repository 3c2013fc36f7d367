//! Lesson 16 exercise: the log-density of the Gaussian policy at the actions it took, the
//! `log π(a|s)` that PPO's ratio is made of once the action is a torque.
//!
//! Grade: `ppo-tutor grade gaussian_log_prob` (or `g` in the tutor).
//! Start over: `ppo-tutor reset gaussian_log_prob` (restores this whole file).

/// How likely the policy was to take each action, on a log scale: the log of the density of
/// a Normal distribution at the action, what PyTorch's
/// `torch.distributions.Normal(mu, std).log_prob(actions)` returns, row by row.
///
/// - Row `i` is one step. The policy's Normal has mean `mu[i]` (the book's μ = 2·tanh(·),
///   in [−2, 2]) and standard deviation `std[i]` (σ = softplus(·), always > 0; torch's
///   `scale`). `actions[i]` is the torque taken: any real number, near μ or far from it.
/// - All three slices have the same length, possibly 0. Return one value per row, in f32.
/// - This is a log-density: it can be above 0 (a narrow Normal has a density above 1 near
///   its mean) and very negative for an action many σ away from μ.
///
/// Taught in lesson 16 (continuous-actions), step 3 "The log-density of a Normal".
pub fn gaussian_log_prob(mu: &[f32], std: &[f32], actions: &[f32]) -> Vec<f32> {
    // TODO: your code here.
    todo!()
}
