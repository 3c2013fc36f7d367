//! notebooks/zh/04-policy-gradient.ipynb 的生成脚本，是 ../04-policy-gradient.rs 的中文版（代码相同，注释和打印的文字为中文）。

// %%
use ppo_engine::lesson::{Snapshot, TensorView};
use ppo_engine::notebook::snapshot;
use ppo_engine::ppo::{PpoConfig, SurrogateGradients, UpdateTrace};
// 原教程代码的设置，随机种子 0，训练 30 个回合；最后的实验每次运行训练 500 个回合。
const LAB_EPISODES: usize = 500;
let config: PpoConfig = PpoConfig::default();
let snap: Snapshot = snapshot(config.clone(), 0, 30)?;
let trace: UpdateTrace = snap.cartpole_update().expect("已训练 30 个回合").trace.clone();

// %% step: What we want: J(θ)
// log P_θ(τ) 只保留策略中受 θ 控制的因子：Σ_t log π(a_t|s_t)。
let log_p: f32 = trace.old_log_probs.iter().sum();
println!("共采取了 {} 个动作；Σ_t log π(a_t|s_t) = {log_p:.3}", trace.actions.len());

// %% step: The log-derivative trick: REINFORCE
// G_t = r_t + γ·G_{t+1}，从最后一步往回算（done 之后的部分记为 0），这里取库里的计算：
// 亲手写这个反向循环，是第 8 课的练习。
use ppo_engine::lesson::live::values::return_to_go;
let g: Vec<f64> = return_to_go(&trace.rewards, &trace.dones, config.gamma);
let g32: Vec<f32> = g.iter().map(|&x| x as f32).collect();
TensorView::column("return_to_go", &g32)

// %% step: A baseline removes variance, not truth
// REINFORCE 加在 ∇log π 上的权重：不用基线，以及用价值网络作基线。
let centred: Vec<f64> = g.iter().zip(&trace.values).map(|(g, v)| g - f64::from(*v)).collect();
fn mean_abs(xs: &[f64]) -> f64 {
    xs.iter().map(|x| x.abs()).sum::<f64>() / xs.len() as f64
}
println!("|G_t| 的均值 = {:.3}，|G_t − V(s_t)| 的均值 = {:.3}", mean_abs(&g), mean_abs(&centred));

// %% step: The advantage, not the return
let same_sign = trace
    .advantage
    .iter()
    .zip(&centred)
    .filter(|(a, c)| (**a > 0.0) == (**c > 0.0))
    .count();
println!(
    "GAE（λ = {}）与 G_t − V(s_t) 在 {same_sign} 行上符号相同（共 {} 行）",
    config.lmbda,
    centred.len()
);

// %% step: The bridge to PPO: one gradient at θ_old
// check: grad_surrogate after 30 episodes
// 会话在采样第 30 个回合的那个策略网络处，对两个目标分别求了梯度。
let grads: SurrogateGradients = snap.cartpole_update().expect("每个回合之后都会计算").gradients.clone();
println!("{:<16} {:>14} {:>14}", "参数", "∇ mean(r·Â)", "∇ mean(log π·Â)");
for i in [640, 641, 642, 896, 897] {
    let name = grads.label(i).unwrap_or_default();
    println!("{name:<18} {:>14.6e} {:>14.6e}", grads.surrogate[i], grads.log_prob[i]);
}
println!("最大差值 {:.3e}；最大梯度 {:.3e}", grads.max_abs_diff(), grads.max_abs());
TensorView::column("grad_surrogate", &grads.surrogate)

// %% step: REINFORCE with a baseline, one switch away
// 在 PPO 旁边跑一次 REINFORCE，随机种子 0，其余用原教程代码的设置：
use ppo_engine::ppo::Algorithm;
let reinforce = PpoConfig { algorithm: Algorithm::Reinforce, ..config.clone() };
let r_snap: Snapshot = snapshot(reinforce, 0, 100)?;
let p_snap: Snapshot = snapshot(config.clone(), 0, 100)?;
fn last20(s: &Snapshot) -> f64 {
    s.returns[80..].iter().sum::<f64>() / 20.0
}
println!("训练 100 个回合后，最后 20 个回报的均值：PPO {:.1}，REINFORCE {:.1}", last20(&p_snap), last20(&r_snap));
