//! 第 13 课练习：衡量一次更新让策略移动了多远，并及时让它停下。
//!
//! 评分：`ppo-tutor grade approx_kl` 和 `ppo-tutor grade kl_early_stop`（或在本教程中
//! 按 `g`）。重新开始：`ppo-tutor reset approx_kl`（恢复整个文件）。

/// 策略离收集这批数据的那个策略有多远，用一个数表示。
///
/// 只用采样到的动作来估计 KL 散度 KL(π_old ‖ π_θ)：使用 CleanRL 记为 `approx_kl` 的
/// 估计量，它逐行来看从不为负，并且因为动作是从 π_old 中抽取的，所以是无偏的。
/// 第 13 课给出了它的名字。
///
/// - `old_log_probs[i]` 是 `log π_old(a_i|s_i)`，在更新之前就已固定；`log_probs[i]` 是
///   当前参数下的 `log π_θ(a_i|s_i)`。两者长度相同，至少为 1。
/// - 返回对所有行的均值，用 float32 计算。
///
/// 讲解见第 13 课（clip-lab）第 1 节“每次更新都要看什么”。
pub fn approx_kl(old_log_probs: &[f32], log_probs: &[f32]) -> f32 {
    // TODO：哪个估计量逐行来看从不为负？（按 `h` 可逐条显示提示。）
    todo!()
}

/// 在 Spinning Up 的提前停止之下，一次更新执行了多少个梯度步。
///
/// 截断并不能阻止策略离收集这批数据的那个策略越来越远（第 13 课实验 4）。Spinning Up 的
/// PPO 加了一道防线：在每一轮执行梯度步之前，先估计策略已经移动了多远；如果估计值超过了
/// `target_kl` 之上的那道界限，就在那里结束本次更新，这一步也不再执行。请用它的估计量、
/// 按它的规则，处理一次逐轮给出对数概率的更新。
///
/// - `old_log_probs[i]` 是 `log π_old(a_i|s_i)`，在更新之前就已固定；共 `N` 行，至少 1 行。
/// - `log_probs_per_epoch` 依次存放 `E` 行、每行 `N` 个数（按行优先排列，
///   `E = log_probs_per_epoch.len() / N`，至少为 1）：第 `e` 行是第 `e` 轮开始时、
///   也就是这一轮的梯度步之前，策略给出的 `log π(a_i|s_i)`。
/// - `target_kl` 就是 Spinning Up 的 `target_kl`（默认 0.01）。
///
/// 返回 `E` 轮中有多少轮执行了梯度步：防线从未触发时返回 `E`。各个估计值都是对所有行
/// 求的均值，用 float32 计算。
///
/// 讲解见第 13 课（clip-lab）第 5 节“实验 4：在目标 KL 处提前停止”。
pub fn kl_early_stop(old_log_probs: &[f32], log_probs_per_epoch: &[f32], target_kl: f32) -> usize {
    // TODO：在这里写代码；在本教程中按 `h` 可逐条显示提示。
    // Spinning Up 检验的是 KL 散度的哪一种估计？估计值第一次过大的那一轮，它的梯度步会怎样？
    todo!()
}
