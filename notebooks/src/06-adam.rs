//! Recipe for notebooks/06-adam.ipynb (see 01-what-is-ppo.rs for the format).

// %%
use ppo_engine::lesson::Snapshot;
use ppo_engine::notebook::snapshot;
use ppo_engine::ppo::{NamedWeights, PpoConfig, Trainer};
let config: PpoConfig = PpoConfig::default();
let snap: Snapshot = snapshot(config.clone(), 0, 30)?;

// %% step: Two optimizers, one per network
// %% step: What Adam does with a gradient
// One episode = one update = `epochs` Adam steps on each network.
let mut trainer: Trainer = Trainer::new(config.clone(), 0)?;
let before: NamedWeights = trainer.agent().weights()?;
trainer.next_episode()?;
let after: NamedWeights = trainer.agent().weights()?;

// %% step: Why a step is about the size of lr
// Adam's step is close to lr whatever the gradient's size: after one update of
// `epochs` steps no weight has moved much more than epochs × lr.
for (name, w) in &before {
    let moved = w.data.iter().zip(&after[name].data).map(|(a, b)| (a - b).abs()).fold(0.0_f32, f32::max);
    let lr = if name.starts_with("actor") { config.actor_lr } else { config.critic_lr };
    println!("{name:20} max |Δw| = {moved:.6}   epochs × lr = {:.6}", config.epochs as f64 * lr);
}

// %% step: Optimizer state lives for the whole run
