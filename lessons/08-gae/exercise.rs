//! Lesson 08 exercise: generalised advantage estimation.
//!
//! Grade: `ppo-tutor grade compute_advantage` (or `g` in the tutor).
//! Start over: `ppo-tutor reset compute_advantage`.

/// The seed's `rl_utils.compute_advantage(gamma, lmbda, td_delta)`: one advantage per step.
pub fn compute_advantage(gamma: f32, lmbda: f32, td_delta: &[f32]) -> Vec<f32> {
    // TODO: walk the episode from its last step to its first, carrying a running value
    // that starts at 0: running = gamma * lmbda * running + td_delta[t]. The advantage at
    // step t is the running value there. Return the advantages in the episode's order.
    todo!()
}
