//! notebooks/zh/08-gae.ipynb 的生成脚本，是 ../08-gae.rs 的中文版（代码相同，注释和打印的文字为中文）。

// %%
use ppo_engine::lesson::{Snapshot, TensorView};
use ppo_engine::notebook::snapshot;
use ppo_engine::ppo::{PpoConfig, UpdateTrace};
let config: PpoConfig = PpoConfig::default();
let snap: Snapshot = snapshot(config.clone(), 0, 30)?;
let trace: UpdateTrace = snap.cartpole_update().expect("已训练 30 个回合").trace.clone();

// %% step: From one-step errors to an advantage
// Â_t 中 l 步之后那个 TD 误差的权重 (γλ)^l。
let gl = config.gamma * config.lmbda;
for l in [0, 1, 10, 30] {
    println!("l = {l:2}: (γλ)^l = {:.3}", gl.powi(l));
}

// %% step: λ between two extremes
// λ = 0：优势值就是一步的 TD 误差；λ = 1：所有 TD 误差的折扣和
// （这是库里的 GAE 在旋钮两端的结果；你自己的 `compute_advantage` 在后面）。
let lambda_0: Vec<f32> = ppo_engine::ppo::compute_advantage(config.gamma, 0.0, &trace.td_delta);
let lambda_1: Vec<f32> = ppo_engine::ppo::compute_advantage(config.gamma, 1.0, &trace.td_delta);
assert_eq!(lambda_0, trace.td_delta);
println!(
    "A_0：λ = 0 时为 {:.4}，λ = {} 时为 {:.4}，λ = 1 时为 {:.4}",
    lambda_0[0], config.lmbda, trace.advantage[0], lambda_1[0]
);

// %% step: Why the loop runs backwards
// %% step: The numpy detour, in float32
// %% step: Episode boundaries
// %% step: Advantage plus value: the λ-return, a second critic target
// check: lambda_return after 30 episodes
// CleanRL 的 `returns = advantages + values`：原教程代码的 GAE 加上 V(s_t)。
let lambda_return: Vec<f32> = trace.advantage.iter().zip(&trace.values).map(|(a, v)| a + v).collect();
let n = lambda_return.len();
println!("最后一行：λ-回报 {:.4}，TD 目标 {:.4}", lambda_return[n - 1], trace.td_target[n - 1]);
println!("第一行：λ-回报 {:.4}，TD 目标 {:.4}", lambda_return[0], trace.td_target[0]);
TensorView::column("lambda_return", &lambda_return)

// %% exercise
