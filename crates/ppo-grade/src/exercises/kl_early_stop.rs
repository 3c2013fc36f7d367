//! `kl_early_stop` (lesson 13): Spinning Up's early stopping, the k1 estimate of the KL
//! divergence tested against 1.5 × `target_kl` before each epoch's step. Its signature,
//! reference, typical mistakes and cases; the hints that name the mistakes are in the
//! lesson's `exercise.toml`.

use crate::plain::*;
use crate::solutions as sol;
use crate::value::{Arg, Kind, OutKind, Output};

/// The exercise.
pub const EXERCISE: Plain = Plain {
    name: "kl_early_stop",
    lesson: "13-clip-lab",
    params: &[
        ("old_log_probs", Kind::F32s),
        ("log_probs_per_epoch", Kind::F32s),
        ("target_kl", Kind::F32),
    ],
    output: OutKind::Usize,
    tolerance: F32_TOL,
    reference: |a| Output::Usize(sol::clip_lab::kl_early_stop(a.f32s(0), a.f32s(1), a.f32(2))),
    mistakes: &[
        Mistake {
            id: "k3_estimator",
            answer: |a| steps(a, k3, 1.5, 0),
        },
        Mistake {
            id: "inverted_sign",
            answer: |a| steps(a, |old, new| new - old, 1.5, 0),
        },
        Mistake {
            id: "no_margin",
            answer: |a| steps(a, k1, 1.0, 0),
        },
        Mistake {
            id: "counts_the_overshooting_step",
            answer: |a| steps(a, k1, 1.5, 1),
        },
        Mistake {
            id: "absolute_difference",
            answer: |a| steps(a, |old, new| (old - new).abs(), 1.5, 0),
        },
        Mistake {
            id: "stops_at_the_threshold",
            answer: |a| {
                let kls = estimates(a.f32s(0), a.f32s(1), k1);
                let limit = 1.5 * a.f32(2);
                Output::Usize(kls.iter().position(|&kl| kl >= limit).unwrap_or(kls.len()))
            },
        },
    ],
    checks,
};

/// The signature of `kl_early_stop`.
pub type Signature = fn(&[f32], &[f32], f32) -> usize;

/// Grades a `kl_early_stop` running in this process (a notebook cell): the cases,
/// diagnosis and hints of `ppo-tutor grade kl_early_stop`.
#[must_use]
pub fn in_place(f: Signature) -> crate::Report {
    EXERCISE.grade_in_place(std::sync::Arc::new(move |a: Args<'_>| {
        Output::Usize(f(a.f32s(0), a.f32s(1), a.f32(2)))
    }))
}

/// One row of Spinning Up's estimate: `log π_old − log π`.
fn k1(old: f32, new: f32) -> f32 {
    old - new
}

/// One row of CleanRL's `approx_kl`: `(r − 1) − log r`.
fn k3(old: f32, new: f32) -> f32 {
    ((new - old).exp() - 1.0) - (new - old)
}

/// The mean over the rows of `row(old, new)` for each epoch's row of log-probabilities.
fn estimates(old: &[f32], per_epoch: &[f32], row: impl Fn(f32, f32) -> f32) -> Vec<f32> {
    per_epoch
        .chunks(old.len().max(1))
        .map(|log_probs| mean(old.iter().zip(log_probs).map(|(&o, &n)| row(o, n))))
        .collect()
}

/// The steps taken when each epoch's `row` estimate is tested against `margin · target_kl`,
/// counting `extra` more once it stops.
fn steps(a: Args<'_>, row: fn(f32, f32) -> f32, margin: f32, extra: usize) -> Output {
    let kls = estimates(a.f32s(0), a.f32s(1), row);
    let limit = margin * a.f32(2);
    Output::Usize(match kls.iter().position(|&kl| kl > limit) {
        Some(epoch) => epoch + extra,
        None => kls.len(),
    })
}

