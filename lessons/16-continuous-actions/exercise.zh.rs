//! 第 16 课练习：高斯策略在它所采取的动作处的对数密度，也就是动作变成力矩之后，
//! 构成 PPO 比率的那个 `log π(a|s)`。
//!
//! 评分：`ppo-tutor grade gaussian_log_prob`（或在教程中按 `g`）。
//! 重新开始：`ppo-tutor reset gaussian_log_prob`（恢复整个文件）。

/// 策略采取每个动作的可能性有多大，以对数尺度表示：正态分布在该动作处密度的对数，
/// 即 PyTorch 的 `torch.distributions.Normal(mu, std).log_prob(actions)` 逐行返回的值。
///
/// - 第 `i` 行是一个时间步。策略的正态分布均值为 `mu[i]`（书中的 μ = 2·tanh(·)，
///   在 [−2, 2] 内），标准差为 `std[i]`（σ = softplus(·)，总是 > 0；即 torch 的
///   `scale`）。`actions[i]` 是所采取的力矩：任意实数，可能离 μ 很近，也可能很远。
/// - 三个切片长度相同，可能为 0。每一行返回一个值，类型为 f32。
/// - 这是对数密度：它可以大于 0（窄正态分布在均值附近的密度大于 1），对于离 μ 好几个 σ
///   的动作，它也可以是很大的负数。
///
/// 讲解见第 16 课（continuous-actions）第 3 节“正态分布的对数密度”。
pub fn gaussian_log_prob(mu: &[f32], std: &[f32], actions: &[f32]) -> Vec<f32> {
    // TODO：在这里写代码。
    todo!()
}
