//! Reference solution for lesson 07: the n-step target, of which the seed's
//! `td_target = rewards + self.gamma * self.critic(next_states) * (1 - dones)` is the case
//! `n = 1`.

/// For each step `t`: up to `n` real rewards from `t` on, each discounted once per step it
/// lies ahead, then the critic's `V` of the state reached, discounted once more per step,
/// unless the episode terminated on the way (then the sum stops after that step's reward,
/// and nothing is bootstrapped). The rollout's end shortens the window to what remains.
pub fn n_step_target(
    rewards: &[f32],
    values: &[f32],
    dones: &[bool],
    gamma: f32,
    n: usize,
) -> Vec<f32> {
    let steps = rewards.len();
    let mut targets = Vec::with_capacity(steps);
    for t in 0..steps {
        let window = n.min(steps - t);
        let mut target = 0.0_f32;
        let mut discount = 1.0_f32;
        let mut terminated = false;
        for k in 0..window {
            target += discount * rewards[t + k];
            discount *= gamma;
            if dones[t + k] {
                terminated = true;
                break;
            }
        }
        if !terminated {
            // `discount` is now γ^window: the state reached lies `window` steps ahead.
            target += discount * values[t + window];
        }
        targets.push(target);
    }
    targets
}
