//! 第 12 课练习：CleanRL 用来观察一次更新的两个数，由你自己从批次数据算出来。
//!
//! 评分：`ppo-tutor grade approx_kl` 和 `ppo-tutor grade clip_fraction`（或在 tutor 中
//! 按 `g`）。从头再来：`ppo-tutor reset approx_kl`（恢复整个文件）。

/// 策略离收集这批数据的那个策略有多远，用一个数表示。
///
/// 只用采样到的动作来估计 KL 散度 KL(π_old ‖ π_θ)：使用 CleanRL 记为 `approx_kl` 的
/// 估计量，它逐行来看从不为负，并且因为动作是从 π_old 中抽取的，所以是无偏的。
/// 第 12 课给出了它的名字。
///
/// - `old_log_probs[i]` 是 `log π_old(a_i|s_i)`，在更新之前就已固定；`log_probs[i]` 是
///   当前参数下的 `log π_θ(a_i|s_i)`。两者长度相同，至少为 1。
/// - 返回对所有行的均值，用 float32 计算。
///
/// 讲解见第 12 课（clip-lab）第 1 节“每次更新都要看什么”。
pub fn approx_kl(old_log_probs: &[f32], log_probs: &[f32]) -> f32 {
    // TODO：哪个估计量逐行来看从不为负？（按 `h` 可逐条显示提示。）
    todo!()
}

/// 截断作用在批次中多大的比例上：即 CleanRL 的 `clipfracs`。
///
/// - `ratio[i]` 是 `π_θ(a_i|s_i) / π_old(a_i|s_i)`，至少有一行；`eps` 是截断范围 ε。
/// - 返回比率离 1 超过 ε 的行所占的比例（介于 0 和 1 之间），按 CleanRL 的方式测量，
///   用 float32 计算。
///
/// 讲解见第 12 课（clip-lab）第 1 节“每次更新都要看什么”，以及第 10 课（clipping）
/// 第 6 节“有多少行被截断”。
pub fn clip_fraction(ratio: &[f32], eps: f32) -> f32 {
    // TODO：在这里写代码。
    todo!()
}
