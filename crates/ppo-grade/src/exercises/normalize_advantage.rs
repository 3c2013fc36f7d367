//! `normalize_advantage` (lesson 15): CleanRL's `(adv - adv.mean()) / (adv.std() + 1e-8)`.
//! Its signature, reference, typical mistakes and cases; the hints that name the mistakes
//! are in the lesson's `exercise.toml`.

use crate::plain::*;
use crate::solutions as sol;
use crate::value::{Arg, Kind, OutKind, Output};

/// The exercise.
pub const EXERCISE: Plain = Plain {
    name: "normalize_advantage",
    lesson: "15-beyond-the-seed",
    params: &[("advantage", Kind::F32s)],
    output: OutKind::F32s,
    tolerance: F32_TOL,
    reference: |a| Output::F32s(sol::beyond::normalize_advantage(a.f32s(0))),
    mistakes: &[
        Mistake {
            id: "biased_std",
            answer: |a| scaled(a, true, |var, n| (var / n).sqrt() + 1e-8),
        },
        Mistake {
            id: "variance_not_std",
            answer: |a| scaled(a, true, |var, n| var / (n - 1.0) + 1e-8),
        },
        Mistake {
            id: "no_epsilon",
            answer: |a| scaled(a, true, |var, n| (var / (n - 1.0)).sqrt()),
        },
        Mistake {
            id: "not_centred",
            answer: |a| scaled(a, false, |var, n| (var / (n - 1.0)).sqrt() + 1e-8),
        },
        Mistake {
            id: "not_scaled",
            answer: |a| scaled(a, true, |_, _| 1.0),
        },
    ],
    checks,
};

/// The signature of `normalize_advantage`.
pub type Signature = fn(&[f32]) -> Vec<f32>;

/// Grades a `normalize_advantage` running in this process (a notebook cell): the cases,
/// diagnosis and hints of `ppo-tutor grade normalize_advantage`.
#[must_use]
pub fn in_place(f: Signature) -> crate::Report {
    EXERCISE.grade_in_place(std::sync::Arc::new(move |a: Args<'_>| Output::F32s(f(a.f32s(0)))))
}

/// `(a − mean)/scale(Σ(a − mean)², n)`, or `a/scale(…)` when not `centre`d.
fn scaled(a: Args<'_>, centre: bool, scale: impl Fn(f32, f32) -> f32) -> Output {
    let adv = a.f32s(0);
    let n = adv.len() as f32;
    let mean = adv.iter().sum::<f32>() / n;
    let squares = adv.iter().map(|x| (x - mean) * (x - mean)).sum::<f32>();
    let s = scale(squares, n);
    let shift = if centre { mean } else { 0.0 };
    Output::F32s(adv.iter().map(|x| (x - shift) / s).collect())
}

/// The checks, with their cases (deterministic: seeded).
fn checks() -> Vec<CheckCases> {
    let random = random(19, |g| {
        let n = g.int(2, 80);
        let centre = g.f(-5.0, 5.0);
        let width = g.f(0.5, 20.0);
        vec![Arg::F32s(g.f32s(n, centre - width, centre + width))]
    });
    let recorded = fixture(|b| vec![vec![Arg::F32s(b.advantage.clone())]]);
    let two = vec![vec![Arg::F32s(vec![1.0, 3.0])], vec![Arg::F32s(vec![-4.0, 0.5])]];
    let equal = vec![vec![Arg::F32s(vec![2.0; 5])], vec![Arg::F32s(vec![-0.5; 2])]];
    let small = vec![vec![Arg::F32s(vec![0.1, 0.2, 0.3, 0.4])]];
    vec![
        random,
        recorded,
        check("two rows", two),
        check("every advantage equal", equal),
        check("advantages smaller than 1", small),
    ]
}
