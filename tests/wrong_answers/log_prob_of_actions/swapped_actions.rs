pub fn log_prob_of_actions(probs: &[[f32; 2]], actions: &[usize]) -> Vec<f32> {
    let mut out = Vec::new();
    for i in 0..probs.len() {
        let p = if actions[i] == 0 { probs[i][1] } else { probs[i][0] };
        out.push(p.ln());
    }
    out
}
