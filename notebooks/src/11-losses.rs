//! Recipe for notebooks/11-losses.ipynb (see 01-what-is-ppo.rs for the format).

// %%
use ppo_tutor::lesson::{Snapshot, TensorView};
use ppo_tutor::notebook::snapshot;
use ppo_tutor::ppo::{EpochTrace, PpoConfig, UpdateTrace};
let config: PpoConfig = PpoConfig::default();
let snap: Snapshot = snapshot(config.clone(), 0, 30)?;
let trace: UpdateTrace = snap.trace.clone().expect("30 episodes were trained");
let first: EpochTrace = trace.epochs[0].clone();

// %% step: The actor loss
// In the first epoch every ratio is 1, so the actor loss is minus the mean advantage.
let n = trace.advantage.len() as f32;
let minus_mean_adv = -trace.advantage.iter().sum::<f32>() / n;
println!("epoch 1 actor loss {:.6}, −mean(advantage) {:.6}", first.actor_loss, minus_mean_adv);
assert!((first.actor_loss - minus_mean_adv).abs() < 1e-4 * (1.0 + minus_mean_adv.abs()));

// %% step: The critic loss
// In the first epoch V(s_t) − y_t = −δ_t, so the critic loss is the mean squared TD error.
let mse = trace.td_delta.iter().map(|d| d * d).sum::<f32>() / n;
println!("epoch 1 critic loss {:.6}, mean(td_delta²) {:.6}", first.critic_loss, mse);
assert!((first.critic_loss - mse).abs() < 1e-4 * (1.0 + mse));

// %% step: Why the target is detached
// %% step: zero_grad, backward, step
// %% step: Ten epochs on the same batch
for (k, e) in trace.epochs.iter().enumerate() {
    println!("epoch {:2}: actor_loss {:+.5}  critic_loss {:.5}", k + 1, e.actor_loss, e.critic_loss);
}

// %% exercise
