//! 第 16 课练习：能分清时限中断和真正结束的目标值与优势值，作用在向量化环境产生的数据流上。
//!
//! 评分：`ppo-tutor grade td_target_truncation` 和 `ppo-tutor grade gae_rollout`
//! （或在本教程中按 `g`）。
//! 重新开始：`ppo-tutor reset td_target_truncation`（恢复整个文件）。

/// 带“同一步”自动重置的向量化环境（Gymnasium 0.29，即 CleanRL 固定使用的版本）产生的数据流中，
/// 每一行的一步 TD 目标：第 `t` 步的价值，等于它得到的奖励，加上价值网络对之后的预期，
/// 前提是“之后”确实存在。这样的环境在回合结束的那一步就把回合重置了。
///
/// - `rewards[t]` 是 `r_t`；`gamma` 是 γ。
/// - `next_values[t]` 是价值网络对第 `t` 步之后环境返回的那个观测的估值。在回合结束的行上，
///   环境已经重置过了：那个观测是下一个回合的第一个观测。
/// - `final_values[t]` 是价值网络对在 `t` 处结束的那个回合真正的最后一个观测的估值
///   （Gymnasium 把这个观测单独交出来，放在 `infos["final_observation"]` 里）。只有在
///   `terminated[t]` 或 `truncated[t]` 为真的行上它才有意义；其余每一行都是 NaN，
///   只是占位的值，绝不能进入任何目标值。
/// - `terminated[t]`：回合在 `t` 处真正结束了（杆倒下了）。`truncated[t]`：时限在 `t` 处
///   把回合中断了，杆还立着。两者可以同时为真。
/// - 所有切片长度相同；每一行返回一个目标值。
///
/// 通过标准：每个目标值与参考答案相差不超过 1e-5（绝对误差加相对误差），用例包括 100 条
/// 由随机种子生成的数据流、连成一条数据流的录制 PyTorch 回合，以及手工构造的数据流：
/// 一次时限中断、一次杆倒下、同一行两个标志都为真、第一行和最后一行都因时限中断，
/// 以及一段完全没有回合结束的采样。该是数值的地方出现 NaN，算作错误。
///
/// 请逐行判断：哪一个值（如果有的话）代表第 `t` 步之后的未来。讲解见第 16 课
/// （beyond-the-seed）第 1 节“时限中断不是终止”；这种数据流见第 4 节
/// “固定长度采样、向量化环境与小批量”。
pub fn td_target_truncation(
    rewards: &[f32],
    next_values: &[f32],
    final_values: &[f32],
    terminated: &[bool],
    truncated: &[bool],
    gamma: f32,
) -> Vec<f32> {
    // TODO：时限把回合中断时，哪个观测的估值还能说明这个状态值多少？杆倒下时呢？
    // 什么都没有结束的行呢？
    todo!()
}

/// 在跨越多个回合的一段采样上计算 GAE，采用 CleanRL 的布局：每步一行，回合首尾相接，
/// 最后一个回合可能尚未结束。
///
/// - `values[t]` 是 `V(s_t)`；`next_values[t]` 是第 `t` 步之后真实的下一个观测的 `V`，
///   只有这一列，旁边没有 `final_values`；`rewards`、`terminated`、`truncated`、`gamma`
///   的含义与 `td_target_truncation` 相同；`lmbda` 是 λ。
/// - 返回 `(advantages, returns)`，每行各一个，其中 returns 是 CleanRL 由优势值推出的
///   价值网络目标（第 8 课第 6 节的 λ-回报）。
/// - 在 `td_target_truncation` 的目标值会自举的那些行上，每一行的一步 TD 误差都从
///   `next_values[t]` 自举。优势值绝不跨过回合的结束处，无论回合以何种方式结束。
///   最后一行之后什么也没有：把那里的优势值当作 0。
///
/// 通过标准：每个优势值和回报与参考答案相差不超过 1e-4 的绝对误差加上 1e-4 的相对误差，
/// 用例包括 100 段由随机种子生成的采样（3 到 80 行，回合以两种方式结束）、连成一段采样的
/// 录制 PyTorch 回合，以及手工构造的采样：时限中断后开始新回合、杆倒下后开始新回合，
/// 以及在回合中途结束的采样。
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
