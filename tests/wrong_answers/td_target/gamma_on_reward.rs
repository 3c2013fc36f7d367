pub fn td_target(rewards: &[f32], next_values: &[f32], dones: &[bool], gamma: f32) -> Vec<f32> {
    let mut out = Vec::new();
    for i in 0..rewards.len() {
        let done = if dones[i] { 1.0 } else { 0.0 };
        out.push(gamma * (rewards[i] + next_values[i] * (1.0 - done)));
    }
    out
}
