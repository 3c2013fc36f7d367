pub fn log_prob_of_actions(probs: &[[f32; 2]], actions: &[usize]) -> Vec<f32> {
    probs.iter().zip(actions).map(|(p, &a)| p[a]).collect()
}
