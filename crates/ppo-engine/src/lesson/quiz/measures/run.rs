//! Run measures: numbers of this run that follow from givens by what a lesson taught. The
//! value is the agent's own; `from` is the lesson's formula on the shown givens, and a test
//! checks that the two agree, and that the value differs from run to run.

use super::{Basis, Measure, at, batch, clipped_objective, extreme_row, from_end, hyper};
use crate::i18n::Text;
use crate::lesson::AgentKind;

/// The run measures.
pub(super) static RUN: &[Measure] = &[
    Measure {
        name: "log_prob_taken_first",
        about: Text::new(
            "log π_θ(a_0|s_0), the log-probability of the first row's action",
            "log π_θ(a_0|s_0)，第一行所取动作的对数概率",
        ),
        value: |s| at(&s.cartpole_update()?.trace.old_log_probs, 0),
        choices: 0,
        basis: Basis::Run {
            given: &["prob_left_first", "prob_right_first", "action_first"],
            from: |g| if g[2] < 0.5 { g[0].ln() } else { g[1].ln() },
        },
    },
    Measure {
        name: "theta_next_last",
        about: Text::new(
            "the pole angle of the observation that ended the episode",
            "结束该回合的那个观测中的杆角",
        ),
        value: |s| {
            s.cartpole_update()?
                .trace
                .next_states
                .last()
                .map(|o| f64::from(o[2]))
        },
        choices: 0,
        basis: Basis::Run {
            given: &["theta_last", "theta_dot_last"],
            // Explicit Euler with τ = 0.02 s: the angle moves with the velocity from before
            // the step.
            from: |g| g[0] + 0.02 * g[1],
        },
    },
    Measure {
        name: "right_per_100_first",
        about: Text::new(
            "pushes to the right expected in 100 visits to the first state",
            "在第一个状态上访问 100 次，预期向右推的次数",
        ),
        value: |s| {
            s.cartpole_update()?
                .probs
                .first()
                .map(|p| 100.0 * f64::from(p[1]))
        },
        choices: 0,
        basis: Basis::Run {
            given: &["prob_left_first"],
            from: |g| 100.0 * (1.0 - g[0]),
        },
    },
    Measure {
        name: "mc_advantage_first",
        about: Text::new(
            "G_0 − V(s_0), REINFORCE-with-baseline's weight on the first action",
            "G_0 − V(s_0)，带基线的 REINFORCE 对第一个动作的权重",
        ),
        value: |s| {
            let t = &s.cartpole_update()?.trace;
            let g = crate::lesson::live::values::return_to_go(&t.rewards, &t.dones, s.gamma);
            Some(g.first()? - at(&t.values, 0)?)
        },
        choices: 0,
        basis: Basis::Run {
            given: &["batch_rows", "gamma", "value_first"],
            // Reward 1 for each of the L steps: G_0 = 1 + γ + … + γ^(L−1).
            from: |g| (1.0 - g[1].powf(g[0])) / (1.0 - g[1]) - g[2],
        },
    },
    Measure {
        name: "logit_gap_first",
        about: Text::new(
            "z_0 − z_1, the actor's logit difference in the first state",
            "z_0 − z_1，策略网络在第一个状态上两个 logit 之差",
        ),
        value: |s| {
            let p = s.cartpole_update()?.probs.first()?;
            Some((f64::from(p[0]) / f64::from(p[1])).ln())
        },
        choices: 0,
        basis: Basis::Run {
            given: &["prob_left_first", "prob_right_first"],
            from: |g| (g[0] / g[1]).ln(),
        },
    },
    Measure {
        name: "adam_first_step_fc2_bias0",
        about: Text::new(
            "how far Adam's first step (t = 1) moves fc2.bias[0] with this gradient",
            "以这个梯度走 Adam 的第一步（t = 1）时，fc2.bias[0] 移动的量",
        ),
        value: |s| {
            let lr = hyper(s, "actor_lr")?;
            let g = super::measure("grad_fc2_bias0").and_then(|m| (m.value)(s))?;
            Some(adam_first_step(lr, g))
        },
        choices: 0,
        basis: Basis::Run {
            given: &["actor_lr", "grad_fc2_bias0"],
            from: |g| adam_first_step(g[0], g[1]),
        },
    },
    Measure {
        name: "td_delta_first",
        about: Text::new(
            "δ_0, the TD error of the batch's first row",
            "δ_0，批次第一行的 TD 误差",
        ),
        value: |s| at(&s.cartpole_update()?.trace.td_delta, 0),
        choices: 0,
        basis: Basis::Run {
            given: &["gamma", "value_first", "next_value_first"],
            // r_0 = 1 and done_0 = 0 on the first row of a CartPole episode.
            from: |g| 1.0 + g[0] * g[2] - g[1],
        },
    },
    Measure {
        name: "gae_last3",
        about: Text::new(
            "Â_{T−3}, the GAE advantage of the batch's third-to-last row",
            "Â_{T−3}，批次倒数第三行的 GAE 优势值",
        ),
        // The λ-return less the value: the advantage before any normalisation.
        value: |s| {
            let t = &s.cartpole_update()?.trace;
            Some(from_end(&t.lambda_return, 3)? - from_end(&t.values, 3)?)
        },
        choices: 0,
        basis: Basis::Run {
            given: &[
                "gamma_lambda",
                "td_delta_last3",
                "td_delta_last2",
                "td_delta_last",
            ],
            from: |g| g[1] + g[0] * (g[2] + g[0] * g[3]),
        },
    },
    Measure {
        name: "ratio_last_first",
        about: Text::new(
            "the first row's ratio in the update's last epoch",
            "更新最后一轮中第一行的比率",
        ),
        value: |s| at(batch(s)?.epochs.last()?.ratio, 0),
        choices: 0,
        basis: Basis::Run {
            given: &["log_prob_last_first", "old_log_prob_first"],
            from: |g| (g[0] - g[1]).exp(),
        },
    },
    Measure {
        name: "kl_at_ratio_max_last",
        about: Text::new(
            "KL(π_old ‖ π_θ) at the state of the last epoch's largest-ratio row, between the \
             policy that played and the last epoch's",
            "最后一轮比率最大那一行的状态上，采样这批数据的策略与最后一轮的策略之间的 KL(π_old ‖ π_θ)",
        ),
        // CartPole only (`trace`): the two-action KL from the taken action's probabilities.
        value: |s| {
            let t = &s.cartpole_update()?.trace;
            let i = extreme_row(s, true)?;
            let p = at(&t.old_log_probs, i)?.exp();
            let q = at(&t.epochs.last()?.log_probs, i)?.exp();
            Some(kl_two_actions(p, q))
        },
        choices: 0,
        basis: Basis::Run {
            given: &["ratio_max_last", "prob_old_at_ratio_max_last"],
            // The last epoch's policy gives the action q = r·p, the other action 1 − q.
            from: |g| kl_two_actions(g[1], g[0] * g[1]),
        },
    },
    Measure {
        name: "trpo_c",
        about: Text::new(
            "TRPO's C = 4·γ·max|A| / (1 − γ)², with the batch's largest |Â| for max|A|",
            "TRPO 的 C = 4·γ·max|A| / (1 − γ)²，用批次中最大的 |Â| 代替 max|A|",
        ),
        value: |s| {
            let adv = &s.cartpole_update()?.trace.advantage;
            let largest = adv.iter().map(|a| f64::from(a.abs())).reduce(f64::max)?;
            Some(trpo_c(hyper(s, "gamma")?, largest))
        },
        choices: 0,
        basis: Basis::Run {
            given: &["gamma", "adv_abs_max"],
            from: |g| trpo_c(g[0], g[1]),
        },
    },
    Measure {
        name: "pull_at_ratio_max_last",
        about: Text::new(
            "what the clipped objective does to the ratio of the last epoch's largest-ratio \
             row (0 pushes it up, 1 down, 2 nothing)",
            "截断后的目标对最后一轮比率最大那一行的比率的作用（0 向上推，1 向下推，2 不推）",
        ),
        value: |s| {
            if !clipped_objective(s) {
                return None;
            }
            let b = batch(s)?;
            let i = extreme_row(s, true)?;
            Some(pull(
                at(b.epochs.last()?.ratio, i)?,
                at(b.advantage, i)?,
                hyper(s, "eps")?,
            ))
        },
        choices: 3,
        basis: Basis::Run {
            given: &["ratio_max_last", "adv_at_ratio_max_last", "eps"],
            from: |g| pull(g[0], g[1], g[2]),
        },
    },
    Measure {
        name: "loss_term_ratio_min_last",
        about: Text::new(
            "−min(r·Â, clip(r, 1 − ε, 1 + ε)·Â) of the last epoch's smallest-ratio row",
            "最后一轮比率最小那一行的 −min(r·Â, clip(r, 1 − ε, 1 + ε)·Â)",
        ),
        value: |s| {
            if !clipped_objective(s) {
                return None;
            }
            let b = batch(s)?;
            let i = extreme_row(s, false)?;
            let e = b.epochs.last()?;
            Some(-at(e.surr1, i)?.min(at(e.surr2, i)?))
        },
        choices: 0,
        basis: Basis::Run {
            given: &["ratio_min_last", "adv_at_ratio_min_last", "eps"],
            from: |g| -(g[0] * g[1]).min(g[0].clamp(1.0 - g[2], 1.0 + g[2]) * g[1]),
        },
    },
    Measure {
        name: "clip_frac_last",
        about: Text::new(
            "clip_frac, the clip fraction of the update's last epoch",
            "clip_frac，更新最后一轮的截断比例",
        ),
        value: |s| {
            let t = &s.cartpole_update()?.trace;
            t.epochs.last().map(|e| f64::from(e.clip_fraction))
        },
        choices: 0,
        basis: Basis::Run {
            given: &[
                "above_pos_last",
                "above_neg_last",
                "below_pos_last",
                "below_neg_last",
                "batch_rows",
            ],
            from: |g| (g[0] + g[1] + g[2] + g[3]) / g[4],
        },
    },
    Measure {
        name: "moving_average_second",
        about: Text::new(
            "the seed's moving average at index 1",
            "原教程代码的移动平均在下标 1 处的值",
        ),
        value: |s| s.moving_average.get(1).copied(),
        choices: 0,
        basis: Basis::Run {
            given: &["return_first", "return_second", "return_third"],
            from: |g| (g[0] + g[1] + g[2]) / 3.0,
        },
    },
    Measure {
        name: "env_steps",
        about: Text::new(
            "environment steps of the run so far",
            "本次运行到目前为止的环境时间步数",
        ),
        value: |s| (s.agent() == AgentKind::CartPole).then_some(s.env_steps as f64),
        choices: 0,
        basis: Basis::Run {
            given: &["episodes", "mean_return"],
            from: |g| g[0] * g[1],
        },
    },
    Measure {
        name: "adv_norm_first",
        about: Text::new(
            "Â_0 after CleanRL's normalisation",
            "经 CleanRL 归一化之后的 Â_0",
        ),
        value: |s| {
            let adv = &s.cartpole_update()?.trace.advantage;
            if adv.len() < 2 {
                return None;
            }
            at(&crate::ppo::advantage::normalize_advantage(adv), 0)
        },
        choices: 0,
        basis: Basis::Run {
            given: &["adv_first", "adv_mean", "adv_std"],
            from: |g| (g[0] - g[1]) / (g[2] + 1e-8),
        },
    },
    Measure {
        name: "log_density_first",
        about: Text::new(
            "log N(a_0; μ, σ), the first row's old log-density",
            "log N(a_0; μ, σ)，第一行的旧对数密度",
        ),
        value: |s| at(&s.pendulum_update()?.trace.old_log_probs, 0),
        choices: 0,
        basis: Basis::Run {
            given: &["mu_first", "std_first", "action_first"],
            from: |g| {
                let z = (g[2] - g[0]) / g[1];
                -0.5 * z * z - g[1].ln() - 0.5 * (2.0 * std::f64::consts::PI).ln()
            },
        },
    },
    Measure {
        name: "reward_first",
        about: Text::new(
            "the reward of the batch's first Pendulum step",
            "批次第一个倒立摆时间步的奖励",
        ),
        value: |s| at(&s.pendulum_update()?.trace.rewards, 0),
        choices: 0,
        basis: Basis::Run {
            given: &["cos_first", "sin_first", "theta_dot_first", "action_first"],
            from: |g| {
                let theta = g[1].atan2(g[0]);
                let u = g[3].clamp(-2.0, 2.0);
                -(theta * theta + 0.1 * g[2] * g[2] + 0.001 * u * u)
            },
        },
    },
];

