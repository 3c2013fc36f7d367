//! Recipe for notebooks/09-ratio.ipynb (see 01-what-is-ppo.rs for the format).

// %%
use ppo_engine::lesson::Snapshot;
use ppo_engine::notebook::snapshot;
use ppo_engine::ppo::{EpochTrace, PpoConfig, UpdateTrace};
let config: PpoConfig = PpoConfig::default();
let snap: Snapshot = snapshot(config.clone(), 0, 30)?;
let trace: UpdateTrace = snap.cartpole_update().expect("30 episodes were trained").trace.clone();

// %% step: Log-probability of the action taken
// Row 0: the action picks a column of probs; old_log_probs is the log of that entry, so its
// exponential gives the entry back.
println!(
    "probs {:?}, action {}: old_log_prob {:.6}, exp(old_log_prob) = {:.6}",
    snap.cartpole_update().expect("a trained CartPole run").probs[0],
    trace.actions[0],
    trace.old_log_probs[0],
    trace.old_log_probs[0].exp()
);

// %% step: Why old_log_probs is detached
// %% step: The ratio
// The last of the ten epochs, first rows: ln(ratio) is log_probs − old_log_probs.
let last: EpochTrace = trace.epochs[trace.epochs.len() - 1].clone();
println!("row   log_probs  old_log_probs     ratio  ln(ratio)");
for t in 0..3 {
    println!(
        "{t:3}  {:10.6}  {:13.6}  {:8.6}  {:9.6}",
        last.log_probs[t], trace.old_log_probs[t], last.ratio[t], last.ratio[t].ln()
    );
}

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
