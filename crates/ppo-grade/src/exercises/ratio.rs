//! `ratio` (lesson 9): the probability ratio π/π_old from log-probabilities. Its signature, reference, typical mistakes
//! and cases; the hints that name the mistakes are in the lesson's `exercise.toml`.

use crate::plain::*;
use crate::solutions as sol;
use crate::value::{Arg, Kind, OutKind, Output};

/// The exercise.
pub const EXERCISE: Plain = Plain {
    name: "ratio",
    lesson: "09-ratio",
    params: &[("log_probs", Kind::F32s), ("old_log_probs", Kind::F32s)],
    output: OutKind::F32s,
    tolerance: F32_TOL,
    reference: |a| Output::F32s(sol::ratio::ratio(a.f32s(0), a.f32s(1))),
    mistakes: &[
        Mistake {
            id: "no_exp",
            answer: |a| map2(a.f32s(0), a.f32s(1), |n, o| n - o),
        },
        Mistake {
            id: "inverted",
            answer: |a| map2(a.f32s(0), a.f32s(1), |n, o| (o - n).exp()),
        },
        Mistake {
            id: "divided_logs",
            answer: |a| map2(a.f32s(0), a.f32s(1), |n, o| n / o),
        },
    ],
    checks,
};

/// Grades a `ratio` running in this process (a notebook cell): the cases, diagnosis and
/// hints of `ppo-tutor grade ratio`.
#[must_use]
pub fn in_place(f: fn(&[f32], &[f32]) -> Vec<f32>) -> crate::Report {
    EXERCISE.grade_in_place(std::sync::Arc::new(move |a: Args<'_>| Output::F32s(f(a.f32s(0), a.f32s(1)))))
}

/// The checks, with their cases (deterministic: seeded).
fn checks() -> Vec<CheckCases> {
    let random = random(10, |g| {
        let n = g.int(1, 60);
        let old: Vec<f32> = (0..n).map(|_| g.f(0.05, 1.0).ln()).collect();
        let new = old.iter().map(|o| o + g.f(-0.5, 0.5)).collect();
        vec![Arg::F32s(new), Arg::F32s(old)]
    });
    let recorded = fixture(|b| {
        b.epochs
            .iter()
            .map(|(log_probs, _)| {
                vec![
                    Arg::F32s(log_probs.clone()),
                    Arg::F32s(b.old_log_probs.clone()),
                ]
            })
            .collect()
    });
    let single = vec![vec![Arg::F32s(vec![-0.6]), Arg::F32s(vec![-0.7])]];
    let first_epoch = vec![vec![
        Arg::F32s(vec![-0.69, -0.1, -2.3]),
        Arg::F32s(vec![-0.69, -0.1, -2.3]),
    ]];
    let outside = vec![vec![
        Arg::F32s(vec![-0.2, -1.5, -0.05, -3.0]),
        Arg::F32s(vec![-0.9, -0.4, -1.2, -1.0]),
    ]];
    vec![
        random,
        recorded,
        check("a single step", single),
        check("the first epoch (equal log-probabilities)", first_epoch),
        check("ratios outside 1 ± ε", outside),
    ]
}
