pub fn sample_action(probs: &[f32], u: f32) -> usize {
    // Walks the ruler by taking each action's share off u.
    let mut left = u;
    for (i, &p) in probs.iter().enumerate() {
        if left < p {
            return i;
        }
        left -= p;
    }
    probs.len() - 1
}
