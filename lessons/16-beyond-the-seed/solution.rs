//! Reference solution for lesson 16: the TD target that tells a time-limit cut from a real
//! end in an autoreset vector environment's stream, and GAE over a rollout of several
//! episodes (CleanRL's layout).

/// One TD target per row of a same-step autoreset stream: `y_t = r_t` where the episode
/// terminated at `t`; `y_t = r_t + γ·final_values[t]` where only the time limit cut it (the
/// environment already returned the next episode's first observation, so the future of the
/// cut state is the value of the real last one); `y_t = r_t + γ·next_values[t]` on every
/// other row. `final_values` is read on truncated rows only (where no episode ended it is
/// NaN).
pub fn td_target_truncation(
    rewards: &[f32],
    next_values: &[f32],
    final_values: &[f32],
    terminated: &[bool],
    truncated: &[bool],
    gamma: f32,
) -> Vec<f32> {
    let mut out = Vec::with_capacity(rewards.len());
    for t in 0..rewards.len() {
        let target = if terminated[t] {
            rewards[t] // the pole fell: nothing follows
        } else if truncated[t] {
            rewards[t] + gamma * final_values[t] // cut, not ended: the real last observation
        } else {
            rewards[t] + gamma * next_values[t]
        };
        out.push(target);
    }
    out
}

/// Advantages and returns over a rollout that spans several episodes:
/// `δ_t = r_t + γ·V(s_{t+1})·(1 − terminated_t) − V(s_t)`, then backwards
/// `Â_t = δ_t + γλ·(1 − end_t)·Â_{t+1}` with `end_t = terminated_t or truncated_t` and
/// `Â = 0` after the last row; `returns = Â + V(s_t)`.
pub fn gae_rollout(
    rewards: &[f32],
    values: &[f32],
    next_values: &[f32],
    terminated: &[bool],
    truncated: &[bool],
    gamma: f32,
    lmbda: f32,
) -> (Vec<f32>, Vec<f32>) {
    let n = rewards.len();
    let mut advantages = vec![0.0_f32; n];
    let mut next_advantage = 0.0_f32;
    for t in (0..n).rev() {
        let alive = if terminated[t] { 0.0 } else { 1.0 };
        let delta = rewards[t] + gamma * next_values[t] * alive - values[t];
        let same_episode = if terminated[t] || truncated[t] {
            0.0
        } else {
            1.0
        };
        next_advantage = delta + gamma * lmbda * same_episode * next_advantage;
        advantages[t] = next_advantage;
    }
    let returns = advantages.iter().zip(values).map(|(a, v)| a + v).collect();
    (advantages, returns)
}
