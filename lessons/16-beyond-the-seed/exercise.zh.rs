//! 第 16 课练习：能分清时限中断和真正结束的目标值与优势值，作用在跨越多个回合的一段采样上。
//!
//! 评分：`ppo-tutor grade td_target_truncation` 和 `ppo-tutor grade gae_rollout`
//! （或在本教程中按 `g`）。
//! 重新开始：`ppo-tutor reset td_target_truncation`（恢复整个文件）。

/// 正确的一步 TD 目标：第 `t` 步的价值，等于它得到的奖励，加上价值网络对之后的预期，
/// 前提是“之后”确实存在。
///
/// - `rewards[t]` 是 `r_t`；`next_values[t]` 是 `V(s_{t+1})`，即价值网络对第 `t` 步之后
///   环境真正返回的那个观测的估值（回合最后一步之后也是如此）；`gamma` 是 γ。
/// - `terminated[t]`：回合在 `t` 处真正结束了（杆倒下了）。`truncated[t]`：时限在 `t` 处
///   把回合中断了，杆还立着。两者可以同时为真。
/// - 所有切片长度相同；每一行返回一个目标值。
///
/// 原教程代码对两个标志一视同仁（`done = term or trunc`）。请判断其中哪一个意味着不再有任何
/// 有价值的未来。讲解见第 16 课（beyond-the-seed）第 1 节“时限中断不是终止”。
pub fn td_target_truncation(
    rewards: &[f32],
    next_values: &[f32],
    terminated: &[bool],
    truncated: &[bool],
    gamma: f32,
) -> Vec<f32> {
    // TODO：时限把回合中断时，后面还有没有可以用 V(s_{t+1}) 来估计的未来？杆倒下时呢？
    todo!()
}

/// 在跨越多个回合的一段采样上计算 GAE，采用 CleanRL 的布局：每步一行，回合首尾相接，
/// 最后一个回合可能尚未结束。
///
/// - `values[t]` 是 `V(s_t)`；`next_values[t]` 是第 `t` 步之后真实的下一个观测的 `V`；
///   `rewards`、`terminated`、`truncated`、`gamma` 的含义与 `td_target_truncation` 相同；
///   `lmbda` 是 λ。
/// - 返回 `(advantages, returns)`，每行各一个，其中 returns 是 CleanRL 由优势值推出的
///   价值网络目标（第 8 课第 6 节的 λ-回报）。
/// - 每一行的一步 TD 误差按 `td_target_truncation` 的方式自举。优势值绝不跨过回合的结束处，
///   无论回合以何种方式结束。最后一行之后什么也没有：把那里的优势值当作 0。
///
/// 讲解见第 16 课（beyond-the-seed）第 4 节“固定长度采样、向量化环境与小批量”，
/// GAE 本身见第 8 课（gae）。
pub fn gae_rollout(
    rewards: &[f32],
    values: &[f32],
    next_values: &[f32],
    terminated: &[bool],
    truncated: &[bool],
    gamma: f32,
    lmbda: f32,
) -> (Vec<f32>, Vec<f32>) {
    // TODO：每一行有两个问题：它的 TD 误差要不要自举？下一行的优势值与它属于同一个回合吗？
    todo!()
}
