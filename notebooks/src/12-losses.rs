//! Recipe for notebooks/12-losses.ipynb (see 01-what-is-ppo.rs for the format).

// %%
use ppo_engine::lesson::{Snapshot, TensorView};
use ppo_engine::notebook::snapshot;
use ppo_engine::ppo::{EpochTrace, PpoConfig, UpdateTrace};
let config: PpoConfig = PpoConfig::default();
let snap: Snapshot = snapshot(config.clone(), 0, 30)?;
let trace: UpdateTrace = snap.cartpole_update().expect("30 episodes were trained").trace.clone();
let first: EpochTrace = trace.epochs[0].clone();

// %% step: The actor loss
// In the first epoch every ratio is 1, so the actor loss is minus the mean advantage.
let n = trace.advantage.len() as f32;
let minus_mean_adv = -trace.advantage.iter().sum::<f32>() / n;
println!("epoch 1 actor loss {:.6}, −mean(advantage) {:.6}", first.actor_loss, minus_mean_adv);
assert!((first.actor_loss - minus_mean_adv).abs() < 1e-4 * (1.0 + minus_mean_adv.abs()));

// %% step: The critic loss
// %% step: Why the target is detached
// %% step: zero_grad, backward, step
// %% step: Ten epochs on the same batch
// An arrow marks an epoch whose critic loss rose: Adam's steps of about critic_lr overshoot.
for (k, e) in trace.epochs.iter().enumerate() {
    let rose = k > 0 && e.critic_loss > trace.epochs[k - 1].critic_loss;
    let arrow = if rose { "  ↑" } else { "" };
    println!("epoch {:2}: actor_loss {:+.5}  critic_loss {:.5}{arrow}", k + 1, e.actor_loss, e.critic_loss);
}
fn rises(t: &UpdateTrace) -> usize {
    t.epochs.windows(2).filter(|w| w[1].critic_loss > w[0].critic_loss).count()
}
// The same 30 episodes with a critic_lr ten times smaller (a different run, so a different
// last episode): fewer rises.
let slow_config = PpoConfig { critic_lr: 1e-3, ..PpoConfig::default() };
let slow: UpdateTrace = snapshot(slow_config, 0, 30)?.cartpole_update().expect("30 episodes were trained").trace.clone();
println!("critic_loss rose in {} of {} epoch steps at critic_lr 1e-2, in {} at 1e-3", rises(&trace), trace.epochs.len() - 1, rises(&slow));
// The clip does not bound the ratio: after the tenth epoch some ratios are outside the band.
let eps = config.eps as f32;
let last: EpochTrace = trace.epochs[trace.epochs.len() - 1].clone();
let outside = last.clipped.iter().filter(|c| **c).count();
let lowest = last.ratio.iter().copied().fold(f32::INFINITY, f32::min);
let highest = last.ratio.iter().copied().fold(f32::NEG_INFINITY, f32::max);
println!("after epoch 10: {} of {} ratios outside [{:.1}, {:.1}]; ratios range from {lowest:.3} to {highest:.3}",
    outside, last.ratio.len(), 1.0 - eps, 1.0 + eps);

// %% exercise
// Back to "The critic loss", now that the exercises are graded: in the first epoch
// V(s_t) − y_t = −δ_t, so the critic loss is the mean squared TD error.
let mse = trace.td_delta.iter().map(|d| d * d).sum::<f32>() / n;
println!("epoch 1 critic loss {:.6}, mean(td_delta²) {:.6}", first.critic_loss, mse);
assert!((first.critic_loss - mse).abs() < 1e-4 * (1.0 + mse));
