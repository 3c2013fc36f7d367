pub fn sample_action(probs: &[f32], u: f32) -> usize {
    let mut best = 0;
    for i in 1..probs.len() {
        if probs[i] > probs[best] {
            best = i;
        }
    }
    best
}
