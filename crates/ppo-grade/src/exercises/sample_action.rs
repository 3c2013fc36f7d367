//! `sample_action` (lesson 3): sampling an action from the policy's probabilities with one uniform number. Its signature, reference, typical mistakes
//! and cases; the hints that name the mistakes are in the lesson's `exercise.toml`.

use crate::plain::*;
use crate::solutions as sol;
use crate::value::{Arg, Kind, OutKind, Output};

/// The exercise.
pub const EXERCISE: Plain = Plain {
    name: "sample_action",
    lesson: "03-episode-loop",
    params: &[("probs", Kind::F32s), ("u", Kind::F32)],
    output: OutKind::Usize,
    tolerance: F32_TOL,
    reference: |a| Output::Usize(sol::episode_loop::sample_action(a.f32s(0), a.f32(1))),
    mistakes: &[
        Mistake {
            id: "swapped_actions",
            answer: |a| {
                let n = a.f32s(0).len();
                let right = sol::episode_loop::sample_action(a.f32s(0), a.f32(1));
                Output::Usize(n.saturating_sub(1).saturating_sub(right))
            },
        },
        Mistake {
            id: "greedy",
            answer: |a| {
                let probs = a.f32s(0);
                let best = probs
                    .iter()
                    .enumerate()
                    .fold(
                        (0, f32::NEG_INFINITY),
                        |b, (i, &p)| {
                            if p > b.1 { (i, p) } else { b }
                        },
                    );
                Output::Usize(best.0)
            },
        },
        Mistake {
            id: "less_or_equal",
            answer: |a| {
                let (probs, u) = (a.f32s(0), a.f32(1));
                let mut c = 0.0_f32;
                for (i, &p) in probs.iter().enumerate() {
                    c += p;
                    if u <= c {
                        return Output::Usize(i);
                    }
                }
                Output::Usize(probs.len().saturating_sub(1))
            },
        },
        Mistake {
            id: "no_cumulative",
            answer: |a| {
                let (probs, u) = (a.f32s(0), a.f32(1));
                let i = probs.iter().position(|&p| u < p);
                Output::Usize(i.unwrap_or(probs.len().saturating_sub(1)))
            },
        },
        Mistake {
            id: "no_fallback",
            answer: |a| {
                let (probs, u) = (a.f32s(0), a.f32(1));
                let mut c = 0.0_f32;
                for (i, &p) in probs.iter().enumerate() {
                    c += p;
                    if u < c {
                        return Output::Usize(i);
                    }
                }
                Output::Usize(probs.len())
            },
        },
    ],
    checks,
};

/// Grades a `sample_action` running in this process (a notebook cell): the cases, diagnosis and
/// hints of `ppo-tutor grade sample_action`.
#[must_use]
pub fn in_place(f: fn(&[f32], f32) -> usize) -> crate::Report {
    EXERCISE.grade_in_place(std::sync::Arc::new(move |a: Args<'_>| {
        Output::Usize(f(a.f32s(0), a.f32(1)))
    }))
}

/// The checks, with their cases (deterministic: seeded).
fn checks() -> Vec<CheckCases> {
    // u is kept away from the cumulative sums, where f32 and f64 sums could disagree.
    fn away_from_edges(g: &mut Gen, probs: &[f32]) -> f32 {
        loop {
            let u = g.f(0.0, 1.0);
            let mut c = 0.0_f32;
            let near = probs.iter().any(|&p| {
                c += p;
                (u - c).abs() < 1e-4
            });
            if !near {
                return u;
            }
        }
    }
    let random = random(6, |g| {
        let n = if g.chance(0.7) { 2 } else { g.int(3, 5) };
        let raw = g.f32s(n, 0.05, 1.0);
        let total: f32 = raw.iter().sum();
        let probs: Vec<f32> = raw.iter().map(|p| p / total).collect();
        let u = away_from_edges(g, &probs);
        vec![Arg::F32s(probs), Arg::F32(u)]
    });
    let policy = fixture(|b| {
        b.probs
            .iter()
            .take(40)
            .map(|p| {
                let u = away_from_edges(&mut Gen::for_pair(p), p);
                vec![Arg::F32s(p.to_vec()), Arg::F32(u)]
            })
            .collect()
    });
    let zero = vec![
        vec![Arg::F32s(vec![0.0, 1.0]), Arg::F32(0.0)],
        vec![Arg::F32s(vec![1.0, 0.0]), Arg::F32(0.999_9)],
        vec![Arg::F32s(vec![0.5, 0.0, 0.5]), Arg::F32(0.5)],
        vec![Arg::F32s(vec![0.25, 0.75]), Arg::F32(0.0)],
    ];
    let near_one = vec![
        vec![Arg::F32s(vec![0.3, 0.699_99]), Arg::F32(0.999_995)],
        vec![Arg::F32s(vec![0.2, 0.2, 0.599_9]), Arg::F32(0.999_95)],
        // The last action has probability 0 and still gets what rounding left over (the
        // sum, 0.99998999 in f32 and in f64, is below u).
        vec![Arg::F32s(vec![0.3, 0.699_99, 0.0]), Arg::F32(0.999_995)],
    ];
    vec![
        random,
        policy,
        check(
            Text::new(
                "an action of probability 0 is never chosen",
                "概率为 0 的动作永远不会被选中",
            ),
            zero,
        ),
        check(
            Text::new(
                "probabilities summing a hair below u",
                "概率之和比 u 略小一点",
            ),
            near_one,
        ),
    ]
}

impl Gen {
    /// A generator seeded from a probability pair, so fixture cases do not depend on order.
    fn for_pair(p: &[f32; 2]) -> Self {
        Self::new(u64::from(p[0].to_bits()) ^ (u64::from(p[1].to_bits()) << 17))
    }
}
