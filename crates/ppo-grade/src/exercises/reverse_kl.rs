//! `reverse_kl` (lesson 13): the other direction of the KL divergence, KL(π_θ ‖ π_old),
//! estimated from rows whose actions π_old drew. Each row weighs its log-ratio by the
//! importance weight r and adds the control variate r − 1 with the sign that makes it
//! `r·log r − (r − 1) ≥ 0`. Its signature, reference, typical mistakes and cases; the hints
//! that name the mistakes are in the lesson's `exercise.toml`.

use crate::plain::*;
use crate::solutions as sol;
use crate::value::{Arg, Kind, OutKind, Output};

/// The exercise.
pub const EXERCISE: Plain = Plain {
    name: "reverse_kl",
    lesson: "13-clip-lab",
    params: &[("old_log_probs", Kind::F32s), ("log_probs", Kind::F32s)],
    output: OutKind::F32,
    tolerance: LOSS_TOL,
    reference: |a| Output::F32(sol::clip_lab::reverse_kl(a.f32s(0), a.f32s(1))),
    mistakes: &[
        Mistake {
            id: "forward_direction",
            answer: |a| per_row(a, |x, r| (r - 1.0) - x, mean),
        },
        Mistake {
            id: "no_correction",
            answer: |a| per_row(a, |x, r| r * x, mean),
        },
        Mistake {
            id: "unweighted_log_ratio",
            answer: |a| per_row(a, |x, _| x, mean),
        },
        Mistake {
            id: "correction_sign_flipped",
            answer: |a| per_row(a, |x, r| r * x + (r - 1.0), mean),
        },
        Mistake {
            id: "sum_instead_of_mean",
            answer: |a| per_row(a, |x, r| r * x - (r - 1.0), sum),
        },
    ],
    checks,
};

/// The signature of `reverse_kl`.
pub type Signature = fn(&[f32], &[f32]) -> f32;

/// Grades a `reverse_kl` running in this process (a notebook cell): the cases, diagnosis
/// and hints of `ppo-tutor grade reverse_kl`.
#[must_use]
pub fn in_place(f: Signature) -> crate::Report {
    EXERCISE.grade_in_place(std::sync::Arc::new(move |a: Args<'_>| {
        Output::F32(f(a.f32s(0), a.f32s(1)))
    }))
}

/// `reduce` over the rows of `f(x, r)`, with the row's log-ratio `x = log π_θ − log π_old`
/// and ratio `r = eˣ`.
fn per_row(
    a: Args<'_>,
    f: impl Fn(f32, f32) -> f32,
    reduce: fn(std::vec::IntoIter<f32>) -> f32,
) -> Output {
    let rows: Vec<f32> = a
        .f32s(0)
        .iter()
        .zip(a.f32s(1))
        .map(|(&old, &new)| {
            let x = new - old;
            f(x, x.exp())
        })
        .collect();
    Output::F32(reduce(rows.into_iter()))
}

/// The checks, with their cases (deterministic: seeded).
fn checks() -> Vec<CheckCases> {
    let random = random(131, |g| {
        let n = g.int(2, 60);
        let old: Vec<f32> = (0..n).map(|_| g.f(0.05, 0.95).ln()).collect();
        // Moves of up to ±0.6 in log-probability, both ways, kept below probability 1.
        let spread = g.f(0.1, 0.6);
        let new = old
            .iter()
            .map(|o| (o + g.f(-spread, spread)).min(-1e-3))
            .collect();
        case(old, new)
    });
    let recorded = fixture(|b| {
        b.epochs
            .iter()
            .skip(1)
            .map(|(log_probs, _)| case(b.old_log_probs.clone(), log_probs.clone()))
            .collect()
    });
    // One row alone is its own estimate: a row whose action became less likely (r < 1) is
    // where r·log r alone, log r alone and the flipped correction go negative; the right
    // term stays above 0 on every one.
    let single = vec![
        case(vec![-0.7], vec![-0.2]),
        case(vec![-0.2], vec![-0.7]),
        case(vec![-0.5], vec![-2.0]),
    ];
    // Nothing moved: log-ratio exactly 0, r exactly 1, every row's term exactly 0.
    let unchanged = vec![case(vec![-0.69, -0.1, -2.3], vec![-0.69, -0.1, -2.3])];
    // Every sampled action less likely than before: the mean of r·log r is negative here.
    let less_likely = vec![case(
        vec![-0.5, -0.5, -0.5, -0.5],
        vec![-0.9, -0.8, -1.0, -0.7],
    )];
    vec![
        random,
        recorded,
        check(
            Text::new(
                "a single row, its action more and less likely",
                "只有一行，它的动作概率变高或变低",
            ),
            single,
        ),
        check(
            Text::new("the first epoch (nothing moved)", "第一轮（什么都没变）"),
            unchanged,
        ),
        check(
            Text::new(
                "every action less likely than before",
                "每个动作的概率都比以前低",
            ),
            less_likely,
        ),
    ]
}

fn case(old_log_probs: Vec<f32>, log_probs: Vec<f32>) -> Vec<Arg> {
    vec![Arg::F32s(old_log_probs), Arg::F32s(log_probs)]
}

#[cfg(test)]
mod tests {
    use super::*;

    fn value(f: Compute, case: &[Arg]) -> f32 {
        match f(Args(case)) {
            Output::F32(v) => v,
            other => panic!("not one number: {other:?}"),
        }
    }

    /// Each single row is its own estimate: the reference is above 0 on every one, and the
    /// mistakes that can go negative do so on the rows whose action became less likely.
    /// Where nothing moved the reference is exactly 0, and the five mistakes and the
    /// reference are six different numbers on the batch that moved every action one way.
    #[test]
    fn the_edge_cases_sit_where_the_contract_says_and_separate_the_mistakes() {
        let checks = checks();
        let named = |en: &str| {
            checks
                .iter()
                .find(|c| c.name.in_lang(crate::i18n::Lang::En) == en)
                .unwrap_or_else(|| panic!("no check {en:?}"))
        };
        let answer = |id: &str| {
            EXERCISE
                .mistakes
                .iter()
                .find(|m| m.id == id)
                .unwrap_or_else(|| panic!("no mistake {id}"))
                .answer
        };
        for case in &named("a single row, its action more and less likely").cases {
            assert!(value(EXERCISE.reference, case) > 0.0, "{case:?}");
            if Args(case).f32s(1)[0] < Args(case).f32s(0)[0] {
                for id in [
                    "no_correction",
                    "unweighted_log_ratio",
                    "correction_sign_flipped",
                ] {
                    assert!(value(answer(id), case) < 0.0, "{id}: {case:?}");
                }
            }
        }
        for case in &named("the first epoch (nothing moved)").cases {
            assert_eq!(value(EXERCISE.reference, case), 0.0);
        }
        let case = &named("every action less likely than before").cases[0];
        let mut values: Vec<f32> = EXERCISE
            .mistakes
            .iter()
            .map(|m| value(m.answer, case))
            .chain([value(EXERCISE.reference, case)])
            .collect();
        values.sort_by(f32::total_cmp);
        assert!(values.windows(2).all(|w| w[1] - w[0] > 1e-3), "{values:?}");
    }
}
