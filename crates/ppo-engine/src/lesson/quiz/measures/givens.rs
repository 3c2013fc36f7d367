//! Givens: numbers of this run that a question shows in its prompt (`{{name}}`), for the
//! learner to compute a run measure's answer from.

use super::{Basis, Measure, Snapshot, at, batch, extreme_row, from_end, hyper};
use crate::i18n::Text;

/// A given: a number, shown, never asked.
const fn given(
    name: &'static str,
    about: &'static str,
    about_zh: &'static str,
    value: fn(&Snapshot) -> Option<f64>,
) -> Measure {
    Measure {
        name,
        about: Text::new(about, about_zh),
        value,
        choices: 0,
        basis: Basis::Given,
    }
}

/// The given measures.
pub(super) static GIVENS: &[Measure] = &[
    given(
        "gamma",
        "γ, the run's discount factor",
        "本次运行的折扣因子 γ",
        |s| hyper(s, "gamma"),
    ),
    given(
        "eps",
        "ε, the run's clip range",
        "本次运行的截断范围 ε",
        |s| hyper(s, "eps"),
    ),
    given(
        "actor_lr",
        "the actor's learning rate",
        "策略网络的学习率",
        |s| hyper(s, "actor_lr"),
    ),
    given(
        "episodes",
        "episodes played so far",
        "到目前为止已采样的回合数",
        |s| (s.episodes > 0).then_some(s.episodes as f64),
    ),
    given(
        "episode_return",
        "the latest episode's return",
        "最新回合的回报",
        |s| s.returns.last().copied(),
    ),
    given(
        "mean_return",
        "the mean return of the episodes so far",
        "到目前为止各回合回报的均值",
        |s| (!s.returns.is_empty()).then(|| s.returns.iter().sum::<f64>() / s.returns.len() as f64),
    ),
    given(
        "return_first",
        "the run's first return",
        "本次运行的第一个回报",
        |s| s.returns.first().copied(),
    ),
    given(
        "return_second",
        "the run's second return",
        "本次运行的第二个回报",
        |s| s.returns.get(1).copied(),
    ),
    given(
        "return_third",
        "the run's third return",
        "本次运行的第三个回报",
        |s| s.returns.get(2).copied(),
    ),
    given(
        "prob_left_first",
        "π(left|s_0) in the batch's first row",
        "批次第一行的 π(left|s_0)",
        |s| s.cartpole_update()?.probs.first().map(|p| f64::from(p[0])),
    ),
    given(
        "prob_right_first",
        "π(right|s_0) in the batch's first row",
        "批次第一行的 π(right|s_0)",
        |s| s.cartpole_update()?.probs.first().map(|p| f64::from(p[1])),
    ),
    given(
        "action_first",
        "the action of the batch's first row",
        "批次第一行的动作",
        |s| s.batch()?.actions.get(0),
    ),
    given(
        "theta_last",
        "the pole angle θ in the batch's last state",
        "批次最后一个状态中的杆角 θ",
        |s| {
            s.cartpole_update()?
                .trace
                .states
                .last()
                .map(|o| f64::from(o[2]))
        },
    ),
    given(
        "theta_dot_last",
        "the pole's angular velocity θ̇ in the batch's last state",
        "批次最后一个状态中杆的角速度 θ̇",
        |s| {
            s.cartpole_update()?
                .trace
                .states
                .last()
                .map(|o| f64::from(o[3]))
        },
    ),
    given(
        "value_first",
        "V(s_0), the critic's value of the batch's first state",
        "V(s_0)，价值网络对批次第一个状态的估值",
        |s| at(batch(s)?.values, 0),
    ),
    given(
        "next_value_first",
        "V(s_1), the critic's value of the first row's next state",
        "V(s_1)，价值网络对第一行下一状态的估值",
        |s| at(batch(s)?.next_values, 0),
    ),
    given(
        "grad_fc2_bias0",
        "the actor loss's gradient for fc2.bias[0] at θ_old",
        "θ_old 处策略网络损失对 fc2.bias[0] 的梯度",
        loss_gradient_fc2_bias0,
    ),
    given(
        "td_delta_last",
        "the TD error of the batch's last row",
        "批次最后一行的 TD 误差",
        |s| from_end(batch(s)?.td_delta, 1),
    ),
    given(
        "td_delta_last2",
        "the TD error of the batch's second-to-last row",
        "批次倒数第二行的 TD 误差",
        |s| from_end(batch(s)?.td_delta, 2),
    ),
    given(
        "td_delta_last3",
        "the TD error of the batch's third-to-last row",
        "批次倒数第三行的 TD 误差",
        |s| from_end(batch(s)?.td_delta, 3),
    ),
    given(
        "old_log_prob_first",
        "log π_old(a_0|s_0), the first row's old log-probability",
        "第一行的旧对数概率 log π_old(a_0|s_0)",
        |s| at(batch(s)?.old_log_probs, 0),
    ),
    given(
        "log_prob_last_first",
        "log π_θ(a_0|s_0) in the update's last epoch",
        "更新最后一轮中的 log π_θ(a_0|s_0)",
        |s| at(batch(s)?.epochs.last()?.log_probs, 0),
    ),
    given(
        "ratio_max_last",
        "the largest ratio of the update's last epoch",
        "更新最后一轮中最大的比率",
        |s| at(batch(s)?.epochs.last()?.ratio, extreme_row(s, true)?),
    ),
    given(
        "adv_at_ratio_max_last",
        "the advantage of the row with the last epoch's largest ratio",
        "最后一轮中比率最大那一行的优势值",
        |s| at(batch(s)?.advantage, extreme_row(s, true)?),
    ),
    given(
        "ratio_min_last",
        "the smallest ratio of the update's last epoch",
        "更新最后一轮中最小的比率",
        |s| at(batch(s)?.epochs.last()?.ratio, extreme_row(s, false)?),
    ),
    given(
        "adv_at_ratio_min_last",
        "the advantage of the row with the last epoch's smallest ratio",
        "最后一轮中比率最小那一行的优势值",
        |s| at(batch(s)?.advantage, extreme_row(s, false)?),
    ),
    given(
        "above_pos_last",
        "rows with r > 1 + ε and Â > 0 in the last epoch",
        "最后一轮中 r > 1 + ε 且 Â > 0 的行数",
        |s| outside(s, true, true),
    ),
    given(
        "above_neg_last",
        "rows with r > 1 + ε and Â < 0 in the last epoch",
        "最后一轮中 r > 1 + ε 且 Â < 0 的行数",
        |s| outside(s, true, false),
    ),
    given(
        "below_pos_last",
        "rows with r < 1 − ε and Â > 0 in the last epoch",
        "最后一轮中 r < 1 − ε 且 Â > 0 的行数",
        |s| outside(s, false, true),
    ),
    given(
        "below_neg_last",
        "rows with r < 1 − ε and Â < 0 in the last epoch",
        "最后一轮中 r < 1 − ε 且 Â < 0 的行数",
        |s| outside(s, false, false),
    ),
    given(
        "prob_old_at_ratio_max_last",
        "π_old(a|s), the old probability of the action of the last epoch's largest-ratio row",
        "最后一轮中比率最大那一行的动作在旧策略下的概率 π_old(a|s)",
        |s| {
            at(
                &s.cartpole_update()?.trace.old_log_probs,
                extreme_row(s, true)?,
            )
            .map(f64::exp)
        },
    ),
    given(
        "adv_abs_max",
        "the largest |Â| of the latest batch",
        "最近一批数据中最大的 |Â|",
        |s| {
            let adv = &s.cartpole_update()?.trace.advantage;
            adv.iter().map(|a| f64::from(a.abs())).reduce(f64::max)
        },
    ),
    given(
        "adv_first",
        "Â_0, the advantage of the batch's first row",
        "Â_0，批次第一行的优势值",
        |s| at(batch(s)?.advantage, 0),
    ),
    given(
        "adv_mean",
        "the mean of the batch's advantages",
        "批次优势值的均值",
        |s| mean_std(batch(s)?.advantage).map(|(m, _)| m),
    ),
    given(
        "adv_std",
        "the unbiased standard deviation of the batch's advantages",
        "批次优势值的无偏标准差",
        |s| mean_std(batch(s)?.advantage).map(|(_, sd)| sd),
    ),
    given(
        "mu_first",
        "μ(s_0), the Gaussian policy's mean in the first row",
        "μ(s_0)，第一行高斯策略的均值",
        |s| at(&s.pendulum_update()?.trace.mu, 0),
    ),
    given(
        "std_first",
        "σ(s_0), the Gaussian policy's standard deviation in the first row",
        "σ(s_0)，第一行高斯策略的标准差",
        |s| at(&s.pendulum_update()?.trace.std, 0),
    ),
    given(
        "cos_first",
        "cos θ in the batch's first Pendulum state",
        "批次第一个倒立摆状态中的 cos θ",
        |s| {
            s.pendulum_update()?
                .trace
                .states
                .first()
                .map(|o| f64::from(o[0]))
        },
    ),
    given(
        "sin_first",
        "sin θ in the batch's first Pendulum state",
        "批次第一个倒立摆状态中的 sin θ",
        |s| {
            s.pendulum_update()?
                .trace
                .states
                .first()
                .map(|o| f64::from(o[1]))
        },
    ),
    given(
        "theta_dot_first",
        "θ̇ in the batch's first Pendulum state",
        "批次第一个倒立摆状态中的 θ̇",
        |s| {
            s.pendulum_update()?
                .trace
                .states
                .first()
                .map(|o| f64::from(o[2]))
        },
    ),
];

