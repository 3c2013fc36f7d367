//! Recipe for notebooks/13-clip-lab.ipynb (see 01-what-is-ppo.rs for the format).
//! Each experiment trains 10 to 15 runs of 500 episodes on every core (a minute or more).

// %%
use ppo_engine::lesson::Snapshot;
use ppo_engine::notebook::snapshot;
use ppo_engine::ppo::{EpochTrace, PpoConfig, UpdateTrace};
const LAB_EPISODES: usize = 500;
let config: PpoConfig = PpoConfig::default();
let snap: Snapshot = snapshot(config.clone(), 0, 100)?;
let trace: UpdateTrace = snap.cartpole_update().expect("100 episodes were trained").trace.clone();

// %% step: What to watch in every update
// The latest update, epoch by epoch: what the diagnostics are made of.
println!("epoch  approx_kl  clip_frac  ratio min  ratio max  entropy");
for (k, e) in trace.epochs.iter().enumerate() {
    let lo = e.ratio.iter().copied().fold(f32::INFINITY, f32::min);
    let hi = e.ratio.iter().copied().fold(f32::NEG_INFINITY, f32::max);
    println!("{:5}  {:9.5}  {:9.4}  {:9.4}  {:9.4}  {:7.4}", k + 1, e.approx_kl, e.clip_fraction, lo, hi, e.entropy);
}
println!("explained variance before the update: {:?}", trace.explained_variance);

// %% step: Experiment 1: the clip range
// %% step: Experiment 2: how many epochs
// %% step: Experiment 3: a ten times larger actor step
// %% step: Experiment 4: stopping early at a target KL
// %% step: What the clip promises, and what it does not
// The last epoch: the rows marked clipped are the ratios outside [1 − ε, 1 + ε].
let last: EpochTrace = trace.epochs[trace.epochs.len() - 1].clone();
let eps = config.eps as f32;
let marked = last.clipped.iter().filter(|c| **c).count();
let lo = last.ratio.iter().copied().fold(f32::INFINITY, f32::min);
let hi = last.ratio.iter().copied().fold(f32::NEG_INFINITY, f32::max);
println!(
    "last epoch: ratios from {lo:.4} to {hi:.4}; {marked} of {} rows outside [{}, {}], marked clipped",
    last.ratio.len(),
    1.0 - eps,
    1.0 + eps
);

// %% exercise
