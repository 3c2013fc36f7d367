//! Recipe for notebooks/10-clipping.ipynb (see 01-what-is-ppo.rs for the format).

// %%
use ppo_tutor::lesson::{Snapshot, TensorView};
use ppo_tutor::notebook::snapshot;
use ppo_tutor::ppo::{EpochTrace, PpoConfig, UpdateTrace};
let config: PpoConfig = PpoConfig::default();
let snap: Snapshot = snapshot(config.clone(), 0, 30)?;
let trace: UpdateTrace = snap.trace.clone().expect("30 episodes were trained");
let last: EpochTrace = trace.epochs[trace.epochs.len() - 1].clone();

// %% step: Two surrogates
// check: surr1 after 30 episodes
let surr1: Vec<f32> = last.ratio.iter().zip(&trace.advantage).map(|(r, a)| r * a).collect();
TensorView::column("surr1", &surr1)

// %% step: The clamp: a band around 1
// check: surr2 after 30 episodes
let eps = config.eps as f32;
let surr2: Vec<f32> = last
    .ratio
    .iter()
    .zip(&trace.advantage)
    .map(|(r, a)| r.clamp(1.0 - eps, 1.0 + eps) * a)
    .collect();
TensorView::column("surr2", &surr2)

// %% step: Taking the minimum
// min picks surr2 only where surr2 < surr1: the ratio left the band in the direction its
// advantage favours. Where the ratio left it the other way, surr1 < surr2 and min keeps surr1.
let objective: Vec<f32> = surr1.iter().zip(&surr2).map(|(a, b)| a.min(*b)).collect();
let picked_surr2 = surr1.iter().zip(&surr2).filter(|(a, b)| b < a).count();
let kept_surr1 = surr1.iter().zip(&surr2).filter(|(a, b)| a < b).count();
println!("min(surr1, surr2) picked surr2 on {picked_surr2} of {} rows", objective.len());
println!("on {kept_surr1} other rows the ratio left the band against its advantage: min kept surr1");

// %% step: When the advantage is positive
// %% step: When the advantage is negative
// %% step: How much is being clipped
let clipped = last.ratio.iter().filter(|r| (**r - 1.0).abs() > eps).count();
println!("{clipped} of {} ratios are outside [1 − ε, 1 + ε]: clip_frac = {:.4}", last.ratio.len(), last.clip_fraction);

// %% exercise
