//! `compute_advantage` (lesson 8): GAE, the advantages as a backward recursion over the TD errors. Its signature, reference, typical mistakes
//! and cases; the hints that name the mistakes are in the lesson's `exercise.toml`.

use crate::plain::*;
use crate::solutions as sol;
use crate::value::{Arg, Kind, OutKind, Output, Tolerance};

/// The exercise.
pub const EXERCISE: Plain = Plain {
    name: "compute_advantage",
    lesson: "08-gae",
    params: &[
        ("gamma", Kind::F32),
        ("lmbda", Kind::F32),
        ("td_delta", Kind::F32s),
    ],
    output: OutKind::F32s,
    tolerance: Tolerance {
        abs: 1e-5,
        rel: 1e-4,
    },
    reference: |a| Output::F32s(sol::gae::compute_advantage(a.f32(0), a.f32(1), a.f32s(2))),
    mistakes: &[
        Mistake {
            id: "forwards",
            answer: |a| {
                let coef = gae_coef(a);
                let mut adv = 0.0_f32;
                Output::F32s(
                    a.f32s(2)
                        .iter()
                        .map(|&d| {
                            adv = coef * adv + d;
                            adv
                        })
                        .collect(),
                )
            },
        },
        Mistake {
            id: "not_reversed",
            answer: |a| {
                let mut out = gae_backwards(gae_coef(a), a.f32s(2));
                out.reverse();
                Output::F32s(out)
            },
        },
        Mistake {
            id: "no_lambda",
            answer: |a| Output::F32s(gae_backwards(a.f32(0), a.f32s(2))),
        },
        Mistake {
            id: "no_gamma",
            answer: |a| Output::F32s(gae_backwards(a.f32(1), a.f32s(2))),
        },
        Mistake {
            id: "no_recursion",
            answer: |a| Output::F32s(a.f32s(2).to_vec()),
        },
    ],
    checks,
};

/// Grades a `compute_advantage` running in this process (a notebook cell): the cases, diagnosis and
/// hints of `ppo-tutor grade compute_advantage`.
#[must_use]
pub fn in_place(f: fn(f32, f32, &[f32]) -> Vec<f32>) -> crate::Report {
    EXERCISE.grade_in_place(std::sync::Arc::new(move |a: Args<'_>| {
        Output::F32s(f(a.f32(0), a.f32(1), a.f32s(2)))
    }))
}

fn gae_backwards(coef: f32, td_delta: &[f32]) -> Vec<f32> {
    let mut out = vec![0.0; td_delta.len()];
    let mut adv = 0.0_f32;
    for (o, &d) in out.iter_mut().zip(td_delta).rev() {
        adv = coef * adv + d;
        *o = adv;
    }
    out
}

fn gae_coef(a: Args<'_>) -> f32 {
    (f64::from(a.f32(0)) * f64::from(a.f32(1))) as f32
}

/// The checks, with their cases (deterministic: seeded).
fn checks() -> Vec<CheckCases> {
    let random = random(8, |g| {
        let n = g.int(2, 80);
        let (gamma, lmbda) = if g.chance(0.5) {
            (0.98, 0.95)
        } else {
            (g.f(0.5, 1.0), g.f(0.3, 1.0))
        };
        gae_case(gamma, lmbda, g.f32s(n, -3.0, 3.0))
    });
    let recorded = fixture(|b| {
        vec![gae_case(
            b.config.gamma as f32,
            b.config.lmbda as f32,
            b.td_delta.clone(),
        )]
    });
    let single = vec![
        gae_case(0.98, 0.95, vec![0.7]),
        gae_case(0.98, 0.95, vec![-1.5]),
    ];
    let negative = vec![gae_case(0.98, 0.95, vec![-1.0, -0.5, -2.0, -0.25, -1.0])];
    let extremes = vec![
        gae_case(0.98, 0.0, vec![1.0, -2.0, 3.0]),
        gae_case(0.98, 1.0, vec![1.0, -2.0, 3.0]),
        gae_case(1.0, 1.0, vec![1.0, 1.0, 1.0, 1.0]),
    ];
    vec![
        random,
        recorded,
        check(Text::new("a single step", "只有一步"), single),
        check(Text::new("negative TD errors", "负的 TD 误差"), negative),
        check(Text::new("λ = 0 and λ = 1", "λ = 0 和 λ = 1"), extremes),
    ]
}

fn gae_case(gamma: f32, lmbda: f32, td_delta: Vec<f32>) -> Vec<Arg> {
    vec![Arg::F32(gamma), Arg::F32(lmbda), Arg::F32s(td_delta)]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The reference equals the library's GAE on the recorded PyTorch episodes.
    #[test]
    fn the_reference_equals_the_library() {
        let batches = fixture_batches();
        assert_eq!(batches.len(), 3, "the PyTorch fixture replays");
        for b in batches {
            let ours = crate::ppo::compute_advantage(b.config.gamma, b.config.lmbda, &b.td_delta);
            let reference = sol::gae::compute_advantage(
                b.config.gamma as f32,
                b.config.lmbda as f32,
                &b.td_delta,
            );
            for (x, y) in ours.iter().zip(&reference) {
                assert!((x - y).abs() <= 1e-5 + 1e-5 * x.abs(), "{x} vs {y}");
            }
        }
    }
}
