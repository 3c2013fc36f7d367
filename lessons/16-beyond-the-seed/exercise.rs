//! Lesson 16 exercise: targets and advantages that tell a time-limit cut from a real end,
//! over the streams a vector environment produces.
//!
//! Grade: `ppo-tutor grade td_target_truncation` and `ppo-tutor grade gae_rollout` (or `g`
//! in the tutor).
//! Start over: `ppo-tutor reset td_target_truncation` (restores this whole file).

/// The one-step TD target of every row of a stream from a vector environment with
/// same-step autoreset (Gymnasium 0.29, the version CleanRL pins): what step `t` is worth,
/// as the reward it earned plus what the critic expects afterwards, where "afterwards"
/// exists. Such an environment resets an episode on the very step that ends it.
///
/// - `rewards[t]` is `r_t`; `gamma` is γ.
/// - `next_values[t]` is the critic's value of the observation the environment returned
///   after step `t`. On a row where an episode ended, the environment had already reset:
///   that observation is the first one of the next episode.
/// - `final_values[t]` is the critic's value of the real last observation of the episode
///   that ended at `t` (Gymnasium hands that observation over separately, in
///   `infos["final_observation"]`). It means something only on rows where `terminated[t]`
///   or `truncated[t]` is true. On every other row it is NaN, a filler that must never
///   reach a target.
/// - `terminated[t]`: the episode really ended at `t` (the pole fell). `truncated[t]`: the
///   time limit cut it at `t`; the pole was still up. Both can be true at once.
/// - All slices have the same length; return one target per row.
///
/// Pass bar: every target within 1e-5 (absolute plus relative) of the reference's, on 100
/// seeded random streams, the recorded PyTorch episodes joined into one stream, and
/// hand-made streams: a cut, a fall, both flags on one row, cuts on the first and the last
/// row, and a stretch with no end at all. A NaN where a number is due counts as wrong.
///
/// Decide, row by row, which value, if any, stands for what follows step `t`. Taught in
/// lesson 16 (beyond-the-seed), step 1 "Truncation is not termination"; the stream is the
/// one of step 4 "Rollouts, vector environments and minibatches".
pub fn td_target_truncation(
    rewards: &[f32],
    next_values: &[f32],
    final_values: &[f32],
    terminated: &[bool],
    truncated: &[bool],
    gamma: f32,
) -> Vec<f32> {
    // TODO: when the clock cut the episode, which observation's value still says what the
    // state was worth? When the pole fell? And on a row where nothing ended?
    todo!()
}

/// GAE over a rollout that spans several episodes, in CleanRL's layout: one row per step,
/// episodes one after another, the last one possibly unfinished.
///
/// - `values[t]` is `V(s_t)`; `next_values[t]` is `V` of the real next observation after
///   step `t`, one column with no `final_values` beside it; `rewards`, `terminated`,
///   `truncated`, `gamma` as in `td_target_truncation`; `lmbda` is λ.
/// - Return `(advantages, returns)`, one of each per row, where the returns are the
///   critic's targets CleanRL derives from the advantages (the λ-return of lesson 8, step 6).
/// - Each row's one-step error bootstraps, from `next_values[t]`, on the rows where
///   `td_target_truncation`'s target bootstraps at all. An advantage never reaches across
///   the end of an episode, however it ended. Past the last row there is nothing: treat the
///   advantage there as 0.
///
/// Pass bar: every advantage and return within 1e-4 absolute plus 1e-4 relative of the
/// reference's, on 100 seeded random rollouts (3 to 80 rows, episodes ending both ways), the
/// recorded PyTorch episodes joined into one rollout, and hand-made rollouts: a time-limit
/// cut then a new episode, a fall then a new episode, and a rollout that ends mid-episode.
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
