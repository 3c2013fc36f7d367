//! 第 11 课练习：截断后的目标已经不再推动哪些行。
//!
//! 评分：`ppo-tutor grade zero_gradient_rows`（或在本教程中按 `g`）。
//! 重新开始：`ppo-tutor reset zero_gradient_rows`。

/// 截断后的目标已经不再推动哪些行。
///
/// 每一行为 PPO 所最大化的截断替代目标贡献一项 `min(r·Â, clamp(r, 1 − ε, 1 + ε)·Â)`
/// （原教程代码的策略网络损失就是这些项取相反数后的平均）。对每一行，当该项对这一行比率的导数为零、因而这次更新不再改变策略选择该行动作
/// 的概率时，返回 `true`；梯度仍在流动时返回 `false`。
///
/// - `ratio[i]` 是 `π_θ(a_i|s_i) / π_old(a_i|s_i)`，`advantage[i]` 是 `Â_i`，两者长度相同；
///   `eps` 是截断范围 ε。结果每行一个标记。
/// - 根据优势值的符号和比率所在的位置来判断；不要做数值求导。
/// - 恰好在 `r = 1 − ε` 或 `r = 1 + ε` 时，以 PyTorch 为准：`clamp` 在边界上会传递梯度。
///   优势值恰好为 0 的行，没有任何可推动的东西。
///
/// 讲解见第 11 课（clipping）第 4 节和第 5 节：“优势值为正时”和“优势值为负时”。
/// 评分：`ppo-tutor grade zero_gradient_rows`。
pub fn zero_gradient_rows(ratio: &[f32], advantage: &[f32], eps: f32) -> Vec<bool> {
    // TODO：优势值为正时，区间的哪一侧让梯度停止？优势值为负时呢？
    todo!()
}
