pub fn sample_action(probs: &[f32], u: f32) -> usize {
    let mut cumulative = 0.0;
    let mut i = 0;
    while i < probs.len() {
        cumulative += probs[i];
        if u < cumulative {
            break;
        }
        i += 1;
    }
    i
}
