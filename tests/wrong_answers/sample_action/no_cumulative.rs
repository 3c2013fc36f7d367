pub fn sample_action(probs: &[f32], u: f32) -> usize {
    for (i, &p) in probs.iter().enumerate() {
        if u < p {
            return i;
        }
    }
    probs.len() - 1
}
