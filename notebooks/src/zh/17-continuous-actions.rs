//! notebooks/zh/17-continuous-actions.ipynb 的生成脚本，是 ../17-continuous-actions.rs 的中文版（代码相同，注释和打印的文字为中文）。

// %%
use ppo_engine::lesson::Snapshot;
use ppo_engine::notebook::snapshot;
use ppo_engine::ppo::{ContinuousUpdateTrace, PpoContinuousConfig};
fn range(r: &[f32]) -> (f32, f32) {
    r.iter().fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), &x| (lo.min(x), hi.max(x)))
}
// 书中的 PPOContinuous 以默认设置在 Pendulum-v1 上训练，随机种子 0：20 个回合，每个 200 步。
let config: PpoContinuousConfig = PpoContinuousConfig::default();
let snap: Snapshot = snapshot(config.clone(), 0, 20)?;
let trace: ContinuousUpdateTrace = snap.pendulum_update().expect("已训练 20 个回合").trace.clone();
println!("第 {} 个回合：{} 步，回报 {:.1}", snap.episodes, trace.actions.len(), snap.returns[19]);

// %% step: From two actions to a torque
// 两个压缩函数：2·tanh 让 μ 保持在 (−2, 2) 之内，softplus 让 σ 保持大于 0。
use ppo_engine::ppo::continuous::softplus_f32;
for x in [-20.0_f32, -5.0, 0.0, 5.0, 25.0] {
    println!("x = {x:>5}:  2·tanh(x) = {:+.6}   softplus(x) = {:.6}", 2.0 * x.tanh(), softplus_f32(x));
}
println!("σ 的 softplus 永远不会等于 0（除非 float32 把 e^x 舍入掉）；μ 的 2·tanh 永远到不了 ±2");

// %% step: Sampling a torque
// 最近一个回合的力矩如何分布在各自的 μ 周围，以 σ 为单位：
let z: Vec<f32> = trace.actions.iter().zip(&trace.mu).zip(&trace.std)
    .map(|((a, m), s)| (a - m) / s)
    .collect();
let within_1 = z.iter().filter(|v| v.abs() < 1.0).count();
let within_2 = z.iter().filter(|v| v.abs() < 2.0).count();
let outside = trace.actions.iter().filter(|a| a.abs() > 2.0).count();
println!("{within_1} 个力矩（共 {} 个）离 μ 不到一个 σ，{within_2} 个不到两个 σ", z.len());
println!("{outside} 个力矩在 [−2, 2] 之外：按采样值存储，由环境限幅");

// %% step: The log-density of a Normal
// 密度可以大于 1：这个批次中最大的对数密度，以及与它对应的 σ。
let (best, at) = trace.old_log_probs.iter().enumerate()
    .fold((f32::NEG_INFINITY, 0), |(b, i), (j, &v)| if v > b { (v, j) } else { (b, i) });
println!("最大的 old_log_prob 为 {best:.4}，在第 {at} 行，该行 σ = {:.4}", trace.std[at]);

// %% step: The ratio and the clip carry over unchanged
for (i, epoch) in trace.epochs.iter().enumerate() {
    let (lo, hi) = range(&epoch.ratio);
    println!("第 {:>2} 轮：比率在 [{lo:.5}, {hi:.5}] 之内", i + 1);
}
println!("第 1 轮评估的就是 π_old 本身；之后每一轮都比前一轮多走一步 Adam");

// %% step: Rescaled rewards and a short horizon
let (lo, hi) = range(&trace.scaled_rewards);
println!("最近一个回合缩放后的奖励在 [{lo:.4}, {hi:.4}] 之内");
println!("(r + 8) / 8 的两个极值：最差 {:.4}，最好 {:.4}", (-16.2736044_f64 + 8.0) / 8.0, (0.0_f64 + 8.0) / 8.0);
println!("γ = {}：视野 1/(1 − γ) = {:.1} 步；γ^20 = {:.4}", config.gamma, 1.0 / (1.0 - config.gamma), config.gamma.powi(20));

// %% exercise