/// Adam's first step (t = 1) on a weight with gradient `g`: m̂ = g and v̂ = g², so the
/// weight moves by −lr·g/(|g| + 1e-8), about −lr·sign(g).
fn adam_first_step(lr: f64, g: f64) -> f64 {
    -lr * g / (g.abs() + 1e-8)
}

/// `KL(π_old ‖ π_θ)` between two policies over two actions that give the first action `p`
/// and `q`: `p·ln(p/q) + (1 − p)·ln((1 − p)/(1 − q))`.
fn kl_two_actions(p: f64, q: f64) -> f64 {
    p * (p / q).ln() + (1.0 - p) * ((1.0 - p) / (1.0 - q)).ln()
}

/// The constant of TRPO's bound, `4·γ·max|A| / (1 − γ)²` (Schulman et al., 2015, with
/// `max|A|` the largest absolute advantage).
fn trpo_c(gamma: f64, max_abs_advantage: f64) -> f64 {
    4.0 * gamma * max_abs_advantage / (1.0 - gamma).powi(2)
}

/// What PPO's clipped objective does to a row's ratio `r` with advantage `adv`: 0 pushes it
/// up, 1 pushes it down, 2 nothing (the min picks the clamped, constant term).
fn pull(r: f64, adv: f64, eps: f64) -> f64 {
    if adv > 0.0 && r <= 1.0 + eps {
        0.0
    } else if adv < 0.0 && r >= 1.0 - eps {
        1.0
    } else {
        2.0
    }
}
