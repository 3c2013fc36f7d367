//! notebooks/zh/18-pendulum.ipynb 的生成脚本，是 ../18-pendulum.rs 的中文版（代码相同，注释和打印的文字为中文）。

// %%
use ppo_engine::lesson::{Session, Snapshot};
use ppo_engine::notebook::snapshot;
use ppo_engine::ppo::PpoContinuousConfig;
fn mean(r: &[f64]) -> f64 {
    r.iter().sum::<f64>() / r.len() as f64
}
// 书中的 PPOContinuous 以默认设置在 Pendulum-v1 上训练，随机种子 0，目前只训练了一个回合。
let config: PpoContinuousConfig = PpoContinuousConfig::default();
let snap: Snapshot = snapshot(config.clone(), 0, 1)?;
println!("第 1 个回合：回报 {:.1}", snap.returns[0]);

// %% step: The pendulum's physics
// 原生的 Pendulum-v1，从 reset(seed=0) 开始手动步进，不施加力矩：只有重力在起作用。
use ppo_engine::env::Pendulum;
let mut env = Pendulum::new();
let first: [f32; 3] = env.reset(Some(0));
println!("reset(seed=0): (cos θ, sin θ, θ̇) = {first:?}");
for step in 1..=5 {
    let s = env.step(0.0)?;
    println!("第 {step} 步：观测 {:?}，奖励 {:.4}", s.obs, s.reward);
}
println!("没有力矩时，杆从竖直位置附近倒下：θ̇ 越来越大，代价也随之增大");

// %% step: The cost, and why the rod must swing up
use ppo_engine::env::pendulum::cost;
use std::f64::consts::PI;
println!("静止下垂：代价 {:.4}", cost(PI, 0.0, 0.0));
println!("最坏情况：代价 {:.4}", cost(PI, 8.0, 2.0));
println!("最大力矩：6 rad/s²，对抗重力的 15·sin θ；电机只能在偏离竖直 {:.1}° 以内稳住杆", (0.4_f64).asin().to_degrees());

// %% step: The training run and its return curve
// 这里训练 300 个回合（书中训练 2000 个：在终端里运行 `ppo-tutor train --env Pendulum-v1`）。
let mut session = Session::new(config.clone(), 0)?;
let mut maps: Vec<(usize, Snapshot)> = Vec::new();
for episode in 1..=300 {
    let s = session.next_episode()?.expect("2000 个回合中的 300 个");
    if [1, 100, 300].contains(&episode) {
        maps.push((episode, s.clone()));
    }
}
let snap: Snapshot = session.into_snapshot();
println!("第 1-20 个回合的平均回报：{:.1}；第 281-300 个回合：{:.1}", mean(&snap.returns[..20]), mean(&snap.returns[280..]));

// %% step: The mean torque across the state space
// 随着训练进行，网格中心（竖直、静止）处的 μ，以及网格上最大的 |μ|：
for (episode, s) in &maps {
    let map = &s.pendulum_update().expect("倒立摆的快照带有策略图").policy_map;
    let biggest = map.mu.iter().fold(0.0_f32, |m, v| m.max(v.abs()));
    println!("第 {episode:>3} 个回合之后：竖直静止时 μ = {:+.4}，网格上最大的 |μ| = {biggest:.4}", map.mu[40]);
}
// 第 300 个回合之后的策略图，画成图片（下面的表格里是同样的数）：
ppo_engine::notebook::policy_map_svg(&snap.pendulum_update().expect("倒立摆的快照带有策略图").policy_map)

// %% step: The spread σ as training goes on
for (episode, s) in &maps {
    let map = &s.pendulum_update().expect("倒立摆的快照带有策略图").policy_map;
    let mean_std = map.std.iter().sum::<f32>() / map.std.len() as f32;
    println!("第 {episode:>3} 个回合之后：网格上 σ 的均值 = {mean_std:.4}");
}
println!("（书中完整训练 2000 个回合会让它变小：在终端里运行 `ppo-tutor train --env Pendulum-v1`）");
