pub fn sample_action(probs: &[f32], u: f32) -> usize {
    let mut cumulative = 0.0;
    for (i, p) in probs.iter().enumerate() {
        cumulative += p;
        if u <= cumulative {
            return i;
        }
    }
    probs.len() - 1
}
