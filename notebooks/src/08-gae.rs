//! Recipe for notebooks/08-gae.ipynb (see 01-what-is-ppo.rs for the format).

// %%
use ppo_engine::lesson::{Snapshot, TensorView};
use ppo_engine::notebook::snapshot;
use ppo_engine::ppo::{PpoConfig, UpdateTrace};
let config: PpoConfig = PpoConfig::default();
let snap: Snapshot = snapshot(config.clone(), 0, 30)?;
let trace: UpdateTrace = snap.cartpole_update().expect("30 episodes were trained").trace.clone();

// %% step: From one-step errors to an advantage
// The weight (γλ)^l of the TD error l steps later in Â_t.
let gl = config.gamma * config.lmbda;
for l in [0, 1, 10, 30] {
    println!("l = {l:2}: (γλ)^l = {:.3}", gl.powi(l));
}

// %% step: λ between two extremes
// λ = 0: the advantage is the one-step TD error; λ = 1: the discounted sum of all of them
// (the library's GAE at both ends of the dial; your own `compute_advantage` comes below).
let lambda_0: Vec<f32> = ppo_engine::ppo::compute_advantage(config.gamma, 0.0, &trace.td_delta);
let lambda_1: Vec<f32> = ppo_engine::ppo::compute_advantage(config.gamma, 1.0, &trace.td_delta);
assert_eq!(lambda_0, trace.td_delta);
println!(
    "A_0 with λ = 0: {:.4}, λ = {}: {:.4}, λ = 1: {:.4}",
    lambda_0[0], config.lmbda, trace.advantage[0], lambda_1[0]
);

// %% step: Why the loop runs backwards
// %% step: The numpy detour, in float32
// %% step: Episode boundaries
// %% step: Advantage plus value: the λ-return, a second critic target
// check: lambda_return after 30 episodes
// CleanRL's `returns = advantages + values`: the seed's GAE plus V(s_t).
let lambda_return: Vec<f32> = trace.advantage.iter().zip(&trace.values).map(|(a, v)| a + v).collect();
let n = lambda_return.len();
println!("last row: λ-return {:.4}, TD target {:.4}", lambda_return[n - 1], trace.td_target[n - 1]);
println!("first row: λ-return {:.4}, TD target {:.4}", lambda_return[0], trace.td_target[0]);
TensorView::column("lambda_return", &lambda_return)

// %% exercise
