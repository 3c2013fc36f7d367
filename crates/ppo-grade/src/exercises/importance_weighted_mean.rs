//! `importance_weighted_mean` (lesson 9): the new policy's mean return estimated from the
//! old policy's samples, each return weighted by its importance ratio. It tests what the
//! ratio is for (reweighting samples drawn by another policy) in a situation the lesson does
//! not show: a plain average, any number of actions. Its signature, reference, typical
//! mistakes and cases; the hints that name the mistakes are in the lesson's `exercise.toml`.

use crate::plain::*;
use crate::solutions as sol;
use crate::value::{Arg, Kind, OutKind, Output};

/// The exercise.
pub const EXERCISE: Plain = Plain {
    name: "importance_weighted_mean",
    lesson: "09-ratio",
    params: &[
        ("probs", Kind::F32s),
        ("n_actions", Kind::Usize),
        ("actions", Kind::Usizes),
        ("old_log_probs", Kind::F32s),
        ("returns", Kind::F32s),
    ],
    output: OutKind::F32,
    tolerance: LOSS_TOL,
    reference: |a| {
        Output::F32(sol::ratio::importance_weighted_mean(
            a.f32s(0),
            a.usize(1),
            a.usizes(2),
            a.f32s(3),
            a.f32s(4),
        ))
    },
    mistakes: &[
        Mistake {
            id: "unweighted",
            answer: |a| Output::F32(mean(a.f32s(4).iter().copied())),
        },
        Mistake {
            id: "inverted_ratio",
            answer: |a| weighted_mean(a, row_major, |new, old| (old - new.ln()).exp()),
        },
        Mistake {
            id: "log_ratio_as_weight",
            answer: |a| weighted_mean(a, row_major, |new, old| new.ln() - old),
        },
        Mistake {
            id: "new_prob_as_weight",
            answer: |a| weighted_mean(a, row_major, |new, _| new),
        },
        Mistake {
            id: "wrong_row_index",
            answer: |a| weighted_mean(a, column_major, ratio),
        },
        Mistake {
            id: "self_normalised",
            answer: |a| {
                let samples = samples(a, row_major);
                let weights: Vec<f32> = samples.iter().map(|s| ratio(s.new, s.old)).collect();
                let total = sum(samples.iter().zip(&weights).map(|(s, w)| w * s.ret));
                Output::F32(total / sum(weights.iter().copied()))
            },
        },
    ],
    checks,
};

/// The signature of `importance_weighted_mean`.
pub type Signature = fn(&[f32], usize, &[usize], &[f32], &[f32]) -> f32;

/// Grades an `importance_weighted_mean` running in this process (a notebook cell): the
/// cases, diagnosis and hints of `ppo-tutor grade importance_weighted_mean`.
#[must_use]
pub fn in_place(f: Signature) -> crate::Report {
    EXERCISE.grade_in_place(std::sync::Arc::new(move |a: Args<'_>| {
        Output::F32(f(a.f32s(0), a.usize(1), a.usizes(2), a.f32s(3), a.f32s(4)))
    }))
}

/// One sample: the probability read for its action, `log π_old(a|s)` and its return.
struct Sample {
    new: f32,
    old: f32,
    ret: f32,
}

/// Where sample `i`'s action `action` is in `probs` (`n` samples, `k` actions): row-major.
fn row_major(i: usize, action: usize, _n: usize, k: usize) -> usize {
    i * k + action
}

/// Column-major: the mistake of reading `probs` as one column per action.
fn column_major(i: usize, action: usize, n: usize, _k: usize) -> usize {
    action * n + i
}

/// `exp(ln π_new − log π_old)`, the ratio.
fn ratio(new: f32, old: f32) -> f32 {
    (new.ln() - old).exp()
}

fn samples(a: Args<'_>, index: fn(usize, usize, usize, usize) -> usize) -> Vec<Sample> {
    let (probs, k, actions) = (a.f32s(0), a.usize(1), a.usizes(2));
    let n = actions.len();
    actions
        .iter()
        .zip(a.f32s(3))
        .zip(a.f32s(4))
        .enumerate()
        .map(|(i, ((&action, &old), &ret))| Sample {
            new: probs.get(index(i, action, n, k)).copied().unwrap_or(1.0),
            old,
            ret,
        })
        .collect()
}

/// The mean of `weight(π read, log π_old) · return` over the samples.
fn weighted_mean(
    a: Args<'_>,
    index: fn(usize, usize, usize, usize) -> usize,
    weight: impl Fn(f32, f32) -> f32,
) -> Output {
    Output::F32(mean(
        samples(a, index)
            .iter()
            .map(|s| weight(s.new, s.old) * s.ret),
    ))
}

/// `k` probabilities, each at least `floor` before normalising.
fn distribution(g: &mut Gen, k: usize, floor: f32) -> Vec<f32> {
    let raw = g.f32s(k, floor, 1.0);
    let total: f32 = raw.iter().sum();
    raw.iter().map(|p| p / total).collect()
}

