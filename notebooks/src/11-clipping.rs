//! Recipe for notebooks/11-clipping.ipynb (see 01-what-is-ppo.rs for the format).

// %%
use ppo_engine::lesson::Snapshot;
use ppo_engine::notebook::snapshot;
use ppo_engine::ppo::{EpochTrace, PpoConfig, UpdateTrace};
let config: PpoConfig = PpoConfig::default();
let snap: Snapshot = snapshot(config.clone(), 0, 30)?;
let trace: UpdateTrace = snap.cartpole_update().expect("30 episodes were trained").trace.clone();
let last: EpochTrace = trace.epochs[trace.epochs.len() - 1].clone();

// %% step: Two surrogates
// In the first epoch every ratio is exactly 1, so surr1 and surr2 both equal the advantage;
// in the last they differ on the rows whose ratio left the band.
let first: EpochTrace = trace.epochs[0].clone();
assert!(first.surr1 == trace.advantage && first.surr2 == trace.advantage);
let differ = last.surr1.iter().zip(&last.surr2).filter(|(a, b)| a != b).count();
println!(
    "epoch 1: surr1 = surr2 = advantage on all {} rows; epoch {}: they differ on {differ}",
    trace.advantage.len(),
    trace.epochs.len()
);

// %% step: The clamp: a band around 1
// Rows the clamp changed in the last epoch: surr2 / advantage is the clamped ratio.
let eps = config.eps as f32;
println!("band [{}, {}]", 1.0 - eps, 1.0 + eps);
for t in (0..last.ratio.len()).filter(|&t| last.clipped[t]).take(4) {
    println!(
        "row {t:3}: ratio {:.4} -> clamped {:.4}",
        last.ratio[t],
        last.surr2[t] / trace.advantage[t]
    );
}

// %% step: Taking the minimum
// %% step: When the advantage is positive
// %% step: When the advantage is negative
// %% step: How much is being clipped
// The rows the library flagged as clipped, epoch by epoch, with clip_frac and approx_kl.
for (k, e) in trace.epochs.iter().enumerate() {
    let flagged = e.clipped.iter().filter(|c| **c).count();
    println!(
        "epoch {:2}: {flagged:3} of {} rows clipped, clip_frac = {:.4}, approx_kl = {:.2e}",
        k + 1,
        e.clipped.len(),
        e.clip_fraction,
        e.approx_kl
    );
}

// %% exercise
// Back to "Taking the minimum", now that your functions pass: min picks surr2 only where
// surr2 < surr1, where the ratio left the band in the direction its advantage favours. Where
// it left the band the other way, surr1 < surr2 and min keeps surr1.
let picked_surr2 = last.surr1.iter().zip(&last.surr2).filter(|(a, b)| b < a).count();
let kept_surr1 = last.surr1.iter().zip(&last.surr2).filter(|(a, b)| a < b).count();
println!("min(surr1, surr2) picked surr2 on {picked_surr2} of {} rows", last.surr1.len());
println!("on {kept_surr1} other rows the ratio left the band against its advantage: min kept surr1");
