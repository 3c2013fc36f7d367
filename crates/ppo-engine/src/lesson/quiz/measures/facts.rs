//! Measures of facts: values the course teaches, the same in every run with the seed's
//! settings. Each names its fact; no two questions of the course ask the same one.

use super::{Basis, Measure, Snapshot, lambda};
use crate::i18n::Text;

/// The fact that every ratio of an update's first epoch is 1 (θ = θ_old), which several
/// measures read; the course asks it once.
const RATIO_ONE: &str = "every ratio is exactly 1 in epoch 1 (θ = θ_old)";

/// The fact measures.
pub(super) static FACTS: &[Measure] = &[
    Measure {
        name: "batch_rows",
        about: Text::new(
            "transitions in the latest episode's batch",
            "最新回合批次中的状态转移数",
        ),
        value: |s| Some(s.batch()?.rewards.len() as f64),
        choices: 0,
        basis: Basis::Fact("a Pendulum episode, and so its batch, is 200 steps"),
    },
    Measure {
        name: "dones_count",
        about: Text::new(
            "rows of the latest batch with done = 1",
            "最新批次中 done = 1 的行数",
        ),
        value: |s| {
            let dones = s.batch()?.dones;
            Some(dones.iter().filter(|d| **d).count() as f64)
        },
        choices: 0,
        basis: Basis::Fact("a batch is one episode, done only on its last row"),
    },
    Measure {
        name: "obs_dim",
        about: Text::new(
            "numbers in one CartPole observation",
            "一个 CartPole 观测中的数的个数",
        ),
        value: |s| {
            s.cartpole_update()?
                .trace
                .states
                .first()
                .map(|o| o.len() as f64)
        },
        choices: 0,
        basis: Basis::Fact("a CartPole observation is four numbers"),
    },
    Measure {
        name: "actor_parameters",
        about: Text::new(
            "trainable parameters of the actor",
            "策略网络的可训练参数个数",
        ),
        value: |s| parameters(s, "actor."),
        choices: 0,
        basis: Basis::Fact("the actor has 898 parameters"),
    },
    Measure {
        name: "critic_parameters",
        about: Text::new(
            "trainable parameters of the critic",
            "价值网络的可训练参数个数",
        ),
        value: |s| parameters(s, "critic."),
        choices: 0,
        basis: Basis::Fact("the critic has 769 parameters"),
    },
    Measure {
        name: "probs_row_sum",
        about: Text::new(
            "π(left|s_0) + π(right|s_0) for the batch's first row",
            "批次第一行的 π(left|s_0) + π(right|s_0)",
        ),
        value: |s| {
            s.cartpole_update()?
                .probs
                .first()
                .map(|p| f64::from(p[0]) + f64::from(p[1]))
        },
        choices: 0,
        basis: Basis::Fact("softmax rows sum to 1"),
    },
    Measure {
        name: "entropy_max",
        about: Text::new(
            "the largest entropy of a policy over CartPole's actions, in nats",
            "CartPole 动作上策略熵的最大值（单位：奈特）",
        ),
        value: |s| {
            s.cartpole_update()?
                .probs
                .first()
                .map(|p| (p.len() as f64).ln())
        },
        choices: 0,
        basis: Basis::Fact("the entropy of two actions is at most ln 2"),
    },
    Measure {
        name: "td_target_last",
        about: Text::new(
            "the TD target of the batch's last row",
            "批次最后一行的 TD 目标",
        ),
        value: |s| {
            s.cartpole_update()?
                .trace
                .td_target
                .last()
                .map(|&v| f64::from(v))
        },
        choices: 0,
        basis: Basis::Fact("done masks V(s') on the last row: its TD target is its reward"),
    },
    Measure {
        name: "gamma_lambda",
        about: Text::new("γ·λ of the run", "本次运行的 γ·λ"),
        value: |s| Some(s.gamma * lambda(s)?),
        choices: 0,
        basis: Basis::Fact("γλ = 0.931"),
    },
    Measure {
        name: "discount_50",
        about: Text::new(
            "γ^50, the weight of a reward 50 steps ahead",
            "γ^50，即 50 步之后一个奖励的权重",
        ),
        value: |s| Some(s.gamma.powi(50)),
        choices: 0,
        basis: Basis::Fact("γ^50 ≈ 0.364"),
    },
    Measure {
        name: "horizon_gamma",
        about: Text::new("1/(1 − γ)", "1/(1 − γ)"),
        value: |s| Some(1.0 / (1.0 - s.gamma)),
        choices: 0,
        basis: Basis::Fact("the horizon 1/(1 − γ)"),
    },
    Measure {
        name: "horizon_gae",
        about: Text::new("1/(1 − γλ)", "1/(1 − γλ)"),
        value: |s| Some(1.0 / (1.0 - s.gamma * lambda(s)?)),
        choices: 0,
        basis: Basis::Fact("GAE's horizon 1/(1 − γλ)"),
    },
    Measure {
        name: "advantage_last_minus_td_delta_last",
        about: Text::new(
            "Â_T − δ_T for the batch's last row",
            "批次最后一行的 Â_T − δ_T",
        ),
        value: |s| {
            let t = &s.cartpole_update()?.trace;
            Some(f64::from(*t.advantage.last()?) - f64::from(*t.td_delta.last()?))
        },
        choices: 0,
        basis: Basis::Fact("the last advantage is the last TD error"),
    },
    Measure {
        name: "ratio_epoch1_min",
        about: Text::new("the smallest ratio in epoch 1", "第 1 轮中最小的比率"),
        value: |s| first_ratios(s).map(min),
        choices: 0,
        basis: Basis::Fact(RATIO_ONE),
    },
    Measure {
        name: "ratio_epoch1_max",
        about: Text::new("the largest ratio in epoch 1", "第 1 轮中最大的比率"),
        value: |s| first_ratios(s).map(max),
        choices: 0,
        basis: Basis::Fact(RATIO_ONE),
    },
    Measure {
        name: "clipped_rows_epoch1",
        about: Text::new(
            "rows with the clip active in epoch 1",
            "第 1 轮中截断生效的行数",
        ),
        value: |s| first_epoch(s, |e| e.clipped.iter().filter(|c| **c).count() as f64),
        choices: 0,
        basis: Basis::Fact(RATIO_ONE),
    },
    Measure {
        name: "clip_frac_epoch1",
        about: Text::new(
            "the clip fraction of epoch 1",
            "第 1 轮的截断比例（clip fraction）",
        ),
        value: |s| first_epoch(s, |e| f64::from(e.clip_fraction)),
        choices: 0,
        basis: Basis::Fact(RATIO_ONE),
    },
    Measure {
        name: "approx_kl_epoch1",
        about: Text::new("approx_kl in epoch 1", "第 1 轮的 approx_kl"),
        value: |s| first_epoch(s, |e| f64::from(e.approx_kl)),
        choices: 0,
        basis: Basis::Fact(RATIO_ONE),
    },
    Measure {
        name: "actor_loss_epoch1_plus_mean_advantage",
        about: Text::new(
            "the actor loss of epoch 1 plus the batch's mean advantage",
            "第 1 轮的策略网络损失加上批次的平均优势值",
        ),
        value: |s| {
            let t = &s.cartpole_update()?.trace;
            let mean =
                t.advantage.iter().map(|&a| f64::from(a)).sum::<f64>() / t.advantage.len() as f64;
            Some(f64::from(t.epochs.first()?.actor_loss) + mean)
        },
        choices: 0,
        basis: Basis::Fact(RATIO_ONE),
    },
    Measure {
        name: "epochs_run",
        about: Text::new("epochs the latest update ran", "最新一次更新运行的轮数"),
        value: |s| Some(s.cartpole_update()?.trace.epochs_run() as f64),
        choices: 0,
        basis: Basis::Fact("without target_kl every update runs its 10 epochs"),
    },
    Measure {
        name: "grad_max_diff",
        about: Text::new(
            "the largest difference between the two policy gradients at θ_old",
            "θ_old 处两种策略梯度之间的最大差值",
        ),
        value: |s| {
            let g = &s.cartpole_update()?.gradients;
            Some(f64::from(g.max_abs_diff()))
        },
        choices: 0,
        basis: Basis::Fact(RATIO_ONE),
    },
    Measure {
        name: "adv_norm_mean",
        about: Text::new(
            "the mean of the normalised advantages",
            "归一化后优势值的均值",
        ),
        value: |s| normalised(s).map(|(mean, _)| mean),
        choices: 0,
        basis: Basis::Fact("normalised advantages have mean 0"),
    },
    Measure {
        name: "adv_norm_std",
        about: Text::new(
            "the unbiased standard deviation of the normalised advantages",
            "归一化后优势值的无偏标准差",
        ),
        value: |s| normalised(s).map(|(_, std)| std),
        choices: 0,
        basis: Basis::Fact("normalised advantages have standard deviation 1"),
    },
    Measure {
        name: "moving_average_window",
        about: Text::new(
            "the window of the seed's moving average",
            "原教程代码中移动平均的窗口大小",
        ),
        value: |_| Some(crate::lesson::live::session::MOVING_AVERAGE_WINDOW as f64),
        choices: 0,
        basis: Basis::Fact("the seed smooths over 9 episodes"),
    },
];

