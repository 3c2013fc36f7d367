//! notebooks/zh/06-adam.ipynb 的生成脚本，是 ../06-adam.rs 的中文版（代码相同，注释和打印的文字为中文）。

// %%
use ppo_engine::lesson::Snapshot;
use ppo_engine::notebook::snapshot;
use ppo_engine::ppo::{NamedWeights, PpoConfig, Trainer};
let config: PpoConfig = PpoConfig::default();
let snap: Snapshot = snapshot(config.clone(), 0, 30)?;

// %% step: Two optimizers, one per network
// %% step: What Adam does with a gradient
// 一个回合 = 一次更新 = 每个网络走 `epochs` 步 Adam。
let mut trainer: Trainer = Trainer::new(config.clone(), 0)?;
let before: NamedWeights = trainer.agent().weights()?;
trainer.next_episode()?;
let after: NamedWeights = trainer.agent().weights()?;

// %% step: Why a step is about the size of lr
// 无论梯度多大，Adam 每一步的步长都接近 lr：一次 `epochs` 步的更新之后，
// 没有哪个权重的变化明显超过 epochs × lr。
for (name, w) in &before {
    let moved = w.data.iter().zip(&after[name].data).map(|(a, b)| (a - b).abs()).fold(0.0_f32, f32::max);
    let lr = if name.starts_with("actor") { config.actor_lr } else { config.critic_lr };
    println!("{name:20} max |Δw| = {moved:.6}   epochs × lr = {:.6}", config.epochs as f64 * lr);
}

// %% step: Optimizer state lives for the whole run