/// An action drawn from `probs`.
fn draw(g: &mut Gen, probs: &[f32]) -> usize {
    let mut u = g.f(0.0, 1.0);
    for (action, p) in probs.iter().enumerate() {
        if u < *p {
            return action;
        }
        u -= p;
    }
    probs.len() - 1
}

/// `old` moved a little: each probability scaled by `e^x`, `x` uniform in `±spread`.
fn moved(g: &mut Gen, old: &[f32], spread: f32) -> Vec<f32> {
    let raw: Vec<f32> = old.iter().map(|p| p * g.f(-spread, spread).exp()).collect();
    let total: f32 = raw.iter().sum();
    raw.iter().map(|p| p / total).collect()
}

/// The discounted return after each step of an episode.
fn returns_to_go(rewards: &[f32], gamma: f32) -> Vec<f32> {
    let mut out = vec![0.0; rewards.len()];
    let mut running = 0.0_f32;
    for (t, r) in rewards.iter().enumerate().rev() {
        running = r + gamma * running;
        out[t] = running;
    }
    out
}

/// A random case: `n` samples over `k` actions, the new policy `spread` away from the old.
fn random_case(g: &mut Gen, n: usize, k: usize, spread: f32) -> Vec<Arg> {
    let mut probs = Vec::with_capacity(n * k);
    let mut actions = Vec::with_capacity(n);
    let mut old_log_probs = Vec::with_capacity(n);
    for _ in 0..n {
        let old = distribution(g, k, 0.05);
        let action = draw(g, &old);
        actions.push(action);
        old_log_probs.push(old[action].ln());
        probs.extend(moved(g, &old, spread));
    }
    let returns = if g.chance(0.5) {
        g.f32s(n, 1.0, 50.0)
    } else {
        g.f32s(n, -10.0, 30.0)
    };
    case(probs, k, actions, old_log_probs, returns)
}

/// The checks, with their cases (deterministic: seeded).
fn checks() -> Vec<CheckCases> {
    let random = random(91, |g| {
        let n = g.int(1, 40);
        let k = g.int(2, 6);
        random_case(g, n, k, 0.8)
    });
    let recorded = fixture(|b| {
        let returns = returns_to_go(&b.rewards, b.config.gamma as f32);
        let old_probs: Vec<f32> = b.probs.iter().flatten().copied().collect();
        let mut cases = vec![case(
            old_probs,
            2,
            b.actions.clone(),
            b.old_log_probs.clone(),
            returns.clone(),
        )];
        if let Some((log_probs, _)) = b.epochs.last() {
            let new_probs = log_probs
                .iter()
                .zip(&b.actions)
                .flat_map(|(lp, &action)| {
                    let p = lp.exp();
                    if action == 0 {
                        [p, 1.0 - p]
                    } else {
                        [1.0 - p, p]
                    }
                })
                .collect();
            cases.push(case(
                new_probs,
                2,
                b.actions.clone(),
                b.old_log_probs.clone(),
                returns,
            ));
        }
        cases
    });
    let same_policy = vec![
        case(
            vec![0.25, 0.75],
            2,
            vec![1],
            vec![0.75_f32.ln()],
            vec![12.0],
        ),
        case(
            vec![0.2, 0.5, 0.3, 0.6, 0.1, 0.3],
            3,
            vec![2, 0],
            vec![0.3_f32.ln(), 0.6_f32.ln()],
            vec![4.0, -2.0],
        ),
    ];
    let rare = vec![
        case(
            vec![
                0.1, 0.2, 0.3, 0.4, 0.7, 0.1, 0.1, 0.1, 0.25, 0.25, 0.25, 0.25,
            ],
            4,
            vec![3, 0, 1],
            vec![0.02_f32.ln(), 0.7_f32.ln(), 0.25_f32.ln()],
            vec![30.0, 10.0, 5.0],
        ),
        case(
            vec![0.5, 0.5, 0.9, 0.1],
            2,
            vec![0, 1],
            vec![0.01_f32.ln(), 0.5_f32.ln()],
            vec![2.0, 20.0],
        ),
    ];
    let mut g = Gen::new(92);
    let many_actions = (0..5).map(|_| random_case(&mut g, 12, 6, 1.2)).collect();
    vec![
        random,
        recorded,
        check(
            Text::new(
                "the same policy: every weight is 1",
                "同一个策略：每个权重都是 1",
            ),
            same_policy,
        ),
        check(
            Text::new("a rare action: a large weight", "罕见的动作：很大的权重"),
            rare,
        ),
        check(
            Text::new("six actions per row", "每行六个动作"),
            many_actions,
        ),
    ]
}

fn case(
    probs: Vec<f32>,
    n_actions: usize,
    actions: Vec<usize>,
    old_log_probs: Vec<f32>,
    returns: Vec<f32>,
) -> Vec<Arg> {
    vec![
        Arg::F32s(probs),
        Arg::Usize(n_actions),
        Arg::Usizes(actions),
        Arg::F32s(old_log_probs),
        Arg::F32s(returns),
    ]
}