fn parameters(s: &Snapshot, prefix: &str) -> Option<f64> {
    let n: usize = s
        .weights
        .iter()
        .filter(|(name, _)| name.starts_with(prefix))
        .map(|(_, w)| w.data.len())
        .sum();
    (n > 0).then_some(n as f64)
}

fn first_epoch(s: &Snapshot, f: impl Fn(&crate::ppo::EpochTrace) -> f64) -> Option<f64> {
    s.cartpole_update()?.trace.epochs.first().map(f)
}

/// The ratios of the latest update's first epoch, of any agent.
fn first_ratios(s: &Snapshot) -> Option<&[f32]> {
    s.batch()?.epochs.first().map(|e| e.ratio)
}

fn max(xs: &[f32]) -> f64 {
    xs.iter()
        .map(|&x| f64::from(x))
        .fold(f64::NEG_INFINITY, f64::max)
}

fn min(xs: &[f32]) -> f64 {
    xs.iter()
        .map(|&x| f64::from(x))
        .fold(f64::INFINITY, f64::min)
}

/// Mean and unbiased std of CleanRL's normalised advantages of the latest batch.
fn normalised(s: &Snapshot) -> Option<(f64, f64)> {
    let adv = &s.cartpole_update()?.trace.advantage;
    if adv.len() < 2 {
        return None;
    }
    let out = crate::ppo::advantage::normalize_advantage(adv);
    let n = out.len() as f64;
    let mean = out.iter().map(|&x| f64::from(x)).sum::<f64>() / n;
    let var = out
        .iter()
        .map(|&x| (f64::from(x) - mean).powi(2))
        .sum::<f64>()
        / (n - 1.0);
    Some((mean, var.sqrt()))
}
