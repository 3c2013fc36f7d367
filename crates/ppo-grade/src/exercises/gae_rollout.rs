//! `gae_rollout` (lesson 16): advantages and returns over a rollout of several episodes,
//! CleanRL's layout, telling a time-limit cut from a real end. Its signature, reference,
//! typical mistakes and cases; the hints that name the mistakes are in the lesson's
//! `exercise.toml`.

use crate::plain::*;
use crate::solutions as sol;
use crate::value::{Arg, Kind, OutKind, Output, Tolerance};

use super::td_target_truncation::random_ends;

/// The exercise.
pub const EXERCISE: Plain = Plain {
    name: "gae_rollout",
    lesson: "16-beyond-the-seed",
    params: &[
        ("rewards", Kind::F32s),
        ("values", Kind::F32s),
        ("next_values", Kind::F32s),
        ("terminated", Kind::Bools),
        ("truncated", Kind::Bools),
        ("gamma", Kind::F32),
        ("lmbda", Kind::F32),
    ],
    output: OutKind::F32sPair,
    tolerance: Tolerance {
        abs: 1e-4,
        rel: 1e-4,
    },
    reference: |a| call(a, sol::beyond::gae_rollout),
    mistakes: &[
        Mistake {
            id: "forwards",
            answer: |a| gae(a, Rule::FORWARDS),
        },
        Mistake {
            id: "ignores_episode_ends",
            answer: |a| {
                gae(
                    a,
                    Rule {
                        resets: |_, _| false,
                        ..Rule::RIGHT
                    },
                )
            },
        },
        Mistake {
            id: "resets_only_on_termination",
            answer: |a| {
                gae(
                    a,
                    Rule {
                        resets: |term, _| term,
                        ..Rule::RIGHT
                    },
                )
            },
        },
        Mistake {
            id: "bootstraps_through_termination",
            answer: |a| {
                gae(
                    a,
                    Rule {
                        masks: |_, _| false,
                        ..Rule::RIGHT
                    },
                )
            },
        },
        Mistake {
            id: "stops_at_truncation",
            answer: |a| {
                gae(
                    a,
                    Rule {
                        masks: |term, trunc| term || trunc,
                        ..Rule::RIGHT
                    },
                )
            },
        },
        Mistake {
            id: "returns_are_td_targets",
            answer: |a| {
                gae(
                    a,
                    Rule {
                        returns: Returns::TdTargets,
                        ..Rule::RIGHT
                    },
                )
            },
        },
        Mistake {
            id: "returns_are_advantages",
            answer: |a| {
                gae(
                    a,
                    Rule {
                        returns: Returns::Advantages,
                        ..Rule::RIGHT
                    },
                )
            },
        },
    ],
    checks,
};

/// The signature of `gae_rollout`.
pub type Signature = fn(&[f32], &[f32], &[f32], &[bool], &[bool], f32, f32) -> (Vec<f32>, Vec<f32>);

