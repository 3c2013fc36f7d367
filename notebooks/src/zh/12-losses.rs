//! notebooks/zh/12-losses.ipynb 的生成脚本，是 ../12-losses.rs 的中文版（代码相同，注释和打印的文字为中文）。

// %%
use ppo_engine::lesson::{Snapshot, TensorView};
use ppo_engine::notebook::snapshot;
use ppo_engine::ppo::{EpochTrace, PpoConfig, UpdateTrace};
let config: PpoConfig = PpoConfig::default();
let snap: Snapshot = snapshot(config.clone(), 0, 30)?;
let trace: UpdateTrace = snap.cartpole_update().expect("已训练 30 个回合").trace.clone();
let first: EpochTrace = trace.epochs[0].clone();

// %% step: The actor loss
// 第一轮中每个比率都是 1，所以策略网络的损失就是优势值均值的相反数。
let n = trace.advantage.len() as f32;
let minus_mean_adv = -trace.advantage.iter().sum::<f32>() / n;
println!("第 1 轮策略网络损失 {:.6}，−mean(advantage) {:.6}", first.actor_loss, minus_mean_adv);
assert!((first.actor_loss - minus_mean_adv).abs() < 1e-4 * (1.0 + minus_mean_adv.abs()));

// %% step: The critic loss
// %% step: Why the target is detached
// %% step: zero_grad, backward, step
// %% step: Ten epochs on the same batch
// 箭头标出价值网络损失上升的轮次：Adam 每步约 critic_lr 的步长冲过了头。
for (k, e) in trace.epochs.iter().enumerate() {
    let rose = k > 0 && e.critic_loss > trace.epochs[k - 1].critic_loss;
    let arrow = if rose { "  ↑" } else { "" };
    println!("第 {:2} 轮：actor_loss {:+.5}  critic_loss {:.5}{arrow}", k + 1, e.actor_loss, e.critic_loss);
}
fn rises(t: &UpdateTrace) -> usize {
    t.epochs.windows(2).filter(|w| w[1].critic_loss > w[0].critic_loss).count()
}
// 同样训练 30 个回合，但 critic_lr 小十倍（这是另一次运行，所以最后一个回合也不同）：
// 上升的次数更少。
let slow_config = PpoConfig { critic_lr: 1e-3, ..PpoConfig::default() };
let slow: UpdateTrace = snapshot(slow_config, 0, 30)?.cartpole_update().expect("已训练 30 个回合").trace.clone();
println!("critic_lr 为 1e-2 时 critic_loss 上升了 {} 次（共 {} 次轮间变化），为 1e-3 时上升了 {} 次", rises(&trace), trace.epochs.len() - 1, rises(&slow));
// 截断并不限制比率本身：第十轮之后，有些比率落在区间之外。
let eps = config.eps as f32;
let last: EpochTrace = trace.epochs[trace.epochs.len() - 1].clone();
let outside = last.clipped.iter().filter(|c| **c).count();
let lowest = last.ratio.iter().copied().fold(f32::INFINITY, f32::min);
let highest = last.ratio.iter().copied().fold(f32::NEG_INFINITY, f32::max);
println!("第 10 轮之后：{} 个比率（共 {} 个）落在 [{:.1}, {:.1}] 之外；比率的范围从 {lowest:.3} 到 {highest:.3}",
    outside, last.ratio.len(), 1.0 - eps, 1.0 + eps);

// %% exercise
// 练习已经评分，现在回到“价值网络的损失”一节：第一轮中
// V(s_t) − y_t = −δ_t，所以价值网络的损失就是 TD 误差平方的均值。
let mse = trace.td_delta.iter().map(|d| d * d).sum::<f32>() / n;
println!("第 1 轮价值网络损失 {:.6}，mean(td_delta²) {:.6}", first.critic_loss, mse);
assert!((first.critic_loss - mse).abs() < 1e-4 * (1.0 + mse));
