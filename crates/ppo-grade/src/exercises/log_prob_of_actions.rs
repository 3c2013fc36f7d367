//! `log_prob_of_actions` (lesson 9): the log-probability of each action taken. Its signature, reference, typical mistakes
//! and cases; the hints that name the mistakes are in the lesson's `exercise.toml`.

use crate::plain::*;
use crate::solutions as sol;
use crate::value::{Arg, Kind, OutKind, Output};

/// The exercise.
pub const EXERCISE: Plain = Plain {
    name: "log_prob_of_actions",
    lesson: "09-ratio",
    params: &[("probs", Kind::Pairs), ("actions", Kind::Usizes)],
    output: OutKind::F32s,
    tolerance: F32_TOL,
    reference: |a| Output::F32s(sol::ratio::log_prob_of_actions(a.pairs(0), a.usizes(1))),
    mistakes: &[
        Mistake {
            id: "no_log",
            answer: |a| gathered(a, |p, act| p[act]),
        },
        Mistake {
            id: "swapped_actions",
            answer: |a| gathered(a, |p, act| p[1 - act].ln()),
        },
        Mistake {
            id: "log10",
            answer: |a| gathered(a, |p, act| p[act].log10()),
        },
    ],
    checks,
};

/// Grades a `log_prob_of_actions` running in this process (a notebook cell): the cases, diagnosis and
/// hints of `ppo-tutor grade log_prob_of_actions`.
#[must_use]
pub fn in_place(f: fn(&[[f32; 2]], &[usize]) -> Vec<f32>) -> crate::Report {
    EXERCISE.grade_in_place(std::sync::Arc::new(move |a: Args<'_>| Output::F32s(f(a.pairs(0), a.usizes(1)))))
}

fn gathered(a: Args<'_>, f: impl Fn(&[f32; 2], usize) -> f32) -> Output {
    Output::F32s(
        a.pairs(0)
            .iter()
            .zip(a.usizes(1))
            .map(|(p, &act)| f(p, act.min(1)))
            .collect(),
    )
}

/// The checks, with their cases (deterministic: seeded).
fn checks() -> Vec<CheckCases> {
    let random = random(9, |g| {
        let n = g.int(1, 60);
        let probs: Vec<[f32; 2]> = (0..n)
            .map(|_| {
                let p = g.f(0.01, 0.99);
                [p, 1.0 - p]
            })
            .collect();
        let actions = (0..n).map(|_| g.int(0, 1)).collect();
        vec![Arg::Pairs(probs), Arg::Usizes(actions)]
    });
    let recorded = fixture(|b| {
        vec![vec![
            Arg::Pairs(b.probs.clone()),
            Arg::Usizes(b.actions.clone()),
        ]]
    });
    let single = vec![
        vec![Arg::Pairs(vec![[0.3, 0.7]]), Arg::Usizes(vec![0])],
        vec![Arg::Pairs(vec![[0.3, 0.7]]), Arg::Usizes(vec![1])],
    ];
    let sure = vec![vec![
        Arg::Pairs(vec![[0.999, 0.001], [0.001, 0.999], [0.999, 0.001]]),
        Arg::Usizes(vec![0, 0, 1]),
    ]];
    vec![
        random,
        recorded,
        check("a single step", single),
        check("near-certain and near-impossible actions", sure),
    ]
}
