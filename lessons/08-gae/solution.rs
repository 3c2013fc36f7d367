//! Reference solution for lesson 08: the seed's `compute_advantage(gamma, lmbda, td_delta)`,
//! a backward loop over the episode.

/// `advantage[t] = td_delta[t] + gamma * lmbda * advantage[t + 1]`, from the last step to
/// the first, with `advantage[T] = 0`.
pub fn compute_advantage(gamma: f32, lmbda: f32, td_delta: &[f32]) -> Vec<f32> {
    let coef = (f64::from(gamma) * f64::from(lmbda)) as f32;
    let mut advantage = vec![0.0_f32; td_delta.len()];
    let mut adv = 0.0_f32;
    for t in (0..td_delta.len()).rev() {
        adv = coef * adv + td_delta[t];
        advantage[t] = adv;
    }
    advantage
}
