//! `td_target_truncation` (lesson 16): the TD target of each row of a same-step autoreset
//! vector environment's stream, where the observation returned after an episode's end is
//! already the next episode's first and the real last one comes separately. Its signature,
//! reference, typical mistakes and cases; the hints that name the mistakes are in the
//! lesson's `exercise.toml`.
//!
//! `final_values` holds NaN on every row where no episode ended: a right answer never reads
//! it there, and an answer that does (a 0/1 mask multiplied in, since NaN·0 is NaN) shows
//! NaN where a number is expected, which the comparison counts as wrong.

use crate::plain::*;
use crate::solutions as sol;
use crate::value::{Arg, Kind, OutKind, Output};

/// The exercise.
pub const EXERCISE: Plain = Plain {
    name: "td_target_truncation",
    lesson: "16-beyond-the-seed",
    params: &[
        ("rewards", Kind::F32s),
        ("next_values", Kind::F32s),
        ("final_values", Kind::F32s),
        ("terminated", Kind::Bools),
        ("truncated", Kind::Bools),
        ("gamma", Kind::F32),
    ],
    output: OutKind::F32s,
    tolerance: F32_TOL,
    reference: |a| call(a, sol::beyond::td_target_truncation),
    mistakes: &[
        Mistake {
            id: "bootstraps_from_reset",
            answer: |a| {
                targets(
                    a,
                    |term, _| {
                        if term { Future::Nothing } else { Future::Next }
                    },
                )
            },
        },
        Mistake {
            id: "stops_at_truncation",
            answer: |a| {
                targets(a, |term, trunc| {
                    if term || trunc {
                        Future::Nothing
                    } else {
                        Future::Next
                    }
                })
            },
        },
        Mistake {
            id: "bootstraps_through_termination",
            answer: |a| {
                targets(a, |term, trunc| {
                    if term || trunc {
                        Future::Final
                    } else {
                        Future::Next
                    }
                })
            },
        },
        Mistake {
            id: "truncation_wins",
            answer: |a| {
                targets(a, |term, trunc| match (term, trunc) {
                    (_, true) => Future::Final,
                    (true, false) => Future::Nothing,
                    (false, false) => Future::Next,
                })
            },
        },
        Mistake {
            id: "reads_final_values_everywhere",
            answer: masked,
        },
    ],
    checks,
};

/// The signature of `td_target_truncation`.
pub type Signature = fn(&[f32], &[f32], &[f32], &[bool], &[bool], f32) -> Vec<f32>;

