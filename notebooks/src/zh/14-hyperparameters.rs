//! notebooks/zh/14-hyperparameters.ipynb 的生成脚本，是 ../14-hyperparameters.rs 的中文版（代码相同，注释和打印的文字为中文）。

// %%
use ppo_engine::lesson::Snapshot;
use ppo_engine::notebook::snapshot;
use ppo_engine::ppo::PpoConfig;
let config: PpoConfig = PpoConfig::default();
let snap: Snapshot = snapshot(config.clone(), 0, 100)?;

// %% step: Where the numbers live
// 原教程代码的超参数就是 PpoConfig 的默认值：
println!("{config:#?}");

// %% step: Two learning rates: actor_lr and critic_lr
println!(
    "actor_lr = {}，critic_lr = {}：价值网络的步长是策略网络的 {} 倍",
    config.actor_lr,
    config.critic_lr,
    config.critic_lr / config.actor_lr
);

// %% step: How long and how wide: num_episodes and hidden_dim
// 两个网络的参数量：4 -> hidden_dim -> 2 和 4 -> hidden_dim -> 1。
let h = config.hidden_dim;
let actor = 4 * h + h + h * 2 + 2;
let critic = 4 * h + h + h + 1;
println!("策略网络：{actor} 个参数，价值网络：{critic} 个，训练 {} 个回合", config.num_episodes);

// %% step: Looking ahead: gamma and lmbda
let gl = config.gamma * config.lmbda;
println!("γ = {}，λ = {}，γλ = {gl:.4}：k 步之后的 TD 误差权重为 γλ^k", config.gamma, config.lmbda);
for k in [1, 10, 50, 100] {
    println!("  k = {k:3}: γλ^k = {:.4}", gl.powi(k));
}

// %% step: Reuse and restraint: epochs and eps
println!(
    "每个回合的数据用于 {} 步梯度更新；比率被截断到 [{}, {}]",
    config.epochs,
    1.0 - config.eps,
    1.0 + config.eps
);

// %% step: The task: CartPole-v1
use ppo_engine::env::EnvId;
for id in EnvId::ALL {
    println!("{}：回合到 {} 步时因时限中断", id.as_str(), id.max_episode_steps());
}
