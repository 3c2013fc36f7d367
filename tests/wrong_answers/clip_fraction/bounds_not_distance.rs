pub fn clip_fraction(ratio: &[f32], eps: f32) -> f32 {
    let mut count = 0;
    for i in 0..ratio.len() {
        if ratio[i] > 1.0 + eps || ratio[i] < 1.0 - eps {
            count += 1;
        }
    }
    count as f32 / ratio.len() as f32
}
