//! notebooks/zh/16-beyond-the-seed.ipynb 的生成脚本，是 ../16-beyond-the-seed.rs 的中文版（代码相同，注释和打印的文字为中文）。

// %%
use ppo_engine::lesson::Snapshot;
use ppo_engine::notebook::snapshot;
use ppo_engine::ppo::PpoConfig;
fn mean_last(returns: &[f64], k: usize) -> f64 {
    returns[returns.len() - k..].iter().sum::<f64>() / k as f64
}
// 原教程代码原样运行：300 个回合，随机种子 0。
let config: PpoConfig = PpoConfig::default();
let snap: Snapshot = snapshot(config.clone(), 0, 300)?;
println!("原教程代码：最后 50 个回报的均值 = {:.1}", mean_last(&snap.returns, 50));

// %% step: Truncation is not termination
// 修正只需打开一个开关：回合因时限中断时，用 V(s') 自举。
let fixed: Snapshot = snapshot(PpoConfig { bootstrap_on_truncation: true, ..config.clone() }, 0, 300)?;
println!("bootstrap_on_truncation：最后 50 个回报的均值 = {:.1}", mean_last(&fixed.returns, 50));

// %% step: Advantages are not normalised
let normalised: Snapshot = snapshot(PpoConfig { normalize_advantage: true, ..config.clone() }, 0, 300)?;
println!("normalize_advantage：最后 50 个回报的均值 = {:.1}", mean_last(&normalised.returns, 50));

// %% step: CartPole-v0 or CartPole-v1
use ppo_engine::env::EnvId;
let v0: Snapshot = snapshot(PpoConfig { env_id: EnvId::CartPoleV0, ..config.clone() }, 0, 300)?;
let best = v0.returns.iter().copied().fold(0.0, f64::max);
println!("CartPole-v0：没有超过 {best} 的回报（时间上限是 200 步）");

// %% step: Rollouts, vector environments and minibatches
// %% step: Entropy bonus and gradient-norm clipping
// %% step: Value clipping, orthogonal init, learning-rate annealing

// %% exercise
