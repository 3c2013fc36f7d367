//! `approx_kl` (lesson 13): CleanRL's estimate of KL(π_old ‖ π_θ) from the sampled
//! actions. Its signature, reference, typical mistakes and cases; the hints that name the
//! mistakes are in the lesson's `exercise.toml`.

use crate::plain::*;
use crate::solutions as sol;
use crate::value::{Arg, Kind, OutKind, Output};

/// The exercise.
pub const EXERCISE: Plain = Plain {
    name: "approx_kl",
    lesson: "13-clip-lab",
    params: &[("old_log_probs", Kind::F32s), ("log_probs", Kind::F32s)],
    output: OutKind::F32,
    tolerance: LOSS_TOL,
    reference: |a| Output::F32(sol::clip_lab::approx_kl(a.f32s(0), a.f32s(1))),
    mistakes: &[
        Mistake {
            id: "naive_estimator",
            answer: |a| per_row(a, |old, new| old - new, mean),
        },
        Mistake {
            id: "inverted_ratio",
            answer: |a| per_row(a, |old, new| ((old - new).exp() - 1.0) - (old - new), mean),
        },
        Mistake {
            id: "half_squared",
            answer: |a| per_row(a, |old, new| 0.5 * (new - old) * (new - old), mean),
        },
        Mistake {
            id: "no_minus_one",
            answer: |a| per_row(a, |old, new| (new - old).exp() - (new - old), mean),
        },
        Mistake {
            id: "sum_instead_of_mean",
            answer: |a| per_row(a, |old, new| ((new - old).exp() - 1.0) - (new - old), sum),
        },
    ],
    checks,
};

/// The signature of `approx_kl`.
pub type Signature = fn(&[f32], &[f32]) -> f32;

/// Grades an `approx_kl` running in this process (a notebook cell): the cases, diagnosis
/// and hints of `ppo-tutor grade approx_kl`.
#[must_use]
pub fn in_place(f: Signature) -> crate::Report {
    EXERCISE.grade_in_place(std::sync::Arc::new(move |a: Args<'_>| {
        Output::F32(f(a.f32s(0), a.f32s(1)))
    }))
}

/// `reduce` over the rows of `f(old, new)`.
fn per_row(
    a: Args<'_>,
    f: impl Fn(f32, f32) -> f32,
    reduce: fn(std::vec::IntoIter<f32>) -> f32,
) -> Output {
    let rows: Vec<f32> = a
        .f32s(0)
        .iter()
        .zip(a.f32s(1))
        .map(|(&o, &n)| f(o, n))
        .collect();
    Output::F32(reduce(rows.into_iter()))
}

/// The checks, with their cases (deterministic: seeded).
fn checks() -> Vec<CheckCases> {
    let random = random(15, |g| {
        let n = g.int(2, 60);
        let old: Vec<f32> = (0..n).map(|_| g.f(0.05, 0.95).ln()).collect();
        let spread = g.f(0.1, 0.6);
        let new = old.iter().map(|o| o + g.f(-spread, spread)).collect();
        case(old, new)
    });
    let recorded = fixture(|b| {
        b.epochs
            .iter()
            .skip(1)
            .map(|(log_probs, _)| case(b.old_log_probs.clone(), log_probs.clone()))
            .collect()
    });
    let single = vec![case(vec![-0.7], vec![-0.2]), case(vec![-0.2], vec![-0.7])];
    let unchanged = vec![case(vec![-0.69, -0.1, -2.3], vec![-0.69, -0.1, -2.3])];
    let one_sided = vec![case(
        vec![-1.0, -1.0, -1.0, -1.0],
        vec![-0.6, -0.7, -0.5, -0.8],
    )];
    vec![
        random,
        recorded,
        check(
            Text::new("a single step, either way", "只有一步，两个方向"),
            single,
        ),
        check(
            Text::new("the first epoch (nothing moved)", "第一轮（什么都没变）"),
            unchanged,
        ),
        check(
            Text::new(
                "every action more likely than before",
                "每个动作的概率都比以前高",
            ),
            one_sided,
        ),
    ]
}

fn case(old_log_probs: Vec<f32>, log_probs: Vec<f32>) -> Vec<Arg> {
    vec![Arg::F32s(old_log_probs), Arg::F32s(log_probs)]
}
