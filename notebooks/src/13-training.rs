//! Recipe for notebooks/13-training.ipynb (see 01-what-is-ppo.rs for the format).

// %%
use ppo_engine::lesson::Snapshot;
use ppo_engine::notebook::snapshot;
use ppo_engine::ppo::PpoConfig;
// The seed's whole run: 500 episodes (a few seconds).
let config: PpoConfig = PpoConfig::default();
let snap: Snapshot = snapshot(config.clone(), 0, 500)?;

// %% step: Following a run
// The seed prints the mean return of the last ten episodes at the end of each bar.
for bar in 0..10 {
    let end = (bar + 1) * 50;
    let mean: f64 = snap.returns[end - 10..end].iter().sum::<f64>() / 10.0;
    println!("Iteration {bar}: episode {end}, return {mean:.3}");
}

// %% step: Reading the return curve
// %% step: Why smooth, and how much
// %% step: The middle: a sum that slides
// Check a row in the middle: moving_average[100] is the mean of returns[96..=104].
println!("returns[96..=104]   = {:?}", &snap.returns[96..=104]);
println!("moving_average[100] = {:.4}", snap.moving_average[100]);

// rl_utils' prefix sums, (cumsum[w:] − cumsum[:-w]) / w, centred, against the library's
// moving average.
let w = 9;
let mut cumsum = vec![0.0_f64];
for r in &snap.returns {
    cumsum.push(cumsum[cumsum.len() - 1] + r);
}
let middle: Vec<f64> = (w..cumsum.len()).map(|i| (cumsum[i] - cumsum[i - w]) / w as f64).collect();
let centre = w / 2;
for i in [0, 100, 400] {
    assert!((middle[i] - snap.moving_average[i + centre]).abs() < 1e-9);
}
println!("{} middle values match the library's moving average", middle.len());

// %% step: The edges: shrinking odd windows
println!("first five: {:?}", &snap.moving_average[..5]);
println!("returns:    {:?}", &snap.returns[..5]);
