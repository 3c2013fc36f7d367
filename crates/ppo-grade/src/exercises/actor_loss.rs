//! `actor_loss` (lesson 10): the clipped surrogate loss. Its signature, reference, typical mistakes
//! and cases; the hints that name the mistakes are in the lesson's `exercise.toml`.

use crate::plain::*;
use crate::solutions as sol;
use crate::value::{Arg, Kind, OutKind, Output};

/// The exercise.
pub const EXERCISE: Plain = Plain {
    name: "actor_loss",
    lesson: "10-clipping",
    params: &[
        ("ratio", Kind::F32s),
        ("advantage", Kind::F32s),
        ("eps", Kind::F32),
    ],
    output: OutKind::F32,
    tolerance: LOSS_TOL,
    reference: |a| Output::F32(sol::clipping::actor_loss(a.f32s(0), a.f32s(1), a.f32(2))),
    mistakes: &[
        Mistake {
            id: "max_instead_of_min",
            answer: |a| Output::F32(mean(surrogate(a, |r, x, e| -(r * x).max(clip(r, e) * x)))),
        },
        Mistake {
            id: "clamp_advantage",
            answer: |a| Output::F32(mean(surrogate(a, |r, x, e| -(r * x).min(r * clip(x, e))))),
        },
        Mistake {
            id: "clamp_product",
            answer: |a| Output::F32(mean(surrogate(a, |r, x, e| -(r * x).min(clip(r * x, e))))),
        },
        Mistake {
            id: "no_minus",
            answer: |a| Output::F32(mean(surrogate(a, |r, x, e| (r * x).min(clip(r, e) * x)))),
        },
        Mistake {
            id: "sum_instead_of_mean",
            answer: |a| Output::F32(sum(surrogate(a, |r, x, e| -(r * x).min(clip(r, e) * x)))),
        },
        Mistake {
            id: "no_clip",
            answer: |a| Output::F32(mean(surrogate(a, |r, x, _| -(r * x)))),
        },
        Mistake {
            id: "only_clipped",
            answer: |a| Output::F32(mean(surrogate(a, |r, x, e| -(clip(r, e) * x)))),
        },
    ],
    checks,
};

/// Grades a `actor_loss` running in this process (a notebook cell): the cases, diagnosis and
/// hints of `ppo-tutor grade actor_loss`.
#[must_use]
pub fn in_place(f: fn(&[f32], &[f32], f32) -> f32) -> crate::Report {
    EXERCISE.grade_in_place(std::sync::Arc::new(move |a: Args<'_>| Output::F32(f(a.f32s(0), a.f32s(1), a.f32(2)))))
}

fn surrogate(a: Args<'_>, per_row: impl Fn(f32, f32, f32) -> f32) -> impl Iterator<Item = f32> {
    let eps = a.f32(2);
    a.f32s(0)
        .iter()
        .zip(a.f32s(1))
        .map(move |(&r, &adv)| per_row(r, adv, eps))
        .collect::<Vec<_>>()
        .into_iter()
}

fn clip(r: f32, eps: f32) -> f32 {
    r.clamp(1.0 - eps, 1.0 + eps)
}

/// The checks, with their cases (deterministic: seeded).
fn checks() -> Vec<CheckCases> {
    let random = random(11, |g| {
        let n = g.int(2, 60);
        let eps = if g.chance(0.5) { 0.2 } else { g.f(0.1, 0.3) };
        loss_case(g.f32s(n, 0.6, 1.4), g.f32s(n, -3.0, 3.0), eps)
    });
    let recorded = fixture(|b| {
        b.epochs
            .iter()
            .map(|(_, ratio)| loss_case(ratio.clone(), b.advantage.clone(), b.config.eps as f32))
            .collect()
    });
    let single = vec![
        loss_case(vec![1.5], vec![2.0], 0.2),
        loss_case(vec![0.5], vec![-2.0], 0.2),
    ];
    let negative = vec![loss_case(
        vec![0.5, 0.9, 1.1, 1.6],
        vec![-1.0, -2.0, -0.5, -3.0],
        0.2,
    )];
    let outside = vec![
        loss_case(vec![0.5, 1.5, 0.7, 1.3], vec![1.0, 1.0, -1.0, -1.0], 0.2),
        loss_case(vec![1.0, 2.0, 0.1], vec![0.5, 0.5, 0.5], 0.2),
    ];
    vec![
        random,
        recorded,
        check("a single step", single),
        check("negative advantages", negative),
        check("ratios outside 1 ± ε", outside),
    ]
}

fn loss_case(ratio: Vec<f32>, advantage: Vec<f32>, eps: f32) -> Vec<Arg> {
    vec![Arg::F32s(ratio), Arg::F32s(advantage), Arg::F32(eps)]
}
