//! Reference solution for lesson 16: the TD target and GAE that tell a time-limit cut from
//! a real end, over a rollout of several episodes (CleanRL's layout).

/// `y_t = r_t + γ·V(s_{t+1})`, except `y_t = r_t` where the episode terminated at `t`. A
/// truncated step still bootstraps: the pole was up, the future was only cut off.
pub fn td_target_truncation(
    rewards: &[f32],
    next_values: &[f32],
    terminated: &[bool],
    truncated: &[bool],
    gamma: f32,
) -> Vec<f32> {
    let _ = truncated; // the time limit does not change the target
    let mut out = Vec::with_capacity(rewards.len());
    for t in 0..rewards.len() {
        let alive = if terminated[t] { 0.0 } else { 1.0 };
        out.push(rewards[t] + gamma * next_values[t] * alive);
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