/// Grades a `gae_rollout` running in this process (a notebook cell): the cases, diagnosis
/// and hints of `ppo-tutor grade gae_rollout`.
#[must_use]
pub fn in_place(f: Signature) -> crate::Report {
    EXERCISE.grade_in_place(std::sync::Arc::new(move |a: Args<'_>| call(a, f)))
}

/// `f` on a case's seven arguments.
fn call(a: Args<'_>, f: Signature) -> Output {
    let (adv, ret) = f(
        a.f32s(0),
        a.f32s(1),
        a.f32s(2),
        a.bools(3),
        a.bools(4),
        a.f32(5),
        a.f32(6),
    );
    Output::F32sPair(adv, ret)
}

/// What a wrong answer takes as the returns.
#[derive(Clone, Copy)]
enum Returns {
    /// `Â + V(s)`, right.
    Lambda,
    /// `r + γ·V(s′)·(1 − terminated)`.
    TdTargets,
    /// `Â` alone.
    Advantages,
}

/// One way of computing GAE over a rollout, right or wrong.
#[derive(Clone, Copy)]
struct Rule {
    /// Where the TD error drops `V(s′)`: `(terminated, truncated)`.
    masks: fn(bool, bool) -> bool,
    /// Where the recursion restarts from 0.
    resets: fn(bool, bool) -> bool,
    /// Whether the recursion runs from the last row back.
    backwards: bool,
    returns: Returns,
}

impl Rule {
    const RIGHT: Self = Self {
        masks: |term, _| term,
        resets: |term, trunc| term || trunc,
        backwards: true,
        returns: Returns::Lambda,
    };
    const FORWARDS: Self = Self {
        backwards: false,
        ..Self::RIGHT
    };
}

fn gae(a: Args<'_>, rule: Rule) -> Output {
    let (r, v, nv, term, trunc) = (a.f32s(0), a.f32s(1), a.f32s(2), a.bools(3), a.bools(4));
    let (gamma, lmbda) = (a.f32(5), a.f32(6));
    let n = r.len();
    let targets: Vec<f32> = (0..n)
        .map(|t| {
            let alive = if (rule.masks)(term[t], trunc[t]) {
                0.0
            } else {
                1.0
            };
            r[t] + gamma * nv[t] * alive
        })
        .collect();
    let mut adv = vec![0.0_f32; n];
    let mut carry = 0.0_f32;
    let order: Vec<usize> = if rule.backwards {
        (0..n).rev().collect()
    } else {
        (0..n).collect()
    };
    for t in order {
        let same = if (rule.resets)(term[t], trunc[t]) {
            0.0
        } else {
            1.0
        };
        carry = (targets[t] - v[t]) + gamma * lmbda * same * carry;
        adv[t] = carry;
    }
    let returns = match rule.returns {
        Returns::Lambda => adv.iter().zip(v).map(|(a, v)| a + v).collect(),
        Returns::TdTargets => targets,
        Returns::Advantages => adv.clone(),
    };
    Output::F32sPair(adv, returns)
}

/// The checks, with their cases (deterministic: seeded).
fn checks() -> Vec<CheckCases> {
    let random = random(18, |g| {
        let n = g.int(3, 80);
        let rewards = if g.chance(0.6) {
            vec![1.0; n]
        } else {
            g.f32s(n, -2.0, 2.0)
        };
        let (terminated, truncated) = random_ends(g, n);
        let (gamma, lmbda) = if g.chance(0.5) {
            (0.98, 0.95)
        } else {
            (g.f(0.5, 1.0), g.f(0.3, 1.0))
        };
        let values = g.f32s(n, -5.0, 50.0);
        let next_values = g.f32s(n, -5.0, 50.0);
        case(
            rewards,
            values,
            next_values,
            terminated,
            truncated,
            gamma,
            lmbda,
        )
    });
    // The recorded CartPole episodes, one after another in one rollout.
    let batches = fixture_batches();
    let mut joined = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    for b in batches {
        joined.0.extend(&b.rewards);
        joined.1.extend(&b.values);
        joined.2.extend(&b.next_values);
        joined.3.extend(&b.dones);
    }
    let config = batches
        .first()
        .map(|b| b.config.clone())
        .unwrap_or_default();
    let n = joined.0.len();
    let recorded = check(
        Text::new(
            "the recorded PyTorch episodes, as one rollout",
            "录制的 PyTorch 回合，连成一段采样",
        ),
        vec![case(
            joined.0,
            joined.1,
            joined.2,
            joined.3,
            vec![false; n],
            config.gamma as f32,
            config.lmbda as f32,
        )],
    );
    let cut_then_new = vec![case(
        vec![1.0; 4],
        vec![40.0, 41.0, 5.0, 6.0],
        vec![41.0, 48.0, 6.0, 7.0],
        vec![false; 4],
        vec![false, true, false, false],
        0.98,
        0.95,
    )];
    let fell_then_new = vec![case(
        vec![1.0; 4],
        vec![3.0, 2.0, 5.0, 6.0],
        vec![2.0, 9.0, 6.0, 7.0],
        vec![false, true, false, false],
        vec![false; 4],
        0.98,
        0.95,
    )];
    let unfinished = vec![case(
        vec![1.0; 3],
        vec![10.0, 11.0, 12.0],
        vec![11.0, 12.0, 13.0],
        vec![false; 3],
        vec![false; 3],
        0.98,
        0.95,
    )];
    vec![
        random,
        recorded,
        check(
            Text::new(
                "a time-limit cut, then a new episode",
                "时限中断后开始新回合",
            ),
            cut_then_new,
        ),
        check(
            Text::new("a fall, then a new episode", "杆倒下后开始新回合"),
            fell_then_new,
        ),
        check(
            Text::new("a rollout that ends mid-episode", "在回合中途结束的采样"),
            unfinished,
        ),
    ]
}

fn case(
    rewards: Vec<f32>,
    values: Vec<f32>,
    next_values: Vec<f32>,
    terminated: Vec<bool>,
    truncated: Vec<bool>,
    gamma: f32,
    lmbda: f32,
) -> Vec<Arg> {
    vec![
        Arg::F32s(rewards),
        Arg::F32s(values),
        Arg::F32s(next_values),
        Arg::Bools(terminated),
        Arg::Bools(truncated),
        Arg::F32(gamma),
        Arg::F32(lmbda),
    ]
}
