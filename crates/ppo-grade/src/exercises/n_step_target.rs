//! `n_step_target` (lesson 7): the n-step target over a rollout that may hold several
//! episodes, of which the seed's TD target is the case `n = 1`. It tests the idea of the TD
//! target (real rewards, then the critic's discounted guess, never across an episode's end)
//! in a situation the lesson does not show. Its signature, reference, typical mistakes and
//! cases; the hints that name the mistakes are in the lesson's `exercise.toml`.

use crate::plain::*;
use crate::solutions as sol;
use crate::value::{Arg, Kind, OutKind, Output};

/// The exercise.
pub const EXERCISE: Plain = Plain {
    name: "n_step_target",
    lesson: "07-td-target",
    params: &[
        ("rewards", Kind::F32s),
        ("values", Kind::F32s),
        ("dones", Kind::Bools),
        ("gamma", Kind::F32),
        ("n", Kind::Usize),
    ],
    output: OutKind::F32s,
    tolerance: F32_TOL,
    reference: |a| {
        Output::F32s(sol::td_target::n_step_target(
            a.f32s(0),
            a.f32s(1),
            a.bools(2),
            a.f32(3),
            a.usize(4),
        ))
    },
    mistakes: &[
        Mistake {
            id: "one_step_only",
            answer: |a| {
                windows(a, |w| {
                    let mask = if w.done(0) { 0.0 } else { 1.0 };
                    w.reward(0) + w.gamma * w.value(1) * mask
                })
            },
        },
        Mistake {
            id: "crosses_episode_end",
            // The one-step target's (1 − done) mask kept, on the window's last step only:
            // the sum runs on through an earlier done.
            answer: |a| {
                windows(a, |w| {
                    let rewards: f32 = (0..w.m).map(|k| w.discount(k) * w.reward(k)).sum();
                    let mask = if w.done(w.m - 1) { 0.0 } else { 1.0 };
                    rewards + w.discount(w.m) * w.value(w.m) * mask
                })
            },
        },
        Mistake {
            id: "bootstraps_after_done",
            answer: |a| {
                windows(a, |w| {
                    let j = w.rewards_taken();
                    let rewards: f32 = (0..j).map(|k| w.discount(k) * w.reward(k)).sum();
                    rewards + w.discount(j) * w.value(j)
                })
            },
        },
        Mistake {
            id: "bootstrap_off_by_one",
            answer: |a| {
                windows(a, |w| {
                    let j = w.rewards_taken();
                    let rewards: f32 = (0..j).map(|k| w.discount(k) * w.reward(k)).sum();
                    if w.terminated() {
                        rewards
                    } else {
                        rewards + w.discount(j) * w.value(j - 1)
                    }
                })
            },
        },
        Mistake {
            id: "no_discount_on_rewards",
            answer: |a| {
                windows(a, |w| {
                    let j = w.rewards_taken();
                    let rewards: f32 = (0..j).map(|k| w.reward(k)).sum();
                    if w.terminated() {
                        rewards
                    } else {
                        rewards + w.discount(j) * w.value(j)
                    }
                })
            },
        },
    ],
    checks,
};

/// The signature of `n_step_target`.
pub type Signature = fn(&[f32], &[f32], &[bool], f32, usize) -> Vec<f32>;

/// Grades an `n_step_target` running in this process (a notebook cell): the cases,
/// diagnosis and hints of `ppo-tutor grade n_step_target`.
#[must_use]
pub fn in_place(f: Signature) -> crate::Report {
    EXERCISE.grade_in_place(std::sync::Arc::new(move |a: Args<'_>| {
        Output::F32s(f(a.f32s(0), a.f32s(1), a.bools(2), a.f32(3), a.usize(4)))
    }))
}

/// The window of the target at step `t`: the `m = min(n, T − t)` steps from `t` on.
struct Window<'a> {
    rewards: &'a [f32],
    values: &'a [f32],
    dones: &'a [bool],
    gamma: f32,
    t: usize,
    m: usize,
}

impl Window<'_> {
    fn reward(&self, k: usize) -> f32 {
        self.rewards.get(self.t + k).copied().unwrap_or(0.0)
    }
    fn value(&self, k: usize) -> f32 {
        self.values.get(self.t + k).copied().unwrap_or(0.0)
    }
    fn done(&self, k: usize) -> bool {
        self.dones.get(self.t + k).copied().unwrap_or(false)
    }
    /// `γ^k`, as a running product (the reference's order of operations).
    fn discount(&self, k: usize) -> f32 {
        (0..k).fold(1.0, |d, _| d * self.gamma)
    }
    /// Whether a step of the window is done.
    fn terminated(&self) -> bool {
        (0..self.m).any(|k| self.done(k))
    }
    /// How many rewards the target takes: up to and including the first done, else `m`.
    fn rewards_taken(&self) -> usize {
        (0..self.m)
            .find(|&k| self.done(k))
            .map_or(self.m, |k| k + 1)
    }
}

