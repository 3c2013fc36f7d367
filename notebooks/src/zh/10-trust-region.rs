//! notebooks/zh/10-trust-region.ipynb 的生成脚本，是 ../10-trust-region.rs 的中文版（代码相同，注释和打印的文字为中文）。
//! 探测在每个步长上另跑 150 个回合（约一秒）；第 3 到第 6 节各训练一次 40 个回合的短运行
//! （几秒）；最后一节的实验用所有核心训练 20 次、每次 500 个回合（需要几分钟）。

// %%
use ppo_engine::lesson::Snapshot;
use ppo_engine::notebook::snapshot;
use ppo_engine::ppo::{Objective, PpoConfig, PpoError, Trainer, UpdateTrace};
const LAB_EPISODES: usize = 500;
// 原教程代码的设置，随机种子 0；训练 40 个回合，与 `ppo-tutor trust-region` 相同。
let config: PpoConfig = PpoConfig::default();
let snap: Snapshot = snapshot(config.clone(), 0, 40)?;
let trace: UpdateTrace = snap.cartpole_update().expect("已训练 40 个回合").trace.clone();
// 用 `config` 在随机种子 0 上从头训练一个智能体 `episodes` 个回合，
// 记下每个回合的回报，以及紧随其后那次更新的记录。
fn run_updates(config: &PpoConfig, episodes: usize) -> Result<Vec<(f64, UpdateTrace)>, PpoError> {
    let mut trainer = Trainer::new(PpoConfig { num_episodes: episodes, ..config.clone() }, 0)?;
    let mut runs = Vec::new();
    while let Some(report) = trainer.next_episode()? {
        runs.push((report.episode_return, report.trace));
    }
    Ok(runs)
}

// %% step: What the ratio corrects, and what it does not
// 最近一次更新：每一轮都在同样的这些行上计算替代目标，也就是 π_old 到过的状态。
// 一轮又一轮改变的，只有比率，即所采取动作的权重。
let rows = trace.len() as f32;
let mean_advantage: f32 = trace.advantage.iter().sum::<f32>() / rows;
println!("{} 行，每一行都是 π_old 到过的状态；Â 的均值 = {mean_advantage:.4}", trace.len());
println!(" 轮次  mean((r − 1)·Â)  max |r − 1|");
for (k, e) in trace.epochs.iter().enumerate() {
    let gain = e.surr1.iter().sum::<f32>() / rows - mean_advantage;
    let spread = e.ratio.iter().map(|r| (r - 1.0).abs()).fold(0.0_f32, f32::max);
    println!("{:5}  {gain:+15.5}  {spread:11.5}", k + 1);
}

// %% step: Stepping along the surrogate, measured
// 探测，与 `ppo-tutor trust-region` 的做法相同：从 θ_old（采集最近这一批数据的策略网络）出发，
// 沿这一批替代目标的梯度走十二种步长 α，从 0 到 3.2，每种都在另跑的 150 个回合上测量。
// 先是表格，然后是图。
use ppo_engine::notebook::Rich as _; // 显示探测结果：先表格，后图
use ppo_engine::ppo::trust_region::{ProbeSettings, TrustRegionProbe, probe_snapshot};
let probe: TrustRegionProbe = probe_snapshot(&snap, &config, &ProbeSettings::default())?;
probe

// %%
// 每个步长上真实值减去预测值，以及这个差除以它的标准误
// （把两个误差当作相互独立来合并：只是一把尺子，不是检验）。
println!("    α    平均 KL        真实 − 预测 差/标准误");
for p in probe.points.iter().filter(|p| p.step > 0.0) {
    let gap = p.truth - p.predicted;
    let se = (p.truth_se.powi(2) + p.predicted_se.powi(2)).sqrt();
    println!("{:5.3}  {:9.2e}  {gap:+17.3}  {:8.1}", p.step, p.kl, gap / se);
}

// %%
// 同样的探测，换一批更晚的数据：同一个随机种子训练到 100 个回合。
let later: Snapshot = snapshot(config.clone(), 0, 100)?;
let later_probe: TrustRegionProbe = probe_snapshot(&later, &config, &ProbeSettings::default())?;
println!("训练 {} 个回合之后（最后一个回合的回报 {}）：", later.episodes, later.returns[later.returns.len() - 1]);
println!("    α    平均 KL      预测的 ΔJ_γ      真实的 ΔJ_γ");
for p in later_probe.points.iter().filter(|p| p.step > 0.0) {
    println!(
        "{:5.3}  {:9.2e}  {:+7.3} ± {:5.3}  {:+7.3} ± {:5.3}",
        p.step, p.kl, p.predicted, p.predicted_se, p.truth, p.truth_se
    );
}

// %% step: How far is far: the KL between two policies
// PPO-惩罚记录每一行的精确 KL（它的损失要用到）；approx_kl 只用所采样动作的比率估计同一个均值。
// 下面是一次 PPO-惩罚运行（随机种子 0）最近那次更新里的两者，逐轮列出（都是该轮更新一步之前的值）。
let penalty: PpoConfig = PpoConfig { objective: Objective::Penalty, ..config.clone() };
let pen: Snapshot = snapshot(penalty.clone(), 0, 40)?;
let pen_trace: UpdateTrace = pen.cartpole_update().expect("已训练 40 个回合").trace.clone();
println!(" 轮次   精确 KL 均值  approx_kl     单行最大 KL");
for (k, e) in pen_trace.epochs.iter().enumerate() {
    let largest = e.kl.iter().copied().fold(0.0_f32, f32::max);
    let exact = e.kl_mean.unwrap_or(f32::NAN);
    println!("{:5}  {exact:13.3e}  {:9.3e}  {largest:14.3e}", k + 1, e.approx_kl);
}

