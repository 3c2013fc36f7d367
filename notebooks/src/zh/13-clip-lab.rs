//! notebooks/zh/13-clip-lab.ipynb 的生成脚本，是 ../13-clip-lab.rs 的中文版（代码相同，注释和打印的文字为中文）。
//! 每个实验用所有核心训练 10 到 15 次、每次 500 个回合（需要一分钟或更久）。

// %%
use ppo_engine::lesson::Snapshot;
use ppo_engine::notebook::snapshot;
use ppo_engine::ppo::{EpochTrace, PpoConfig, UpdateTrace};
const LAB_EPISODES: usize = 500;
let config: PpoConfig = PpoConfig::default();
let snap: Snapshot = snapshot(config.clone(), 0, 100)?;
let trace: UpdateTrace = snap.cartpole_update().expect("已训练 100 个回合").trace.clone();

// %% step: What to watch in every update
// 最近一次更新，逐轮列出：诊断指标就是由这些数算出来的。
println!("轮次   approx_kl  clip_frac   最小比率   最大比率       熵");
for (k, e) in trace.epochs.iter().enumerate() {
    let lo = e.ratio.iter().copied().fold(f32::INFINITY, f32::min);
    let hi = e.ratio.iter().copied().fold(f32::NEG_INFINITY, f32::max);
    println!("{:5}  {:9.5}  {:9.4}  {:9.4}  {:9.4}  {:7.4}", k + 1, e.approx_kl, e.clip_fraction, lo, hi, e.entropy);
}
println!("更新前的解释方差：{:?}", trace.explained_variance);

// %% step: Experiment 1: the clip range
// %% step: Experiment 2: how many epochs
// %% step: Experiment 3: a ten times larger actor step
// %% step: Experiment 4: stopping early at a target KL
// %% step: What the clip promises, and what it does not
// 最后一轮：标记为被截断的行，正是比率落在 [1 − ε, 1 + ε] 之外的那些行。
let last: EpochTrace = trace.epochs[trace.epochs.len() - 1].clone();
let eps = config.eps as f32;
let marked = last.clipped.iter().filter(|c| **c).count();
let lo = last.ratio.iter().copied().fold(f32::INFINITY, f32::min);
let hi = last.ratio.iter().copied().fold(f32::NEG_INFINITY, f32::max);
println!(
    "最后一轮：比率从 {lo:.4} 到 {hi:.4}；{marked} 行（共 {} 行）落在 [{}, {}] 之外，被标记为截断",
    last.ratio.len(),
    1.0 - eps,
    1.0 + eps
);

// %% exercise