/// One target per step, each computed by `f` from its window.
fn windows(a: Args<'_>, f: impl Fn(&Window<'_>) -> f32) -> Output {
    let (rewards, values, dones) = (a.f32s(0), a.f32s(1), a.bools(2));
    let (gamma, n) = (a.f32(3), a.usize(4));
    let steps = rewards.len();
    Output::F32s(
        (0..steps)
            .map(|t| {
                f(&Window {
                    rewards,
                    values,
                    dones,
                    gamma,
                    t,
                    m: n.min(steps - t),
                })
            })
            .collect(),
    )
}

/// The checks, with their cases (deterministic: seeded).
fn checks() -> Vec<CheckCases> {
    let random = random(71, |g| {
        let steps = g.int(1, 60);
        let rewards = if g.chance(0.5) {
            vec![1.0; steps]
        } else {
            g.f32s(steps, -2.0, 2.0)
        };
        let dones = g.bools(steps, 0.12);
        let gamma = if g.chance(0.5) { 0.98 } else { g.f(0.5, 1.0) };
        let n = if g.chance(0.15) {
            steps + g.int(0, 5)
        } else {
            g.int(1, 10)
        };
        case(rewards, g.f32s(steps + 1, -5.0, 60.0), dones, gamma, n)
    });
    let recorded = fixture(|b| {
        let mut values = b.values.clone();
        values.extend(b.next_values.last());
        let gamma = b.config.gamma as f32;
        [1, 5, b.rewards.len()]
            .into_iter()
            .map(|n| case(b.rewards.clone(), values.clone(), b.dones.clone(), gamma, n))
            .collect()
    });
    let one_step = vec![
        case(vec![1.0], vec![3.0, 30.0], vec![false], 0.98, 1),
        case(vec![1.0], vec![3.0, 30.0], vec![true], 0.98, 1),
        case(
            vec![1.0, 0.5, -1.0, 2.0],
            vec![4.0, 6.0, -2.0, 8.0, 10.0],
            vec![false, true, false, false],
            0.9,
            1,
        ),
    ];
    let every_step_done = vec![
        case(
            vec![1.0; 4],
            vec![10.0, 20.0, -3.0, 40.0, 7.0],
            vec![true; 4],
            0.98,
            1,
        ),
        case(
            vec![0.5, -1.0, 2.0],
            vec![7.0, 8.0, 9.0, 3.0],
            vec![true; 3],
            0.9,
            3,
        ),
        case(vec![1.0; 5], vec![5.0; 6], vec![true; 5], 0.95, 10),
    ];
    let no_done = vec![
        case(
            vec![1.0; 6],
            vec![2.0, 4.0, 6.0, 8.0, 10.0, 12.0, 14.0],
            vec![false; 6],
            0.9,
            3,
        ),
        case(
            vec![0.5, -0.5, 1.5, 2.0],
            vec![1.0, -2.0, 3.0, -4.0, 20.0],
            vec![false; 4],
            0.8,
            4,
        ),
        case(
            vec![1.0; 5],
            vec![3.0, 1.0, 4.0, 1.0, 5.0, 9.0],
            vec![false; 5],
            0.98,
            12,
        ),
    ];
    let done_inside = vec![
        case(
            vec![1.0, 2.0, 3.0, 4.0, 5.0, 6.0],
            vec![10.0, 20.0, 30.0, 40.0, 50.0, 60.0, 70.0],
            vec![false, false, true, false, false, false],
            0.9,
            4,
        ),
        case(
            vec![1.0; 7],
            vec![9.0, 8.0, 7.0, 6.0, 5.0, 4.0, 3.0, 2.0],
            vec![false, true, false, false, true, false, false],
            0.98,
            3,
        ),
    ];
    vec![
        random,
        recorded,
        check(
            Text::new("n = 1 is the TD target", "n = 1 就是 TD 目标"),
            one_step,
        ),
        check(
            Text::new("every step done", "每一步都结束"),
            every_step_done,
        ),
        check(
            Text::new(
                "no done at all: bootstrap at the rollout's end",
                "没有一步结束：在采样段末尾自举",
            ),
            no_done,
        ),
        check(
            Text::new("an episode ends inside the window", "回合在窗口之内结束"),
            done_inside,
        ),
    ]
}

fn case(rewards: Vec<f32>, values: Vec<f32>, dones: Vec<bool>, gamma: f32, n: usize) -> Vec<Arg> {
    vec![
        Arg::F32s(rewards),
        Arg::F32s(values),
        Arg::Bools(dones),
        Arg::F32(gamma),
        Arg::Usize(n),
    ]
}
