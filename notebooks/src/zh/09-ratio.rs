//! notebooks/zh/09-ratio.ipynb 的生成脚本，是 ../09-ratio.rs 的中文版（代码相同，注释和打印的文字为中文）。

// %%
use ppo_engine::lesson::Snapshot;
use ppo_engine::notebook::snapshot;
use ppo_engine::ppo::{EpochTrace, PpoConfig, UpdateTrace};
let config: PpoConfig = PpoConfig::default();
let snap: Snapshot = snapshot(config.clone(), 0, 30)?;
let trace: UpdateTrace = snap.cartpole_update().expect("已训练 30 个回合").trace.clone();

// %% step: Log-probability of the action taken
// 第 0 行：动作从 probs 中选出一列；old_log_probs 是这一项的对数，
// 所以对它取指数就得回这一项。
println!(
    "probs {:?}，动作 {}：old_log_prob {:.6}，exp(old_log_prob) = {:.6}",
    snap.cartpole_update().expect("一次训练过的 CartPole 运行").probs[0],
    trace.actions[0],
    trace.old_log_probs[0],
    trace.old_log_probs[0].exp()
);

// %% step: Why old_log_probs is detached
// %% step: The ratio
// 十轮中的最后一轮，前几行：ln(ratio) 就是 log_probs − old_log_probs。
let last: EpochTrace = trace.epochs[trace.epochs.len() - 1].clone();
println!("行    log_probs  old_log_probs     ratio  ln(ratio)");
for t in 0..3 {
    println!(
        "{t:3}  {:10.6}  {:13.6}  {:8.6}  {:9.6}",
        last.log_probs[t], trace.old_log_probs[t], last.ratio[t], last.ratio[t].ln()
    );
}

// %% step: Exactly 1 in the first epoch
let first: EpochTrace = trace.epochs[0].clone();
assert!(first.ratio.iter().all(|&r| r == 1.0));
println!("第 1 轮：全部 {} 个比率都恰好为 1", first.ratio.len());

// %% step: Later epochs: the ratio drifts
for (k, e) in trace.epochs.iter().enumerate() {
    let spread = e.ratio.iter().map(|r| (r - 1.0).abs()).fold(0.0_f32, f32::max);
    println!("第 {:2} 轮：max |ratio − 1| = {spread:.5}，approx_kl = {:.2e}", k + 1, e.approx_kl);
}

// %% exercise
