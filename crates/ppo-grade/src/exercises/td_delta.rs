//! `td_delta` (lesson 7): the TD error, the target minus the critic's prediction. Its signature, reference, typical mistakes
//! and cases; the hints that name the mistakes are in the lesson's `exercise.toml`.

use crate::plain::*;
use crate::solutions as sol;
use crate::value::{Arg, Kind, OutKind, Output};

/// The exercise.
pub const EXERCISE: Plain = Plain {
    name: "td_delta",
    lesson: "07-td-target",
    params: &[("td_target", Kind::F32s), ("values", Kind::F32s)],
    output: OutKind::F32s,
    tolerance: F32_TOL,
    reference: |a| Output::F32s(sol::td_target::td_delta(a.f32s(0), a.f32s(1))),
    mistakes: &[
        Mistake {
            id: "inverted",
            answer: |a| map2(a.f32s(0), a.f32s(1), |t, v| v - t),
        },
        Mistake {
            id: "added",
            answer: |a| map2(a.f32s(0), a.f32s(1), |t, v| t + v),
        },
    ],
    checks,
};

/// Grades a `td_delta` running in this process (a notebook cell): the cases, diagnosis and
/// hints of `ppo-tutor grade td_delta`.
#[must_use]
pub fn in_place(f: fn(&[f32], &[f32]) -> Vec<f32>) -> crate::Report {
    EXERCISE.grade_in_place(std::sync::Arc::new(move |a: Args<'_>| Output::F32s(f(a.f32s(0), a.f32s(1)))))
}

/// The checks, with their cases (deterministic: seeded).
fn checks() -> Vec<CheckCases> {
    let random = random(70, |g| {
        let n = g.int(1, 60);
        vec![
            Arg::F32s(g.f32s(n, -5.0, 60.0)),
            Arg::F32s(g.f32s(n, -5.0, 60.0)),
        ]
    });
    let recorded = fixture(|b| {
        vec![vec![
            Arg::F32s(b.td_target.clone()),
            Arg::F32s(b.values.clone()),
        ]]
    });
    let single = vec![vec![Arg::F32s(vec![20.4]), Arg::F32s(vec![19.0])]];
    let negative = vec![vec![
        Arg::F32s(vec![1.0, 10.0, 20.0]),
        Arg::F32s(vec![5.0, 12.5, 20.5]),
    ]];
    vec![
        random,
        recorded,
        check("a single step", single),
        check("negative TD errors (the critic overestimates)", negative),
    ]
}
