//! Recipe for notebooks/17-continuous-actions.ipynb (see 01-what-is-ppo.rs for the format).

// %%
use ppo_engine::lesson::Snapshot;
use ppo_engine::notebook::snapshot;
use ppo_engine::ppo::{ContinuousUpdateTrace, PpoContinuousConfig};
fn range(r: &[f32]) -> (f32, f32) {
    r.iter().fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), &x| (lo.min(x), hi.max(x)))
}
// The book's PPOContinuous on Pendulum-v1 with its defaults, seed 0: 20 episodes of 200 steps.
let config: PpoContinuousConfig = PpoContinuousConfig::default();
let snap: Snapshot = snapshot(config.clone(), 0, 20)?;
let trace: ContinuousUpdateTrace = snap.pendulum_update().expect("20 episodes were trained").trace.clone();
println!("episode {}: {} steps, return {:.1}", snap.episodes, trace.actions.len(), snap.returns[19]);

// %% step: From two actions to a torque
// The two squashing functions: 2·tanh keeps μ inside (−2, 2), softplus keeps σ above 0.
use ppo_engine::ppo::continuous::softplus_f32;
for x in [-20.0_f32, -5.0, 0.0, 5.0, 25.0] {
    println!("x = {x:>5}:  2·tanh(x) = {:+.6}   softplus(x) = {:.6}", 2.0 * x.tanh(), softplus_f32(x));
}
println!("σ's softplus never reaches 0 (until float32 rounds e^x away); μ's 2·tanh never reaches ±2");

// %% step: Sampling a torque
// How the latest episode's torques fell around their μ, in units of σ:
let z: Vec<f32> = trace.actions.iter().zip(&trace.mu).zip(&trace.std)
    .map(|((a, m), s)| (a - m) / s)
    .collect();
let within_1 = z.iter().filter(|v| v.abs() < 1.0).count();
let within_2 = z.iter().filter(|v| v.abs() < 2.0).count();
let outside = trace.actions.iter().filter(|a| a.abs() > 2.0).count();
println!("{within_1} of {} torques within one σ of μ, {within_2} within two", z.len());
println!("{outside} torques outside [−2, 2]: stored as drawn, clipped by the environment");

// %% step: The log-density of a Normal
// A density can exceed 1: the largest log-density of the batch, and the σ it came with.
let (best, at) = trace.old_log_probs.iter().enumerate()
    .fold((f32::NEG_INFINITY, 0), |(b, i), (j, &v)| if v > b { (v, j) } else { (b, i) });
println!("largest old_log_prob {best:.4} at row {at}, where σ = {:.4}", trace.std[at]);

// %% step: The ratio and the clip carry over unchanged
for (i, epoch) in trace.epochs.iter().enumerate() {
    let (lo, hi) = range(&epoch.ratio);
    println!("epoch {:>2}: ratio in [{lo:.5}, {hi:.5}]", i + 1);
}
println!("epoch 1 evaluates π_old itself; each later epoch follows one more Adam step");

// %% step: Rescaled rewards and a short horizon
let (lo, hi) = range(&trace.scaled_rewards);
println!("scaled rewards of the latest episode in [{lo:.4}, {hi:.4}]");
println!("the extremes of (r + 8) / 8: worst {:.4}, best {:.4}", (-16.2736044_f64 + 8.0) / 8.0, (0.0_f64 + 8.0) / 8.0);
println!("γ = {}: horizon 1/(1 − γ) = {:.1} steps; γ^20 = {:.4}", config.gamma, 1.0 / (1.0 - config.gamma), config.gamma.powi(20));

// %% exercise
