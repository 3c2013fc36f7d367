//! notebooks/zh/14-training.ipynb 的生成脚本，是 ../14-training.rs 的中文版（代码相同，注释和打印的文字为中文）。
//! 第 3、4 节各在所有核心上训练五次、每次 500 个回合（几秒钟）。

// %%
use ppo_engine::lesson::Snapshot;
use ppo_engine::notebook::snapshot;
use ppo_engine::plot::smoothed_returns;
use ppo_engine::ppo::PpoConfig;
use ppo_engine::ppo::seeds::{SeedRun, mean_std, train_seeds};
// 原教程代码的完整训练：500 个回合（几秒钟）。
let config: PpoConfig = PpoConfig::default();
let snap: Snapshot = snapshot(config.clone(), 0, 500)?;
let threads: usize = std::thread::available_parallelism().map_or(1, |n| n.get());
// 把下标换成回合编号（从 1 数起），没有则为“从未”。
fn episode(index: Option<usize>) -> String {
    index.map_or("从未".to_string(), |i| (i + 1).to_string())
}
// 逐个随机种子打印：第一个 500 步的回合，移动平均首次达到 450 的回合，
// 第一个 500 之后移动平均的最低值，以及最后 50 个回报的均值。
fn describe(runs: &[SeedRun]) {
    println!("随机种子  首个 500  移动平均 >= 450  之后最低  最后 50");
    for run in runs {
        let returns = &run.summary.returns;
        let smooth = smoothed_returns(returns);
        let first = returns.iter().position(|&r| r >= 500.0);
        let at_450 = smooth.iter().position(|&m| m >= 450.0);
        let lowest = first.map_or("-".to_string(), |f| {
            format!("{:.0}", smooth[f..].iter().copied().fold(f64::INFINITY, f64::min))
        });
        println!("{:4}  {:>9}  {:>14}  {:>12}  {:7.1}", run.seed, episode(first), episode(at_450), lowest, run.summary.mean_last(50));
    }
}
// 一次训练的后期回落：第一个 500 步的回合之后，回报低于 250 的回合。
fn late_falls(run: &SeedRun) -> usize {
    let returns = &run.summary.returns;
    let first = returns.iter().position(|&r| r >= 500.0).unwrap_or(returns.len());
    returns[first..].iter().filter(|&&r| r < 250.0).count()
}

// %% step: Following a run
// 原教程代码在每个进度条结束时打印最后十个回合的平均回报。
for bar in 0..10 {
    let end = (bar + 1) * 50;
    let mean: f64 = snap.returns[end - 10..end].iter().sum::<f64>() / 10.0;
    println!("进度条 {bar}：第 {end} 个回合，最近十个回合的平均回报 {mean:.3}");
}

// %% step: Reading the return curve
// 每次训练都成立的两点：最初的回合很短，回报不会超过 500。
let highest: f64 = snap.returns.iter().copied().fold(0.0, f64::max);
println!("前五个回报：{:?}", &snap.returns[..5]);
println!("最高回报：{highest}，共 {} 个回合", snap.returns.len());

// %% step: Five seeds, one setting
// 原教程代码的设置，随机种子 0–4，各 500 个回合。
let seeds_0_4: Vec<SeedRun> = train_seeds(&config, &[0, 1, 2, 3, 4], threads, |_, _| {})?;
describe(&seeds_0_4);

// %% step: What a curve can and cannot tell
// 同一套设置换成随机种子 5–9：抽两次、每次五个随机种子，其他什么都不改。
let seeds_5_9: Vec<SeedRun> = train_seeds(&config, &[5, 6, 7, 8, 9], threads, |_, _| {})?;
describe(&seeds_5_9);
for (name, runs) in [("随机种子 0–4", &seeds_0_4), ("随机种子 5–9", &seeds_5_9)] {
    let ends: Vec<f64> = runs.iter().map(|r| r.summary.mean_last(50)).collect();
    let (mean, std) = mean_std(&ends);
    let falls: usize = runs.iter().map(late_falls).sum();
    println!("{name}：最后 50 个回合均值 {mean:.1} ± {std:.1}，第一个 500 之后有 {falls} 个回合低于 250");
}

// %% step: Smoothing: a centred window of 9
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

// 两端：下标 0 到 3 处的窗口宽度依次为 1、3、5、7。
println!("前五个移动平均：{:?}", &snap.moving_average[..5]);
println!("对应的回报：    {:?}", &snap.returns[..5]);