/// The checks, with their cases (deterministic: seeded).
fn checks() -> Vec<CheckCases> {
    let random = random(112, |g| {
        let n = g.int(4, 64);
        let epochs = g.int(1, 40);
        let old: Vec<f32> = (0..n).map(|_| g.f(0.05, 0.95).ln()).collect();
        // Each epoch moves every row a little further: a drift shared by the rows (mostly
        // making the actions taken less likely, sometimes more) plus a spread of each row's
        // own, both ways, and a little noise. Row 0 is the old policy, or close to it.
        let drift = g.f(-0.004, 0.012);
        let spread = g.f(0.0, 0.03);
        let own: Vec<f32> = (0..n).map(|_| g.f(-spread, spread)).collect();
        let start_noise = if g.chance(0.3) { 0.003 } else { 0.0 };
        let mut per_epoch = Vec::with_capacity(n * epochs);
        for e in 0..epochs {
            let moved = e as f32;
            let noise = if e == 0 { start_noise } else { 0.002 };
            for (o, s) in old.iter().zip(&own) {
                let step = moved * (drift + s) + g.f(-noise, noise);
                per_epoch.push((o - step).min(-1e-4));
            }
        }
        // A target whose threshold no epoch's estimate sits on, so that summing in another
        // order cannot change the answer.
        let kls = estimates(&old, &per_epoch, k1);
        let mut target_kl = g.f(0.005, 0.05);
        for _ in 0..100 {
            let limit = 1.5 * target_kl;
            if kls.iter().all(|kl| (kl - limit).abs() > 0.02 * limit) {
                break;
            }
            target_kl = g.f(0.005, 0.05);
        }
        case(old, per_epoch, target_kl)
    });
    // The recorded PyTorch updates at Spinning Up's 0.01 and at 0.001: in one of them the k1
    // estimate stays negative all ten epochs; at 0.001 the other two stop.
    let recorded = fixture(|b| {
        let per_epoch: Vec<f32> = b.epochs.iter().flat_map(|(lp, _)| lp.clone()).collect();
        [0.01, 0.001]
            .into_iter()
            .map(|target_kl| case(b.old_log_probs.clone(), per_epoch.clone(), target_kl))
            .collect()
    });
    let old = vec![-0.69, -0.36, -1.2, -0.69];
    // Rows moved both ways: the estimate stays small, the moves do not.
    let never = vec![case(
        old.clone(),
        shifted(
            &old,
            &[
                [0.0; 4],
                [0.02, -0.02, 0.02, -0.02],
                [0.05, -0.04, 0.03, -0.03],
            ],
        ),
        0.01,
    )];
    // Every sampled action made more likely: the estimate goes negative.
    let more_likely = vec![case(
        old.clone(),
        shifted(&old, &[[0.0; 4], [-0.02; 4], [-0.04; 4], [-0.06; 4]]),
        0.01,
    )];
    // The estimate passes target_kl at epoch 2 and 1.5 × target_kl at epoch 3.
    let margin = vec![case(
        old.clone(),
        shifted(
            &old,
            &[[0.0; 4], [0.006; 4], [0.012; 4], [0.018; 4], [0.024; 4]],
        ),
        0.01,
    )];
    // The policy had already moved before the first step (a row 0 that is not the old
    // policy).
    let before_first = vec![case(
        old.clone(),
        shifted(&old, &[[0.05, 0.03, 0.06, 0.04], [0.08; 4]]),
        0.01,
    )];
    // The estimate lands exactly on 1.5 × target_kl (0 − (−0.015) = 0.015 = 1.5 × 0.01 in
    // f32, whichever way it is summed or compared): it has not passed it, so the step is
    // taken.
    let on_the_threshold = vec![case(vec![0.0], vec![0.0, -0.015], 0.01)];
    vec![
        random,
        recorded,
        check(
            Text::new(
                "never stops: moves both ways that cancel",
                "从不停止：两个方向的变化相互抵消",
            ),
            never,
        ),
        check(
            Text::new(
                "every sampled action made more likely",
                "每个采样到的动作的概率都提高了",
            ),
            more_likely,
        ),
        check(
            Text::new(
                "passes target_kl one epoch before 1.5 × target_kl",
                "越过 target_kl 比越过 1.5 × target_kl 早一轮",
            ),
            margin,
        ),
        check(
            Text::new("stops before the first step", "在第一步之前就停止"),
            before_first,
        ),
        check(
            Text::new(
                "the estimate exactly on 1.5 × target_kl: not past it",
                "估计值恰好等于 1.5 × target_kl：还没有越过",
            ),
            on_the_threshold,
        ),
    ]
}

/// The epochs' rows of log-probabilities: `old` lowered by each row of `drops`.
fn shifted(old: &[f32], drops: &[[f32; 4]]) -> Vec<f32> {
    drops
        .iter()
        .flat_map(|d| old.iter().zip(d).map(|(o, d)| o - d))
        .collect()
}

fn case(old_log_probs: Vec<f32>, log_probs_per_epoch: Vec<f32>, target_kl: f32) -> Vec<Arg> {
    vec![
        Arg::F32s(old_log_probs),
        Arg::F32s(log_probs_per_epoch),
        Arg::F32(target_kl),
    ]
}
