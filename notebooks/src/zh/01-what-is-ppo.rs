//! notebooks/zh/01-what-is-ppo.ipynb 的生成脚本，是 ../01-what-is-ppo.rs 的中文版（代码相同，注释和打印的文字为中文）。
//! 格式：`// %%` 行之间是代码单元格；markdown、实时数值单元格和练习来自 lessons/01-what-is-ppo。
//! 重新生成：cargo run --features notebook-runner -- --lang zh dev notebooks 01

// %%
use ppo_engine::lesson::Snapshot;
use ppo_engine::notebook::snapshot;
use ppo_engine::ppo::{EpochTrace, PpoConfig, UpdateTrace};
// 原教程代码的设置，随机种子 0；训练 100 个回合（大约一秒）。
let config: PpoConfig = PpoConfig::default();
let snap: Snapshot = snapshot(config.clone(), 0, 100)?;
let trace: UpdateTrace = snap.cartpole_update().expect("已训练 100 个回合").trace.clone();
println!("第 {} 个回合持续了 {} 步", snap.episodes, trace.rewards.len());

// %% step: A policy that learns from its own play
// 作为对照，在原生的 CartPole-v1 上手写一个策略：
// 杆往哪边倾斜，就把小车往哪边推。
use ppo_engine::env::{CartPole, EnvId};
let mut env = CartPole::new(EnvId::CartPoleV1);
let mut obs: [f32; 4] = env.reset(Some(0));
let mut steps: usize = 0;
loop {
    let action = if obs[2] > 0.0 { 1 } else { 0 };
    let step = env.step(action)?;
    obs = step.obs;
    steps += 1;
    if step.terminated || step.truncated {
        break;
    }
}
println!("手写策略让杆保持平衡了 {steps} 步");
println!("训练 {} 个回合后，PPO 最后五个回合的回报：{:?}", snap.episodes, &snap.returns[95..]);

// %% step: The policy gradient
// 最近一个回合前几步的 π(·|s_t)，以及采样到的动作。
for (t, p) in snap.cartpole_update().expect("一次训练过的 CartPole 运行").probs.iter().take(5).enumerate() {
    println!("s_{t}: π(left) = {:.4}  π(right) = {:.4}  采样到的动作：{}", p[0], p[1], trace.actions[t]);
}

// %% step: Reusing a batch: the importance ratio
fn max_distance_from_one(ratio: &[f32]) -> f32 {
    ratio.iter().map(|r| (r - 1.0).abs()).fold(0.0, f32::max)
}
let first: EpochTrace = trace.epochs[0].clone();
let last: EpochTrace = trace.epochs[trace.epochs.len() - 1].clone();
println!("第  1 轮：max |ratio - 1| = {:.6}", max_distance_from_one(&first.ratio));
println!("第 {} 轮：max |ratio - 1| = {:.6}", trace.epochs.len(), max_distance_from_one(&last.ratio));

// %% step: The clipped surrogate
// %% step: Where the advantage comes from: GAE
// 用库里的 GAE 处理这个回合的 TD 误差，得到的正好是这次更新所用的优势值。
let advantage: Vec<f32> = ppo_engine::ppo::compute_advantage(config.gamma, config.lmbda, &trace.td_delta);
assert_eq!(advantage, trace.advantage);
println!("共 {} 个优势值，第一个为 {:.4}，最后一个为 {:.4}", advantage.len(), advantage[0], advantage[advantage.len() - 1]);

// %% step: The whole loop at a glance
