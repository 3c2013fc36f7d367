//! Recipe for notebooks/14-training.ipynb (see 01-what-is-ppo.rs for the format).
//! Steps 3 and 4 each train five runs of 500 episodes on every core (several seconds).

// %%
use ppo_engine::lesson::Snapshot;
use ppo_engine::notebook::snapshot;
use ppo_engine::plot::smoothed_returns;
use ppo_engine::ppo::PpoConfig;
use ppo_engine::ppo::seeds::{SeedRun, mean_std, train_seeds};
// The seed's whole run: 500 episodes (a few seconds).
let config: PpoConfig = PpoConfig::default();
let snap: Snapshot = snapshot(config.clone(), 0, 500)?;
let threads: usize = std::thread::available_parallelism().map_or(1, |n| n.get());
// An episode number (from 1) for an index, or "never".
fn episode(index: Option<usize>) -> String {
    index.map_or("never".to_string(), |i| (i + 1).to_string())
}
// Per seed: its first 500-step episode, the first episode where its moving average reaches
// 450, the lowest the average falls after that first 500, and the mean of its last 50 returns.
fn describe(runs: &[SeedRun]) {
    println!("seed  first 500  average >= 450  lowest after  last 50");
    for run in runs {
        let returns = &run.summary.returns;
        let smooth = smoothed_returns(returns);
        let first = returns.iter().position(|&r| r >= 500.0);
        let at_450 = smooth.iter().position(|&m| m >= 450.0);
        let lowest = first.map_or("-".to_string(), |f| {
            format!("{:.0}", smooth[f..].iter().copied().fold(f64::INFINITY, f64::min))
        });
        println!("{:4}  {:>9}  {:>14}  {:>12}  {:7.1}", run.seed, episode(first), episode(at_450), lowest, run.summary.mean_last(50));
    }
}
// The late falls of a run: its episodes below 250 after its first 500-step episode.
fn late_falls(run: &SeedRun) -> usize {
    let returns = &run.summary.returns;
    let first = returns.iter().position(|&r| r >= 500.0).unwrap_or(returns.len());
    returns[first..].iter().filter(|&&r| r < 250.0).count()
}

// %% step: Following a run
// The seed prints the mean return of the last ten episodes at the end of each bar.
for bar in 0..10 {
    let end = (bar + 1) * 50;
    let mean: f64 = snap.returns[end - 10..end].iter().sum::<f64>() / 10.0;
    println!("Iteration {bar}: episode {end}, return {mean:.3}");
}

// %% step: Reading the return curve
// What holds for every run: short first episodes, and nothing above 500.
let highest: f64 = snap.returns.iter().copied().fold(0.0, f64::max);
println!("first five returns: {:?}", &snap.returns[..5]);
println!("the highest return: {highest}, in {} episodes", snap.returns.len());

// %% step: Five seeds, one setting
// Seeds 0–4, the seed's settings, 500 episodes each.
let seeds_0_4: Vec<SeedRun> = train_seeds(&config, &[0, 1, 2, 3, 4], threads, |_, _| {})?;
describe(&seeds_0_4);

// %% step: What a curve can and cannot tell
// The same setting on seeds 5–9: two draws of five seeds, nothing else changed.
let seeds_5_9: Vec<SeedRun> = train_seeds(&config, &[5, 6, 7, 8, 9], threads, |_, _| {})?;
describe(&seeds_5_9);
for (name, runs) in [("seeds 0-4", &seeds_0_4), ("seeds 5-9", &seeds_5_9)] {
    let ends: Vec<f64> = runs.iter().map(|r| r.summary.mean_last(50)).collect();
    let (mean, std) = mean_std(&ends);
    let falls: usize = runs.iter().map(late_falls).sum();
    println!("{name}: last-50 mean {mean:.1} ± {std:.1}, {falls} episodes below 250 after the first 500");
}

// %% step: Smoothing: a centred window of 9
// A row in the middle: moving_average[100] is the mean of returns[96..=104].
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

// The edges: windows of 1, 3, 5 and 7 at indices 0 to 3.
println!("first five: {:?}", &snap.moving_average[..5]);
println!("returns:    {:?}", &snap.returns[..5]);
