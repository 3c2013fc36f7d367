//! notebooks/zh/07-td-target.ipynb 的生成脚本，是 ../07-td-target.rs 的中文版（代码相同，注释和打印的文字为中文）。

// %%
use ppo_engine::lesson::Snapshot;
use ppo_engine::notebook::snapshot;
use ppo_engine::ppo::{PpoConfig, UpdateTrace};
let config: PpoConfig = PpoConfig::default();
let snap: Snapshot = snapshot(config.clone(), 0, 30)?;
let trace: UpdateTrace = snap.cartpole_update().expect("已训练 30 个回合").trace.clone();
println!("第 {} 个回合持续了 {} 步", snap.episodes, trace.rewards.len());

// %% step: What the critic is for
// %% step: The TD target
// %% step: Why multiply by (1 − done)
let last = trace.rewards.len() - 1;
println!(
    "最后一步：done = {}，V(s') = {:.4}，td_target = {:.4}，即奖励本身",
    trace.dones[last], trace.next_values[last], trace.td_target[last]
);

// %% step: The TD error
// TD 误差为正：这一步的结果好于价值网络在 s_t 处的预期。
let positive = trace.td_delta.iter().filter(|d| **d > 0.0).count();
println!(
    "{positive} 个 TD 误差为正（共 {} 个）；最后一个是 {:.4}，此时 V(s_T−1) = {:.4}",
    trace.td_delta.len(),
    trace.td_delta[last],
    trace.values[last]
);

// %% step: Computed once per update
// %% exercise
