//! notebooks/zh/13-training.ipynb 的生成脚本，是 ../13-training.rs 的中文版（代码相同，注释和打印的文字为中文）。

// %%
use ppo_engine::lesson::Snapshot;
use ppo_engine::notebook::snapshot;
use ppo_engine::ppo::PpoConfig;
// 原教程代码的完整训练：500 个回合（几秒钟）。
let config: PpoConfig = PpoConfig::default();
let snap: Snapshot = snapshot(config.clone(), 0, 500)?;

// %% step: Following a run
// 原教程代码在每个进度条结束时打印最后十个回合的平均回报。
for bar in 0..10 {
    let end = (bar + 1) * 50;
    let mean: f64 = snap.returns[end - 10..end].iter().sum::<f64>() / 10.0;
    println!("Iteration {bar}：第 {end} 个回合，回报 {mean:.3}");
}

// %% step: Reading the return curve
// %% step: Why smooth, and how much
// %% step: The middle: a sum that slides
// 检查中段的一行：moving_average[100] 是 returns[96..=104] 的均值。
println!("returns[96..=104]   = {:?}", &snap.returns[96..=104]);
println!("moving_average[100] = {:.4}", snap.moving_average[100]);

// 把 rl_utils 的前缀和算法 (cumsum[w:] − cumsum[:-w]) / w 居中对齐，与库里的移动平均比较。
let w = 9;
let mut cumsum = vec![0.0_f64];
for r in &snap.returns {
    cumsum.push(cumsum[cumsum.len() - 1] + r);
}
let middle: Vec<f64> = (w..cumsum.len()).map(|i| (cumsum[i] - cumsum[i - w]) / w as f64).collect();
let centre = w / 2;
for i in [0, 100, 400] {
    assert!((middle[i] - snap.moving_average[i + centre]).abs() < 1e-9);
}
println!("中段的 {} 个值与库里的移动平均一致", middle.len());

// %% step: The edges: shrinking odd windows
println!("前五个移动平均：{:?}", &snap.moving_average[..5]);
println!("对应的回报：    {:?}", &snap.returns[..5]);
