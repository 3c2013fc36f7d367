//! Lesson 16 exercise: targets and advantages that tell a time-limit cut from a real end,
//! over a rollout of several episodes.
//!
//! Grade: `ppo-tutor grade td_target_truncation` and `ppo-tutor grade gae_rollout` (or `g`
//! in the tutor).
//! Start over: `ppo-tutor reset td_target_truncation` (restores this whole file).

/// The one-step TD target, done right: what step `t` is worth, as the reward it earned plus
/// what the critic expects afterwards, where "afterwards" exists.
///
/// - `rewards[t]` is `r_t`; `next_values[t]` is `V(s_{t+1})`, the critic's value of the
///   observation the environment really returned after step `t` (also after the last step
///   of an episode); `gamma` is γ.
/// - `terminated[t]`: the episode really ended at `t` (the pole fell). `truncated[t]`: the
///   time limit cut it at `t`; the pole was still up. Both can be true at once.
/// - All slices have the same length; return one target per row.
///
/// The seed treats both flags alike (`done = term or trunc`). Decide which of the two means
/// there is no future worth anything. Taught in lesson 16 (beyond-the-seed), step 1
/// "Truncation is not termination".
pub fn td_target_truncation(
    rewards: &[f32],
    next_values: &[f32],
    terminated: &[bool],
    truncated: &[bool],
    gamma: f32,
) -> Vec<f32> {
    // TODO: when the clock cut the episode, was there still a future worth V(s_{t+1})? And
    // when the pole fell?
    todo!()
}

/// GAE over a rollout that spans several episodes, in CleanRL's layout: one row per step,
/// episodes one after another, the last one possibly unfinished.
///
/// - `values[t]` is `V(s_t)`; `next_values[t]` is `V` of the real next observation after
///   step `t`; `rewards`, `terminated`, `truncated`, `gamma` as in `td_target_truncation`;
///   `lmbda` is λ.
/// - Return `(advantages, returns)`, one of each per row, where the returns are the
///   critic's targets CleanRL derives from the advantages (the λ-return of lesson 8, step 6).
/// - Each row's one-step error bootstraps as `td_target_truncation` does. An advantage never
///   reaches across the end of an episode, however it ended. Past the last row there is
///   nothing: treat the advantage there as 0.
///
/// Taught in lesson 16 (beyond-the-seed), step 4 "Rollouts, vector environments and
/// minibatches", with GAE from lesson 8 (gae).
pub fn gae_rollout(
    rewards: &[f32],
    values: &[f32],
    next_values: &[f32],
    terminated: &[bool],
    truncated: &[bool],
    gamma: f32,
    lmbda: f32,
) -> (Vec<f32>, Vec<f32>) {
    // TODO: two questions per row: does its TD error bootstrap, and does the next row's
    // advantage belong to the same episode?
    todo!()
}
