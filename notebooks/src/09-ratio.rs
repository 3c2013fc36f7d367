//! Recipe for notebooks/09-ratio.ipynb (see 01-what-is-ppo.rs for the format).

// %%
use ppo_tutor::lesson::{Snapshot, TensorView};
use ppo_tutor::notebook::snapshot;
use ppo_tutor::ppo::{EpochTrace, PpoConfig, UpdateTrace};
let config: PpoConfig = PpoConfig::default();
let snap: Snapshot = snapshot(config.clone(), 0, 30)?;
let trace: UpdateTrace = snap.trace.clone().expect("30 episodes were trained");

// %% step: Log-probability of the action taken
// check: old_log_probs after 30 episodes
// gather the probability of the action taken, then log: π_old(a_t|s_t).
let old_log_probs: Vec<f32> = snap.probs.iter().zip(&trace.actions).map(|(p, &a)| p[a].ln()).collect();
TensorView::column("old_log_probs", &old_log_probs)

// %% step: Why old_log_probs is detached
// %% step: The ratio
// check: ratio after 30 episodes
// ratio = exp(log π_θ − log π_θ_old), in the last of the ten epochs.
let last: EpochTrace = trace.epochs[trace.epochs.len() - 1].clone();
let ratios: Vec<f32> = last.log_probs.iter().zip(&trace.old_log_probs).map(|(l, o)| (l - o).exp()).collect();
TensorView::column("ratio", &ratios)

// %% step: Exactly 1 in the first epoch
let first: EpochTrace = trace.epochs[0].clone();
assert!(first.ratio.iter().all(|&r| r == 1.0));
println!("epoch 1: all {} ratios are exactly 1", first.ratio.len());

// %% step: Later epochs: the ratio drifts
for (k, e) in trace.epochs.iter().enumerate() {
    let spread = e.ratio.iter().map(|r| (r - 1.0).abs()).fold(0.0_f32, f32::max);
    println!("epoch {:2}: max |ratio − 1| = {spread:.5}, approx_kl = {:.2e}", k + 1, e.approx_kl);
}

// %% exercise
