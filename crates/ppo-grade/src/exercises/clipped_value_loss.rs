//! `clipped_value_loss` (lesson 12): CleanRL's clipped value loss, PPO's clip applied to the
//! critic. Its signature, reference, typical mistakes and cases; the hints that name the
//! mistakes are in the lesson's `exercise.toml`.

use crate::plain::*;
use crate::solutions as sol;
use crate::value::{Arg, Kind, OutKind, Output};

/// The exercise.
pub const EXERCISE: Plain = Plain {
    name: "clipped_value_loss",
    lesson: "12-losses",
    params: &[
        ("values", Kind::F32s),
        ("old_values", Kind::F32s),
        ("returns", Kind::F32s),
        ("eps", Kind::F32),
    ],
    output: OutKind::F32,
    tolerance: LOSS_TOL,
    reference: |a| {
        Output::F32(sol::losses::clipped_value_loss(
            a.f32s(0),
            a.f32s(1),
            a.f32s(2),
            a.f32(3),
        ))
    },
    mistakes: &[
        Mistake {
            id: "min_instead_of_max",
            answer: |a| loss(a, around_old, f32::min, mean, 0.5),
        },
        Mistake {
            id: "clamps_the_value_not_the_change",
            answer: |a| loss(a, |v, _, _, eps| v.clamp(-eps, eps), f32::max, mean, 0.5),
        },
        Mistake {
            id: "clips_around_returns",
            answer: |a| loss(a, around_returns, f32::max, mean, 0.5),
        },
        Mistake {
            id: "no_half",
            answer: |a| loss(a, around_old, f32::max, mean, 1.0),
        },
        Mistake {
            id: "clipped_term_only",
            answer: |a| loss(a, around_old, |_, clipped| clipped, mean, 0.5),
        },
        Mistake {
            id: "sum_not_mean",
            answer: |a| loss(a, around_old, f32::max, sum, 0.5),
        },
    ],
    checks,
};

/// The signature of `clipped_value_loss`.
pub type Signature = fn(&[f32], &[f32], &[f32], f32) -> f32;

/// Grades a `clipped_value_loss` running in this process (a notebook cell): the cases,
/// diagnosis and hints of `ppo-tutor grade clipped_value_loss`.
#[must_use]
pub fn in_place(f: Signature) -> crate::Report {
    EXERCISE.grade_in_place(std::sync::Arc::new(move |a: Args<'_>| {
        Output::F32(f(a.f32s(0), a.f32s(1), a.f32s(2), a.f32(3)))
    }))
}

/// CleanRL's clipped prediction: `old + clamp(v − old, −ε, ε)`.
fn around_old(v: f32, old: f32, _ret: f32, eps: f32) -> f32 {
    old + (v - old).clamp(-eps, eps)
}

/// The prediction held within ε of the return instead: `R + clamp(v − R, −ε, ε)`.
fn around_returns(v: f32, _old: f32, ret: f32, eps: f32) -> f32 {
    ret + (v - ret).clamp(-eps, eps)
}

/// `scale · reduce_i keep((v − R)², (v̂ − R)²)`, with `v̂ = clipped(v, old, R, ε)`.
fn loss(
    a: Args<'_>,
    clipped: impl Fn(f32, f32, f32, f32) -> f32,
    keep: fn(f32, f32) -> f32,
    reduce: fn(std::vec::IntoIter<f32>) -> f32,
    scale: f32,
) -> Output {
    let eps = a.f32(3);
    let rows: Vec<f32> = a
        .f32s(0)
        .iter()
        .zip(a.f32s(1))
        .zip(a.f32s(2))
        .map(|((&v, &old), &ret)| {
            let v_clipped = clipped(v, old, ret, eps);
            keep((v - ret) * (v - ret), (v_clipped - ret) * (v_clipped - ret))
        })
        .collect();
    Output::F32(scale * reduce(rows.into_iter()))
}

/// The checks, with their cases (deterministic: seeded).
fn checks() -> Vec<CheckCases> {
    let random = random(111, |g| {
        let n = g.int(1, 50);
        let scale = g.f(0.5, 30.0);
        let eps = if g.chance(0.5) {
            0.2
        } else {
            g.f(0.05, 0.3) * scale
        };
        let old = g.f32s(n, -scale, scale);
        // Some predictions stay within ε of the old ones, others move up to 4ε away, either
        // way; the returns lie on either side of both, near and far.
        let values = old
            .iter()
            .map(|o| {
                let reach = if g.chance(0.4) { 0.95 } else { 4.0 };
                o + g.f(-reach, reach) * eps
            })
            .collect();
        let returns = old.iter().map(|o| o + g.f(-5.0, 5.0) * eps).collect();
        case(values, old, returns, eps)
    });
    // The first epoch: the critic has not moved, so nothing is clipped.
    let recorded = fixture(|b| {
        vec![case(
            b.values.clone(),
            b.values.clone(),
            b.td_target.clone(),
            0.2,
        )]
    });
    let within = vec![
        case(
            vec![1.1, 1.85, -0.45, 3.0],
            vec![1.0, 2.0, -0.5, 3.0],
            vec![2.0, 0.0, -1.0, 3.5],
            0.2,
        ),
        case(vec![12.5, 7.0], vec![11.0, 8.5], vec![20.0, 2.0], 2.0),
    ];
    // Rows 1 and 3 moved towards their returns past ε (the clip acts), rows 2 and 4 went
    // past theirs (the plain error is the larger).
    let beyond = vec![case(
        vec![1.6, 3.0, -0.4, -2.0],
        vec![1.0, 1.0, 0.5, 0.0],
        vec![2.5, 1.5, -1.5, -0.5],
        0.2,
    )];
    let single = vec![
        case(vec![1.5], vec![1.0], vec![2.0], 0.2),
        case(vec![3.0], vec![1.0], vec![1.5], 0.2),
    ];
    vec![
        random,
        recorded,
        check(
            Text::new(
                "values within eps of old: the plain half MSE",
                "新旧价值相差不超过 ε：就是普通的半均方误差",
            ),
            within,
        ),
        check(
            Text::new("every value moved beyond eps", "每个价值都移动超过了 ε"),
            beyond,
        ),
        check(Text::new("a single row", "只有一行"), single),
    ]
}

fn case(values: Vec<f32>, old_values: Vec<f32>, returns: Vec<f32>, eps: f32) -> Vec<Arg> {
    vec![
        Arg::F32s(values),
        Arg::F32s(old_values),
        Arg::F32s(returns),
        Arg::F32(eps),
    ]
}