/// Grades a `td_target_truncation` running in this process (a notebook cell): the cases,
/// diagnosis and hints of `ppo-tutor grade td_target_truncation`.
#[must_use]
pub fn in_place(f: Signature) -> crate::Report {
    EXERCISE.grade_in_place(std::sync::Arc::new(move |a: Args<'_>| call(a, f)))
}

/// `f` on a case's six arguments.
fn call(a: Args<'_>, f: Signature) -> Output {
    Output::F32s(f(
        a.f32s(0),
        a.f32s(1),
        a.f32s(2),
        a.bools(3),
        a.bools(4),
        a.f32(5),
    ))
}

/// What a row's target adds to its reward.
#[derive(Clone, Copy)]
enum Future {
    /// Nothing: `r`.
    Nothing,
    /// `γ·next_values[t]`, the observation the environment returned.
    Next,
    /// `γ·final_values[t]`, the real last observation of the episode that ended.
    Final,
}

/// Row by row, the reward plus the future `from(terminated, truncated)` picks.
fn targets(a: Args<'_>, from: impl Fn(bool, bool) -> Future) -> Output {
    let (r, next, last) = (a.f32s(0), a.f32s(1), a.f32s(2));
    let (term, trunc, gamma) = (a.bools(3), a.bools(4), a.f32(5));
    Output::F32s(
        (0..r.len())
            .map(|t| match from(term[t], trunc[t]) {
                Future::Nothing => r[t],
                Future::Next => r[t] + gamma * next[t],
                Future::Final => r[t] + gamma * last[t],
            })
            .collect(),
    )
}

/// The rule written with the flags as 0/1 factors, `r + γ·(1 − term)·((1 − trunc)·V_next +
/// trunc·V_final)`: right wherever an episode ended, NaN on every other row (NaN·0 is NaN).
fn masked(a: Args<'_>) -> Output {
    let (r, next, last) = (a.f32s(0), a.f32s(1), a.f32s(2));
    let (term, trunc, gamma) = (a.bools(3), a.bools(4), a.f32(5));
    let factor = |flag: bool| if flag { 1.0_f32 } else { 0.0 };
    Output::F32s(
        (0..r.len())
            .map(|t| {
                let future = (1.0 - factor(trunc[t])) * next[t] + factor(trunc[t]) * last[t];
                r[t] + gamma * (1.0 - factor(term[t])) * future
            })
            .collect(),
    )
}

/// A rollout of `n` steps with ends of both kinds at random places (the last step is an end
/// or not, as in a rollout cut by its own length).
pub(crate) fn random_ends(g: &mut Gen, n: usize) -> (Vec<bool>, Vec<bool>) {
    let mut terminated = vec![false; n];
    let mut truncated = vec![false; n];
    for t in 0..n {
        match g.int(0, 19) {
            0 | 1 => terminated[t] = true,
            2 | 3 => truncated[t] = true,
            4 => (terminated[t], truncated[t]) = (true, true),
            _ => {}
        }
    }
    (terminated, truncated)
}

/// `values` on the rows where an episode ended, NaN on the others: the sentinel a right
/// answer never reads.
fn nan_where_no_end(values: Vec<f32>, terminated: &[bool], truncated: &[bool]) -> Vec<f32> {
    values
        .into_iter()
        .enumerate()
        .map(|(t, v)| {
            if terminated[t] || truncated[t] {
                v
            } else {
                f32::NAN
            }
        })
        .collect()
}

/// The recorded CartPole episodes, one after another as a same-step autoreset environment
/// hands them over: on the step where the pole fell, `next_values` is the critic's value of
/// the next episode's first state and `final_values` the recorded value of the real last
/// observation. The stream stops one step before the last episode's fall, whose following
/// first state was not recorded: a rollout cut by its length.
fn recorded_stream() -> Vec<Vec<Arg>> {
    let batches = fixture_batches();
    let (mut r, mut next, mut last, mut term) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    'episodes: for (k, b) in batches.iter().enumerate() {
        for t in 0..b.rewards.len() {
            let ended = b.dones[t];
            let (v_next, v_last) = if ended {
                let first = b
                    .values
                    .get(t + 1)
                    .or_else(|| batches.get(k + 1).and_then(|nb| nb.values.first()));
                let Some(&first) = first else {
                    break 'episodes;
                };
                (first, b.next_values[t])
            } else {
                (b.next_values[t], f32::NAN)
            };
            r.push(b.rewards[t]);
            next.push(v_next);
            last.push(v_last);
            term.push(ended);
        }
    }
    let gamma = batches.first().map_or(0.98, |b| b.config.gamma as f32);
    let n = r.len();
    vec![case(r, next, last, term, vec![false; n], gamma)]
}

/// The checks, with their cases (deterministic: seeded).
fn checks() -> Vec<CheckCases> {
    let random = random(17, |g| {
        let n = g.int(2, 60);
        let rewards = if g.chance(0.6) {
            vec![1.0; n]
        } else {
            g.f32s(n, -2.0, 2.0)
        };
        let (terminated, truncated) = random_ends(g, n);
        let gamma = if g.chance(0.5) { 0.98 } else { g.f(0.5, 1.0) };
        let next_values = g.f32s(n, -5.0, 60.0);
        let final_values = nan_where_no_end(g.f32s(n, -5.0, 60.0), &terminated, &truncated);
        case(
            rewards,
            next_values,
            final_values,
            terminated,
            truncated,
            gamma,
        )
    });
    let recorded = check(
        Text::new(
            "the recorded PyTorch episodes, as one autoreset stream",
            "录制的 PyTorch 回合，连成一段自动重置的数据流",
        ),
        recorded_stream(),
    );
    // Hand-made streams with γ = 0.5 or 1 and values in halves: every right target is exact
    // in f32. Row 1 of the first two is an end whose next_values is the new episode's first
    // state, far from the real last one.
    let nan = f32::NAN;
    let cut = vec![case(
        vec![1.0; 3],
        vec![48.0, 5.0, 6.0],
        vec![nan, 49.5, nan],
        vec![false; 3],
        vec![false, true, false],
        0.5,
    )];
    let fell = vec![case(
        vec![1.0; 3],
        vec![20.0, 4.0, 5.0],
        vec![nan, 3.0, nan],
        vec![false, true, false],
        vec![false; 3],
        0.5,
    )];
    let both = vec![case(
        vec![1.0; 2],
        vec![40.0, 6.0],
        vec![nan, 49.0],
        vec![false, true],
        vec![false, true],
        0.5,
    )];
    let first_and_last = vec![case(
        vec![1.0; 4],
        vec![6.0, 30.0, 31.0, 7.0],
        vec![45.5, nan, nan, 32.0],
        vec![false; 4],
        vec![true, false, false, true],
        1.0,
    )];
    let no_end = vec![case(
        vec![0.5, -1.0, 2.0],
        vec![10.0, 12.0, 14.0],
        vec![nan; 3],
        vec![false; 3],
        vec![false; 3],
        0.5,
    )];
    vec![
        random,
        recorded,
        check(
            Text::new(
                "a time-limit cut, then the next episode's first step",
                "时限中断，随后是下一个回合的第一步",
            ),
            cut,
        ),
        check(
            Text::new(
                "a fall, then the next episode's first step",
                "杆倒下，随后是下一个回合的第一步",
            ),
            fell,
        ),
        check(
            Text::new("terminated and truncated at once", "同时终止和时限中断"),
            both,
        ),
        check(
            Text::new(
                "time-limit cuts on the first and the last row, γ = 1",
                "第一行和最后一行都因时限中断，γ = 1",
            ),
            first_and_last,
        ),
        check(
            Text::new(
                "a stretch with no episode end (final_values all NaN)",
                "一段没有回合结束的采样（final_values 全为 NaN）",
            ),
            no_end,
        ),
    ]
}

fn case(
    rewards: Vec<f32>,
    next_values: Vec<f32>,
    final_values: Vec<f32>,
    terminated: Vec<bool>,
    truncated: Vec<bool>,
    gamma: f32,
) -> Vec<Arg> {
    vec![
        Arg::F32s(rewards),
        Arg::F32s(next_values),
        Arg::F32s(final_values),
        Arg::Bools(terminated),
        Arg::Bools(truncated),
        Arg::F32(gamma),
    ]
}
