//! `td_target_truncation` (lesson 16): the TD target that bootstraps through a time-limit
//! cut and not through a real end. Its signature, reference, typical mistakes and cases; the
//! hints that name the mistakes are in the lesson's `exercise.toml`.

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
        ("terminated", Kind::Bools),
        ("truncated", Kind::Bools),
        ("gamma", Kind::F32),
    ],
    output: OutKind::F32s,
    tolerance: F32_TOL,
    reference: |a| {
        Output::F32s(sol::beyond::td_target_truncation(
            a.f32s(0),
            a.f32s(1),
            a.bools(2),
            a.bools(3),
            a.f32(4),
        ))
    },
    mistakes: &[
        Mistake {
            id: "stops_at_truncation",
            answer: |a| targets(a, |term, trunc| term || trunc, a.f32(4)),
        },
        Mistake {
            id: "bootstraps_through_termination",
            answer: |a| targets(a, |_, _| false, a.f32(4)),
        },
        Mistake {
            id: "never_bootstraps",
            answer: |a| targets(a, |_, _| true, a.f32(4)),
        },
        Mistake {
            id: "flags_swapped",
            answer: |a| targets(a, |_, trunc| trunc, a.f32(4)),
        },
        Mistake {
            id: "missing_gamma",
            answer: |a| targets(a, |term, _| term, 1.0),
        },
    ],
    checks,
};

/// The signature of `td_target_truncation`.
pub type Signature = fn(&[f32], &[f32], &[bool], &[bool], f32) -> Vec<f32>;

/// Grades a `td_target_truncation` running in this process (a notebook cell): the cases,
/// diagnosis and hints of `ppo-tutor grade td_target_truncation`.
#[must_use]
pub fn in_place(f: Signature) -> crate::Report {
    EXERCISE.grade_in_place(std::sync::Arc::new(move |a: Args<'_>| {
        Output::F32s(f(a.f32s(0), a.f32s(1), a.bools(2), a.bools(3), a.f32(4)))
    }))
}

/// `r + γ·V′` row by row, or `r` alone where `ends(terminated, truncated)`.
fn targets(a: Args<'_>, ends: impl Fn(bool, bool) -> bool, gamma: f32) -> Output {
    let (r, v, term, trunc) = (a.f32s(0), a.f32s(1), a.bools(2), a.bools(3));
    Output::F32s(
        (0..r.len())
            .map(|t| {
                let alive = if ends(term[t], trunc[t]) { 0.0 } else { 1.0 };
                r[t] + gamma * v[t] * alive
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
        case(rewards, g.f32s(n, -5.0, 60.0), terminated, truncated, gamma)
    });
    // The recorded CartPole episodes end when the pole falls: terminated, never truncated.
    let recorded = fixture(|b| {
        vec![case(
            b.rewards.clone(),
            b.next_values.clone(),
            b.dones.clone(),
            vec![false; b.dones.len()],
            b.config.gamma as f32,
        )]
    });
    let cut = vec![case(
        vec![1.0, 1.0],
        vec![48.0, 49.5],
        vec![false, false],
        vec![false, true],
        0.98,
    )];
    let fell = vec![case(
        vec![1.0, 1.0],
        vec![20.0, 3.0],
        vec![false, true],
        vec![false, false],
        0.98,
    )];
    let both = vec![case(vec![1.0], vec![49.0], vec![true], vec![true], 0.98)];
    vec![
        random,
        recorded,
        check(
            Text::new("an episode cut by the time limit", "因时限中断的回合"),
            cut,
        ),
        check(
            Text::new("an episode where the pole fell", "杆倒下的回合"),
            fell,
        ),
        check(
            Text::new("terminated and truncated at once", "同时终止和时限中断"),
            both,
        ),
    ]
}

fn case(
    rewards: Vec<f32>,
    next_values: Vec<f32>,
    terminated: Vec<bool>,
    truncated: Vec<bool>,
    gamma: f32,
) -> Vec<Arg> {
    vec![
        Arg::F32s(rewards),
        Arg::F32s(next_values),
        Arg::Bools(terminated),
        Arg::Bools(truncated),
        Arg::F32(gamma),
    ]
}
