//! `critic_loss` (lesson 11): the critic's mean squared error. Its signature, reference, typical mistakes
//! and cases; the hints that name the mistakes are in the lesson's `exercise.toml`.

use crate::plain::*;
use crate::solutions as sol;
use crate::value::{Arg, Kind, OutKind, Output};

/// The exercise.
pub const EXERCISE: Plain = Plain {
    name: "critic_loss",
    lesson: "11-losses",
    params: &[("values", Kind::F32s), ("td_target", Kind::F32s)],
    output: OutKind::F32,
    tolerance: LOSS_TOL,
    reference: |a| Output::F32(sol::losses::critic_loss(a.f32s(0), a.f32s(1))),
    mistakes: &[
        Mistake {
            id: "root_mean_square",
            answer: |a| Output::F32(mean(errors(a).into_iter().map(|e| e * e)).sqrt()),
        },
        Mistake {
            id: "sum_instead_of_mean",
            answer: |a| Output::F32(sum(errors(a).into_iter().map(|e| e * e))),
        },
        Mistake {
            id: "mean_absolute",
            answer: |a| Output::F32(mean(errors(a).into_iter().map(f32::abs))),
        },
        Mistake {
            id: "not_squared",
            answer: |a| Output::F32(mean(errors(a).into_iter())),
        },
        Mistake {
            id: "half_mse",
            answer: |a| Output::F32(0.5 * mean(errors(a).into_iter().map(|e| e * e))),
        },
    ],
    checks,
};

/// Grades a `critic_loss` running in this process (a notebook cell): the cases, diagnosis and
/// hints of `ppo-tutor grade critic_loss`.
#[must_use]
pub fn in_place(f: fn(&[f32], &[f32]) -> f32) -> crate::Report {
    EXERCISE.grade_in_place(std::sync::Arc::new(move |a: Args<'_>| Output::F32(f(a.f32s(0), a.f32s(1)))))
}

fn errors(a: Args<'_>) -> Vec<f32> {
    a.f32s(0)
        .iter()
        .zip(a.f32s(1))
        .map(|(v, t)| v - t)
        .collect()
}

/// The checks, with their cases (deterministic: seeded).
fn checks() -> Vec<CheckCases> {
    let random = random(12, |g| {
        let n = g.int(2, 60);
        vec![
            Arg::F32s(g.f32s(n, -5.0, 60.0)),
            Arg::F32s(g.f32s(n, -5.0, 60.0)),
        ]
    });
    let recorded = fixture(|b| {
        vec![vec![
            Arg::F32s(b.values.clone()),
            Arg::F32s(b.td_target.clone()),
        ]]
    });
    let single = vec![vec![Arg::F32s(vec![3.0]), Arg::F32s(vec![5.0])]];
    let both_sides = vec![vec![
        Arg::F32s(vec![1.0, 3.0, 10.0, 10.0]),
        Arg::F32s(vec![2.0, 2.0, 12.0, 8.0]),
    ]];
    vec![
        random,
        recorded,
        check("a single step", single),
        check("errors of both signs", both_sides),
    ]
}
