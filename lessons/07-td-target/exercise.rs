//! Lesson 07 exercise: n-step targets, the family the TD target belongs to.
//!
//! Grade: `ppo-tutor grade n_step_target` (or `g` in the tutor).
//! Start over: `ppo-tutor reset n_step_target`.

/// The n-step target of each step of a rollout: what state `s_t` turned out to be worth,
/// judged `n` steps later instead of one. The seed's TD target waits one step: one real
/// reward, then the critic's guess. Here you wait up to `n` steps, collecting the real
/// rewards on the way, and only then hand over to the critic. With `n = 1` your function
/// gives the seed's `td_target`; with `n` as long as the rollout, the critic only speaks for
/// what lies beyond the rollout's last step.
///
/// - `rewards[t]` is the reward received on step `t`, for `t` in `0..T` (1.0 in CartPole;
///   the grader also uses other values, negative ones included).
/// - `values` has `T + 1` entries: `values[t]` is the critic's estimate `V(s_t)` of the state
///   step `t` started in, and `values[T]` is its estimate of the state after the last step,
///   for a rollout that stops in the middle of an episode.
/// - `dones[t]` is true when the episode *terminated* on step `t`: nothing follows it, and
///   the next row, if any, is the first step of a new episode. A rollout may hold several
///   episodes; the grader also tries rollouts where every step is done, and ones with no done
///   at all.
/// - `gamma` is the discount factor γ (0.98 in the seed).
/// - `n >= 1` is how many real rewards a target may collect at most. It can be larger than
///   the rollout: near the rollout's end fewer steps remain, and a target uses what there is.
///
/// `rewards` and `dones` have the same length `T >= 1`. Return one target per step, `T` in
/// all, in order. A target never mixes two episodes: what happens after a termination
/// belongs to someone else's return. The grader compares in f32, to about 1e-5.
///
/// Taught in lesson 7 (td-target), step 2 "The TD target" and step 3 on the done flag.
pub fn n_step_target(
    rewards: &[f32],
    values: &[f32],
    dones: &[bool],
    gamma: f32,
    n: usize,
) -> Vec<f32> {
    // TODO: your code here; `h` in the tutor reveals hints one by one.
    // Standing at step t, how many real rewards can you collect before you must stop:
    // because you have collected n, because the rollout ends, or because the episode does?
    todo!()
}