// %% step: Answer 1: a hard limit on the KL (TRPO)
// KL 约束下的线搜索，随机种子 0，训练 40 个回合。每次更新列出：第一次尝试的 KL、减半的次数、
// 被接受的 α、它在这一批上的 KL（不超过 δ）和替代目标的增益；“-” 表示没有步长通过，策略网络
// 保持 θ_old。先列前十次更新，再总结全部 40 次。
use ppo_engine::ppo::trace::LineSearchTrace;
let line_search: PpoConfig = PpoConfig { objective: Objective::LineSearch, ..config.clone() };
let searched: Vec<(f64, UpdateTrace)> = run_updates(&line_search, 40)?;
println!(
    "第一次尝试 α = {}，最多减半 {} 次，δ = {}",
    line_search.ls_max_step, line_search.ls_backtracks, line_search.kl_delta
);
// 保留 `digits` 位小数的数；没有值时为 “-”。
fn dash(v: Option<f64>, digits: usize) -> String {
    v.map_or("-".to_string(), |v| format!("{v:.digits$}"))
}
println!("   回合    回报   首次 KL  减半次数       α        KL       增益");
for (i, (ret, t)) in searched.iter().enumerate().take(10) {
    let Some(s) = t.line_search else { continue };
    println!(
        "{:7}  {ret:6}  {:>8}  {:8}  {:>6}  {:>8}  {:>9}",
        i + 1,
        dash(s.first_kl.map(f64::from), 4),
        s.halvings,
        dash(s.step, 4),
        dash(s.kl.map(f64::from), 5),
        dash(s.gain.map(f64::from), 5)
    );
}
let searches: Vec<LineSearchTrace> = searched.iter().filter_map(|(_, t)| t.line_search).collect();
let accepted = searches.iter().filter(|s| s.step.is_some()).count();
let halvings = searches.iter().map(|s| s.halvings).sum::<usize>() as f64 / searches.len() as f64;
println!("全部 {} 次更新：{accepted} 次迈出了一步，平均减半 {halvings:.2} 次", searches.len());

// %% step: Answer 2: a KL penalty with an adaptive β (PPO-Penalty)
// PPO-惩罚，随机种子 0，训练 40 个回合：每次更新时的 β、最后一轮之后的 KL d，以及下一次更新用的 β。
let penalised: Vec<(f64, UpdateTrace)> = run_updates(&penalty, 40)?;
let delta = penalty.kl_delta;
println!(
    "β₀ = {}，δ = {delta}：d < {:.4} 时 β 减半，d > {:.4} 时 β 加倍",
    penalty.beta_init,
    delta / 1.5,
    delta * 1.5
);
println!("   回合    回报 更新时的 β 更新后 KL d   之后的 β");
for (i, (ret, t)) in penalised.iter().enumerate() {
    let Some(p) = t.penalty else { continue };
    println!("{:7}  {ret:6}  {:9.5}  {:10.5}  {:9.5}", i + 1, p.beta_before, p.kl_after, p.beta_after);
}

// 下面的实时数值是这次惩罚运行（随机种子 0，40 个回合，即第 3 节那次运行）的最近一次更新；
// `clip_snap` 留着原教程代码的截断运行，供下一节使用。
let clip_snap: Snapshot = snap.clone();
let snap: Snapshot = pen.clone();

// %% step: Answer 3: the clip (PPO-Clip)
// 下面的实时数值又是原教程代码的截断运行的。
let snap: Snapshot = clip_snap.clone();
// 原教程代码用的截断，同样的随机种子和回合数，与另外两种答案并列：每次更新让策略移动了多少，
// 用精确 KL 衡量（kl_after，对每种目标都是同一个量）。
use ppo_engine::i18n::pad_right;
let clipped: Vec<(f64, UpdateTrace)> = run_updates(&config, 40)?;
println!("目标          平均 KL     最大 KL    超过 1.5δ 的更新         最后 10 个回报的均值");
for (name, runs) in [("截断", &clipped), ("惩罚", &penalised), ("线搜索", &searched)] {
    let kls: Vec<f32> = runs.iter().filter_map(|(_, t)| t.kl_after).collect();
    let mean = kls.iter().sum::<f32>() / kls.len() as f32;
    let largest = kls.iter().copied().fold(0.0_f32, f32::max);
    let above = kls.iter().filter(|&&kl| f64::from(kl) > 1.5 * config.kl_delta).count();
    let last: f64 = runs[runs.len() - 10..].iter().map(|(r, _)| r).sum::<f64>() / 10.0;
    println!("{}  {mean:7.4}  {largest:10.4}  {above:13} / {:2}  {last:27.1}", pad_right(name, 12), kls.len());
}

// %% step: Four ways over five seeds
// %% exercise
