//! Lesson 13 exercise: measuring how far an update moved the policy, and stopping it in time.
//!
//! Grade: `ppo-tutor grade reverse_kl` and `ppo-tutor grade kl_early_stop` (or `g` in the
//! tutor). Start over: `ppo-tutor reset reverse_kl` (restores this whole file).

/// How far the policy has moved, measured the other way round: KL(π_θ ‖ π_old).
///
/// approx_kl estimates KL(π_old ‖ π_θ), the divergence averaged over π_old's actions, from
/// the sampled rows alone, and no row of it is ever negative. The KL divergence is not
/// symmetric (lesson 10). Estimate the other direction, KL(π_θ ‖ π_old), the divergence
/// averaged over π_θ's actions, from the same rows, although their actions were drawn
/// from π_old, not from π_θ.
///
/// - `old_log_probs[i]` is `log π_old(a_i|s_i)`, fixed before the update, for an action
///   `a_i` that π_old drew; `log_probs[i]` is `log π_θ(a_i|s_i)` under the current
///   parameters. Same length, at least 1.
/// - Return the mean over the rows of one term per row, in float32. Each row's term depends
///   only on that row's ratio r = π_θ(a_i|s_i) / π_old(a_i|s_i), and it must be
///   - unbiased: its mean over actions drawn from π_old is KL(π_θ ‖ π_old);
///   - never negative, on every row, and exactly 0 where r = 1.
///
/// Pass bar: within 1e-5 absolute plus 1e-4 relative of the reference, on 100 seeded random
/// batches (moves of up to ±0.6 in log-probability, both ways), the recorded PyTorch
/// episodes' epochs, single rows whose action became more or less likely (one row is its
/// own estimate, so a negative term shows), a batch where nothing moved (exactly 0), and a
/// batch where every action became less likely.
///
/// Taught in lesson 13 (clip-lab), step 1 "What to watch in every update": why approx_kl's
/// rows are never negative and its mean is still unbiased. The weight that turns an average
/// under one policy into an average over another's samples is the ratio of lesson 9, step 3
/// "The ratio".
pub fn reverse_kl(old_log_probs: &[f32], log_probs: &[f32]) -> f32 {
    // TODO: your code here; `h` in the tutor reveals hints one by one.
    // Under which policy is KL(π_θ ‖ π_old) an average, and which term, of mean 0 under
    // π_old, keeps every row at or above 0?
    todo!()
}

/// How many gradient steps an update takes under Spinning Up's early stopping.
///
/// The clip does not stop the policy drifting away from the one that collected the batch
/// (lesson 13, experiment 4). Spinning Up's PPO adds a guard: before each epoch's gradient
/// step it estimates how far the policy has moved, and if the estimate has passed its margin
/// above `target_kl` it ends the update there, without taking that step. Apply its rule, with
/// its estimator, to an update whose log-probabilities you are given epoch by epoch. The
/// rule is a few lines of Spinning Up's source (github.com/openai/spinningup): the loop in
/// `update()` of `spinup/algos/pytorch/ppo/ppo.py`, with the estimate computed in
/// `compute_loss_pi` of the same file. Read them, then write them for this input.
///
/// - `old_log_probs[i]` is `log π_old(a_i|s_i)`, fixed before the update; `N` rows, at
///   least 1.
/// - `log_probs_per_epoch` holds `E` rows of `N` numbers one after the other (row-major,
///   `E = log_probs_per_epoch.len() / N`, at least 1): row `e` is `log π(a_i|s_i)` under the
///   policy at the *start* of epoch `e`, before that epoch's step.
/// - `target_kl` is Spinning Up's `target_kl` (0.01 by default).
///
/// Return how many of the `E` epochs took their gradient step: `E` when the guard never
/// fires. The estimates are means over the rows, in float32.
///
/// Pass bar: the exact number of steps, on 100 seeded random updates (1 to 40 epochs of 4 to
/// 64 rows), the recorded PyTorch updates at `target_kl` 0.01 and 0.001, and hand-made
/// updates: moves both ways that cancel, every action made more likely, an estimate that
/// passes `target_kl` one epoch before the margin, a stop before the first step, and an
/// estimate exactly on the margin.
///
/// Taught in lesson 13 (clip-lab), step 5 "Experiment 4: stopping early at a target KL".
pub fn kl_early_stop(old_log_probs: &[f32], log_probs_per_epoch: &[f32], target_kl: f32) -> usize {
    // TODO: your code here; `h` in the tutor reveals hints one by one.
    // Which estimate of the KL divergence does Spinning Up test, and what happens to the step
    // of the epoch where it is first too large?
    todo!()
}
