//! notebooks/zh/11-clipping.ipynb 的生成脚本，是 ../11-clipping.rs 的中文版（代码相同，注释和打印的文字为中文）。

// %%
use ppo_engine::lesson::Snapshot;
use ppo_engine::notebook::snapshot;
use ppo_engine::ppo::{EpochTrace, PpoConfig, UpdateTrace};
let config: PpoConfig = PpoConfig::default();
let snap: Snapshot = snapshot(config.clone(), 0, 30)?;
let trace: UpdateTrace = snap.cartpole_update().expect("已训练 30 个回合").trace.clone();
let last: EpochTrace = trace.epochs[trace.epochs.len() - 1].clone();

// %% step: Two surrogates
// 第一轮中每个比率都恰好为 1，所以 surr1 和 surr2 都等于优势值；
// 最后一轮中，两者在比率离开区间的那些行上不同。
let first: EpochTrace = trace.epochs[0].clone();
assert!(first.surr1 == trace.advantage && first.surr2 == trace.advantage);
let differ = last.surr1.iter().zip(&last.surr2).filter(|(a, b)| a != b).count();
println!(
    "第 1 轮：全部 {} 行上 surr1 = surr2 = 优势值；第 {} 轮：两者在 {differ} 行上不同",
    trace.advantage.len(),
    trace.epochs.len()
);

// %% step: The clamp: a band around 1
// 最后一轮中被截断改动的行：surr2 / advantage 就是截断之后的比率。
let eps = config.eps as f32;
println!("区间 [{}, {}]", 1.0 - eps, 1.0 + eps);
for t in (0..last.ratio.len()).filter(|&t| last.clipped[t]).take(4) {
    println!(
        "第 {t:3} 行：比率 {:.4} -> 截断后 {:.4}",
        last.ratio[t],
        last.surr2[t] / trace.advantage[t]
    );
}

// %% step: Taking the minimum
// %% step: When the advantage is positive
// %% step: When the advantage is negative
// %% step: How much is being clipped
// 库标记为被截断的行，逐轮列出，并附上 clip_frac 和 approx_kl。
for (k, e) in trace.epochs.iter().enumerate() {
    let flagged = e.clipped.iter().filter(|c| **c).count();
    println!(
        "第 {:2} 轮：{flagged:3} 行被截断（共 {} 行），clip_frac = {:.4}，approx_kl = {:.2e}",
        k + 1,
        e.clipped.len(),
        e.clip_fraction,
        e.approx_kl
    );
}

// %% exercise
// 你的函数通过测试了，现在回到“取最小值”一节：只有在 surr2 < surr1 的地方 min 才选 surr2，
// 也就是比率朝着其优势值所偏好的方向离开区间的地方。比率朝另一个方向离开区间时，
// surr1 < surr2，min 保留 surr1。
let picked_surr2 = last.surr1.iter().zip(&last.surr2).filter(|(a, b)| b < a).count();
let kept_surr1 = last.surr1.iter().zip(&last.surr2).filter(|(a, b)| a < b).count();
println!("min(surr1, surr2) 在 {picked_surr2} 行上选了 surr2（共 {} 行）", last.surr1.len());
println!("另有 {kept_surr1} 行的比率逆着优势值的方向离开了区间：min 保留了 surr1");
