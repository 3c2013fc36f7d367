//! `td_target` (lesson 7): the TD target r + γ·V(s′)·(1 − done). Its signature, reference, typical mistakes
//! and cases; the hints that name the mistakes are in the lesson's `exercise.toml`.

use crate::plain::*;
use crate::solutions as sol;
use crate::value::{Arg, Kind, OutKind, Output};

/// The exercise.
pub const EXERCISE: Plain = Plain {
    name: "td_target",
    lesson: "07-td-target",
    params: &[
        ("rewards", Kind::F32s),
        ("next_values", Kind::F32s),
        ("dones", Kind::Bools),
        ("gamma", Kind::F32),
    ],
    output: OutKind::F32s,
    tolerance: F32_TOL,
    reference: |a| {
        Output::F32s(sol::td_target::td_target(
            a.f32s(0),
            a.f32s(1),
            a.bools(2),
            a.f32(3),
        ))
    },
    mistakes: &[
        Mistake {
            id: "missing_done_mask",
            answer: |a| td_target_with(a, |r, v, _, g| r + g * v),
        },
        Mistake {
            id: "inverted_done_mask",
            answer: |a| td_target_with(a, |r, v, d, g| r + g * v * d),
        },
        Mistake {
            id: "missing_gamma",
            answer: |a| td_target_with(a, |r, v, d, _| r + v * (1.0 - d)),
        },
        Mistake {
            id: "mask_on_reward",
            answer: |a| td_target_with(a, |r, v, d, g| (r + g * v) * (1.0 - d)),
        },
        Mistake {
            id: "gamma_on_reward",
            answer: |a| td_target_with(a, |r, v, d, g| g * (r + v * (1.0 - d))),
        },
    ],
    checks,
};

/// The signature of `td_target`.
pub type Signature = fn(&[f32], &[f32], &[bool], f32) -> Vec<f32>;

/// Grades a `td_target` running in this process (a notebook cell): the cases, diagnosis and
/// hints of `ppo-tutor grade td_target`.
#[must_use]
pub fn in_place(f: Signature) -> crate::Report {
    EXERCISE.grade_in_place(std::sync::Arc::new(move |a: Args<'_>| Output::F32s(f(a.f32s(0), a.f32s(1), a.bools(2), a.f32(3)))))
}

fn td_target_with(a: Args<'_>, f: impl Fn(f32, f32, f32, f32) -> f32) -> Output {
    let (r, v, d, g) = (a.f32s(0), a.f32s(1), a.bools(2), a.f32(3));
    Output::F32s(
        r.iter()
            .zip(v)
            .zip(d)
            .map(|((&r, &v), &d)| f(r, v, if d { 1.0 } else { 0.0 }, g))
            .collect(),
    )
}

/// The checks, with their cases (deterministic: seeded).
fn checks() -> Vec<CheckCases> {
    let random = random(7, |g| {
        let n = g.int(2, 60);
        let rewards = if g.chance(0.6) {
            vec![1.0; n]
        } else {
            g.f32s(n, -2.0, 2.0)
        };
        let mut dones = g.bools(n, 0.15);
        if let Some(last) = dones.last_mut() {
            *last = true;
        }
        let gamma = if g.chance(0.5) { 0.98 } else { g.f(0.5, 1.0) };
        td_target_case(rewards, g.f32s(n, -5.0, 60.0), dones, gamma)
    });
    let recorded = fixture(|b| {
        vec![td_target_case(
            b.rewards.clone(),
            b.next_values.clone(),
            b.dones.clone(),
            b.config.gamma as f32,
        )]
    });
    let single = vec![
        td_target_case(vec![1.0], vec![30.0], vec![false], 0.98),
        td_target_case(vec![1.0], vec![30.0], vec![true], 0.98),
        td_target_case(vec![-0.5], vec![-2.0], vec![false], 0.9),
    ];
    let all_done = vec![
        td_target_case(
            vec![1.0; 4],
            vec![10.0, 20.0, -3.0, 40.0],
            vec![true; 4],
            0.98,
        ),
        td_target_case(vec![0.5, -1.0], vec![7.0, 8.0], vec![true; 2], 0.9),
    ];
    vec![
        random,
        recorded,
        check("a single step", single),
        check("every step done", all_done),
    ]
}

fn td_target_case(rewards: Vec<f32>, next_values: Vec<f32>, dones: Vec<bool>, g: f32) -> Vec<Arg> {
    vec![
        Arg::F32s(rewards),
        Arg::F32s(next_values),
        Arg::Bools(dones),
        Arg::F32(g),
    ]
}
