//! Reference solution for lesson 09: `torch.log(self.actor(states).gather(1, actions))` and
//! `ratio = torch.exp(log_probs - old_log_probs)`.

/// `log(probs[i][actions[i]])`: the log-probability of the action taken in each row.
pub fn log_prob_of_actions(probs: &[[f32; 2]], actions: &[usize]) -> Vec<f32> {
    probs.iter().zip(actions).map(|(p, &a)| p[a].ln()).collect()
}

/// `exp(log_probs[i] - old_log_probs[i])`: `π(a|s) / π_old(a|s)` per row.
pub fn ratio(log_probs: &[f32], old_log_probs: &[f32]) -> Vec<f32> {
    log_probs
        .iter()
        .zip(old_log_probs)
        .map(|(new, old)| (new - old).exp())
        .collect()
}
