pub fn sample_action(probs: &[f32], u: f32) -> usize {
    if u < probs[0] { 1 } else { 0 }
}
