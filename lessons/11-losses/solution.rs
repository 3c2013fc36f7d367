//! Reference solution for lesson 11: the critic's
//! `torch.mean(F.mse_loss(self.critic(states), td_target.detach()))`.

/// `mean_i (values[i] - td_target[i])²`: the mean squared error.
pub fn critic_loss(values: &[f32], td_target: &[f32]) -> f32 {
    let mut total = 0.0_f32;
    for (&v, &t) in values.iter().zip(td_target) {
        total += (v - t) * (v - t);
    }
    total / values.len() as f32
}
