//! notebooks/zh/15-hyperparameters.ipynb 的生成脚本，是 ../15-hyperparameters.rs 的中文版（代码相同，注释和打印的文字为中文）。
//! 每个旋钮的实验要在所有 CPU 核心上跑 5 到 15 次、每次 500 个回合的训练（需要一分钟或更久）。

// %%
use ppo_engine::lesson::Snapshot;
use ppo_engine::notebook::snapshot;
use ppo_engine::ppo::PpoConfig;
const LAB_EPISODES: usize = 500;
let config: PpoConfig = PpoConfig::default();
let snap: Snapshot = snapshot(config.clone(), 0, 100)?;

// %% step: Where the numbers live
// 原教程代码的超参数就是 PpoConfig 的默认值：
println!("{config:#?}");

// %% step: critic_lr: a ten times smaller critic step
println!(
    "critic_lr = {}（原教程代码的值），实验改成 {}，即策略网络自己的学习率 {}",
    config.critic_lr,
    config.critic_lr / 10.0,
    config.actor_lr
);

// %% step: hidden_dim: 16 units instead of 128
// 两个网络的参数量：4 -> hidden_dim -> 2 和 4 -> hidden_dim -> 1。
for h in [config.hidden_dim, 16] {
    let actor = 4 * h + h + h * 2 + 2;
    let critic = 4 * h + h + h + 1;
    println!("hidden_dim = {h:3}：策略网络 {actor} 个参数，价值网络 {critic} 个");
}

// %% step: gamma: a horizon of 10, 50 or 1000 steps
for gamma in [0.9, config.gamma, 0.999] {
    println!("γ = {gamma}：视野 1/(1 − γ) = {:.0} 步", 1.0 / (1.0 - gamma));
}

// %% step: lmbda: how far GAE trusts the critic
// l 步之后的 TD 误差权重为 (γλ)^l：权重每 ln 0.5 / ln(γλ) 步减半。
for lmbda in [0.5, config.lmbda, 1.0] {
    let gl = config.gamma * lmbda;
    println!("λ = {lmbda}：γλ = {gl:.3}，权重每 {:.1} 步减半", 0.5f64.ln() / gl.ln());
}

// %% step: The rest: what lesson 13 measured, and the task
use ppo_engine::env::EnvId;
for id in EnvId::ALL {
    println!("{}：回合到 {} 步时因时限中断", id.as_str(), id.max_episode_steps());
}
