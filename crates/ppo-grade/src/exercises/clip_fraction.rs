//! `clip_fraction` (lesson 12): CleanRL's `clipfracs`, the share of rows whose ratio is
//! further than ε from 1. Its signature, reference, typical mistakes and cases; the hints
//! that name the mistakes are in the lesson's `exercise.toml`.

use crate::plain::*;
use crate::solutions as sol;
use crate::value::{Arg, Kind, OutKind, Output};

/// The exercise.
pub const EXERCISE: Plain = Plain {
    name: "clip_fraction",
    lesson: "12-clip-lab",
    params: &[("ratio", Kind::F32s), ("eps", Kind::F32)],
    output: OutKind::F32,
    tolerance: F32_TOL,
    reference: |a| Output::F32(sol::clip_lab::clip_fraction(a.f32s(0), a.f32(1))),
    mistakes: &[
        Mistake {
            id: "count_not_fraction",
            answer: |a| share(a, |r, eps| (r - 1.0).abs() > eps, false),
        },
        Mistake {
            id: "above_only",
            answer: |a| share(a, |r, eps| r - 1.0 > eps, true),
        },
        Mistake {
            id: "below_only",
            answer: |a| share(a, |r, eps| 1.0 - r > eps, true),
        },
        Mistake {
            id: "bounds_not_distance",
            answer: |a| share(a, |r, eps| r > 1.0 + eps || r < 1.0 - eps, true),
        },
        Mistake {
            id: "inclusive",
            answer: |a| share(a, |r, eps| (r - 1.0).abs() >= eps, true),
        },
        Mistake {
            id: "inverted",
            answer: |a| share(a, |r, eps| (r - 1.0).abs() <= eps, true),
        },
    ],
    checks,
};

/// The signature of `clip_fraction`.
pub type Signature = fn(&[f32], f32) -> f32;

/// Grades a `clip_fraction` running in this process (a notebook cell): the cases,
/// diagnosis and hints of `ppo-tutor grade clip_fraction`.
#[must_use]
pub fn in_place(f: Signature) -> crate::Report {
    EXERCISE.grade_in_place(std::sync::Arc::new(move |a: Args<'_>| {
        Output::F32(f(a.f32s(0), a.f32(1)))
    }))
}

/// The count of rows where `counts(r, ε)`, divided by the row count when `fraction`.
fn share(a: Args<'_>, counts: impl Fn(f32, f32) -> bool, fraction: bool) -> Output {
    let ratio = a.f32s(0);
    let n = ratio.iter().filter(|&&r| counts(r, a.f32(1))).count() as f32;
    Output::F32(if fraction { n / ratio.len() as f32 } else { n })
}

/// The checks, with their cases (deterministic: seeded).
fn checks() -> Vec<CheckCases> {
    let random = random(16, |g| {
        let n = g.int(2, 60);
        let eps = if g.chance(0.6) { 0.2 } else { g.f(0.05, 0.4) };
        let ratio = (0..n)
            .map(|_| match g.int(0, 9) {
                0 => 1.0 + eps,
                1 => 1.0 - eps,
                _ => g.f(0.5, 1.6),
            })
            .collect();
        vec![Arg::F32s(ratio), Arg::F32(eps)]
    });
    let recorded = fixture(|b| {
        b.epochs
            .iter()
            .map(|(_, ratio)| vec![Arg::F32s(ratio.clone()), Arg::F32(b.config.eps as f32)])
            .collect()
    });
    let eps = 0.2_f32;
    let both_sides = vec![vec![Arg::F32s(vec![1.5, 0.5, 1.0, 1.1]), Arg::F32(eps)]];
    let none = vec![vec![Arg::F32s(vec![1.0; 5]), Arg::F32(eps)]];
    // In float32, 1 + ε sits a hair further than ε from 1 (so it counts), 1 − ε does not.
    let edges = vec![vec![
        Arg::F32s(vec![1.0 + eps, 1.0 - eps, 1.0, 1.0]),
        Arg::F32(eps),
    ]];
    // With ε = 0.25 (exact in binary), 1.25 is exactly ε from 1: not further.
    let exact = vec![vec![Arg::F32s(vec![1.25, 0.75, 1.0]), Arg::F32(0.25)]];
    vec![
        random,
        recorded,
        check("both sides of the band", both_sides),
        check("the first epoch (every ratio 1)", none),
        check("ratios exactly at 1 ± ε, in float32", edges),
        check("ratios exactly ε from 1", exact),
    ]
}