/// The gradient of the seed's actor loss with respect to `fc2.bias[0]` at θ_old: at θ_old
/// the loss is −mean(r·Â) (every ratio is 1, inside the band), so it is minus the
/// surrogate's gradient.
fn loss_gradient_fc2_bias0(s: &Snapshot) -> Option<f64> {
    let g = &s.cartpole_update()?.gradients;
    let mut start = 0;
    for (name, shape) in &g.shapes {
        if *name == "fc2.bias" {
            return g.surrogate.get(start).map(|&x| -f64::from(x));
        }
        start += shape.iter().product::<usize>();
    }
    None
}

/// Rows of the last epoch with the ratio above the band (`above`) or below it, and a
/// positive (`positive`) or negative advantage.
fn outside(s: &Snapshot, above: bool, positive: bool) -> Option<f64> {
    let b = batch(s)?;
    let ratio = b.epochs.last()?.ratio;
    let eps = hyper(s, "eps")? as f32;
    let n = ratio
        .iter()
        .zip(b.advantage)
        .filter(|&(&r, &a)| {
            let side = if above { r > 1.0 + eps } else { r < 1.0 - eps };
            let sign = if positive { a > 0.0 } else { a < 0.0 };
            side && sign
        })
        .count();
    Some(n as f64)
}

/// Mean and unbiased standard deviation (as `torch.std`) of `xs`, `None` for fewer than 2.
fn mean_std(xs: &[f32]) -> Option<(f64, f64)> {
    if xs.len() < 2 {
        return None;
    }
    let n = xs.len() as f64;
    let mean = xs.iter().map(|&x| f64::from(x)).sum::<f64>() / n;
    let var = xs
        .iter()
        .map(|&x| (f64::from(x) - mean).powi(2))
        .sum::<f64>()
        / (n - 1.0);
    Some((mean, var.sqrt()))
}
