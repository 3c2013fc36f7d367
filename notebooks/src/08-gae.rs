//! Recipe for notebooks/08-gae.ipynb (see 01-what-is-ppo.rs for the format).

// %%
use ppo_tutor::lesson::{Snapshot, TensorView};
use ppo_tutor::notebook::snapshot;
use ppo_tutor::ppo::{PpoConfig, UpdateTrace};
let config: PpoConfig = PpoConfig::default();
let snap: Snapshot = snapshot(config.clone(), 0, 30)?;
let trace: UpdateTrace = snap.trace.clone().expect("30 episodes were trained");

// %% step: From one-step errors to an advantage
// check: advantage after 30 episodes
// advantage_t = td_delta_t + γλ · advantage_{t+1}, backwards, in float32 as numpy does.
let gl = (config.gamma * config.lmbda) as f32;
let mut advantage = vec![0.0_f32; trace.td_delta.len()];
let mut running = 0.0_f32;
for t in (0..trace.td_delta.len()).rev() {
    running = gl * running + trace.td_delta[t];
    advantage[t] = running;
}
TensorView::column("advantage", &advantage)

// %% step: λ between two extremes
// λ = 0: the advantage is the one-step TD error; λ = 1: the discounted sum of all of them.
let gamma = config.gamma as f32;
let lambda_0: Vec<f32> = trace.td_delta.clone();
let mut lambda_1 = vec![0.0_f32; trace.td_delta.len()];
let mut acc = 0.0_f32;
for t in (0..trace.td_delta.len()).rev() {
    acc = gamma * acc + trace.td_delta[t];
    lambda_1[t] = acc;
}
println!("A_0 with λ = 0: {:.4}, λ = {}: {:.4}, λ = 1: {:.4}", lambda_0[0], config.lmbda, advantage[0], lambda_1[0]);

// %% step: Why the loop runs backwards
// %% step: The numpy detour, in float32
// %% step: Episode boundaries
// %% step: Advantage plus value: the λ-return, a second critic target
// check: lambda_return after 30 episodes
// CleanRL's `returns = advantages + values`: the seed's GAE plus V(s_t).
let lambda_return: Vec<f32> = advantage.iter().zip(&trace.values).map(|(a, v)| a + v).collect();
let n = lambda_return.len();
println!("last row: λ-return {:.4}, TD target {:.4}", lambda_return[n - 1], trace.td_target[n - 1]);
println!("first row: λ-return {:.4}, TD target {:.4}", lambda_return[0], trace.td_target[0]);
TensorView::column("lambda_return", &lambda_return)

// %% exercise
