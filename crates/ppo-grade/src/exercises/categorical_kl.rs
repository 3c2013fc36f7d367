//! `categorical_kl` (lesson 10): the exact `KL(π_old(·|s) ‖ π_new(·|s))` of each state, the
//! divergence PPO-Penalty adds to its loss. It tests what the divergence is (an expectation
//! under the old policy over every action) in situations the lesson does not show: more than
//! two actions, and old rows that put exactly 0 on some action. Its signature, reference,
//! typical mistakes and cases; the hints that name the mistakes are in the lesson's
//! `exercise.toml`.

use crate::plain::*;
use crate::solutions as sol;
use crate::value::{Arg, Kind, OutKind, Output};

/// PyTorch's `kl_divergence(Categorical(probs=old), Categorical(probs=new))` on seeded
/// softmax rows of 2 to 6 actions, some old rows with exact zeros, recorded by
/// `tests/fixtures/categorical_kl_pytorch.py`.
const TORCH_FIXTURE: &str = include_str!("../../../../tests/fixtures/categorical_kl_pytorch.json");

/// The exercise.
pub const EXERCISE: Plain = Plain {
    name: "categorical_kl",
    lesson: "10-trust-region",
    params: &[
        ("old_probs", Kind::F32s),
        ("new_probs", Kind::F32s),
        ("n_actions", Kind::Usize),
    ],
    output: OutKind::F32s,
    // A row sums up to six terms of either sign (each `p·ln(p/q)`), and a right answer may
    // write `ln(p/q)` or `ln p − ln q`: 1e-5 absolute, 1e-4 relative. Every mistake is off
    // by far more on some case.
    tolerance: LOSS_TOL,
    reference: |a| call(a, sol::trust_region::categorical_kl),
    mistakes: &[
        Mistake {
            id: "reversed",
            answer: |a| rows(a, |p, q| kl(q, p)),
        },
        Mistake {
            id: "unweighted_log_ratios",
            answer: |a| rows(a, |p, q| p.iter().zip(q).map(|(p, q)| (p / q).ln()).sum()),
        },
        Mistake {
            id: "mean_over_actions",
            answer: |a| rows(a, |p, q| kl(p, q) / p.len() as f32),
        },
        Mistake {
            id: "no_zero_convention",
            answer: |a| {
                rows(a, |p, q| {
                    p.iter().zip(q).map(|(p, q)| p * (p / q).ln()).sum()
                })
            },
        },
        Mistake {
            id: "log_base_2",
            answer: |a| rows(a, |p, q| kl(p, q) / std::f32::consts::LN_2),
        },
        Mistake {
            id: "log_base_10",
            answer: |a| rows(a, |p, q| kl(p, q) / std::f32::consts::LN_10),
        },
        Mistake {
            id: "symmetric",
            answer: |a| rows(a, |p, q| 0.5 * (kl(p, q) + kl(q, p))),
        },
    ],
    checks,
};

/// The signature of `categorical_kl`.
pub type Signature = fn(&[f32], &[f32], usize) -> Vec<f32>;

/// Grades a `categorical_kl` running in this process (a notebook cell): the cases,
/// diagnosis and hints of `ppo-tutor grade categorical_kl`.
#[must_use]
pub fn in_place(f: Signature) -> crate::Report {
    EXERCISE.grade_in_place(std::sync::Arc::new(move |a: Args<'_>| call(a, f)))
}

/// `f` on a case's three arguments.
fn call(a: Args<'_>, f: Signature) -> Output {
    Output::F32s(f(a.f32s(0), a.f32s(1), a.usize(2)))
}

/// `Σ p·ln(p/q)` over the entries with `p > 0`: `KL(p ‖ q)` of one row.
fn kl(p: &[f32], q: &[f32]) -> f32 {
    p.iter()
        .zip(q)
        .filter(|(p, _)| **p > 0.0)
        .map(|(p, q)| p * (p.ln() - q.ln()))
        .sum()
}

/// `f(old row, new row)` for each row of the case.
fn rows(a: Args<'_>, f: impl Fn(&[f32], &[f32]) -> f32) -> Output {
    let k = a.usize(2).max(1);
    Output::F32s(
        a.f32s(0)
            .chunks(k)
            .zip(a.f32s(1).chunks(k))
            .map(|(p, q)| f(p, q))
            .collect(),
    )
}

/// The softmax of `logits`.
fn softmax(logits: &[f32]) -> Vec<f32> {
    let max = logits.iter().copied().fold(f32::NEG_INFINITY, f32::max);
    let exp: Vec<f32> = logits.iter().map(|l| (l - max).exp()).collect();
    let total: f32 = exp.iter().sum();
    exp.iter().map(|e| e / total).collect()
}

/// A policy-like pair of rows over `k` actions: the old one the softmax of logits of scale
/// up to `scale`, the new one the softmax of those logits moved by up to `spread`.
fn pair(g: &mut Gen, k: usize, scale: f32, spread: f32) -> (Vec<f32>, Vec<f32>) {
    let logits: Vec<f32> = (0..k).map(|_| g.f(-scale, scale)).collect();
    let moved: Vec<f32> = logits.iter().map(|l| l + g.f(-spread, spread)).collect();
    (softmax(&logits), softmax(&moved))
}

/// `old` with each action but its largest set to 0 with probability `p`, renormalised.
fn with_zeros(g: &mut Gen, old: &[f32], p: f64) -> Vec<f32> {
    let keep = old
        .iter()
        .enumerate()
        .fold(0, |best, (a, &x)| if x > old[best] { a } else { best });
    let masked: Vec<f32> = old
        .iter()
        .enumerate()
        .map(|(a, &x)| if a != keep && g.chance(p) { 0.0 } else { x })
        .collect();
    let total: f32 = masked.iter().sum();
    masked.iter().map(|x| x / total).collect()
}

/// A random case of `n` rows over `k` actions; each old row has zeros with probability
/// `zero_rows`.
fn random_case(g: &mut Gen, n: usize, k: usize, zero_rows: f64) -> Vec<Arg> {
    let scale = g.f(0.5, 4.0);
    let spread = g.f(0.05, 1.5);
    let (mut old, mut new) = (Vec::with_capacity(n * k), Vec::with_capacity(n * k));
    for _ in 0..n {
        let (p, q) = pair(g, k, scale, spread);
        if g.chance(zero_rows) {
            old.extend(with_zeros(g, &p, 0.5));
        } else {
            old.extend(p);
        }
        new.extend(q);
    }
    case(old, new, k)
}

/// The checks, with their cases (deterministic: seeded).
fn checks() -> Vec<CheckCases> {
    let random = random(10, |g| {
        let n = g.int(1, 30);
        let k = g.int(2, 6);
        random_case(g, n, k, 0.0)
    });
    let mut g = Gen::new(11);
    let mut zeros = vec![
        // A row that never takes action 2, one that always takes action 0, and an ordinary
        // one: ln 1.25, ln(1/0.7), and 0.6·ln 1.5 + 0.4·ln 0.8.
        case(
            vec![0.5, 0.5, 0.0, 1.0, 0.0, 0.0, 0.6, 0.4, 0.0],
            vec![0.4, 0.4, 0.2, 0.7, 0.2, 0.1, 0.4, 0.5, 0.1],
            3,
        ),
        case(vec![0.0, 1.0, 0.25, 0.75], vec![0.3, 0.7, 0.25, 0.75], 2),
    ];
    zeros.extend((0..8).map(|_| {
        let (n, k) = (g.int(1, 12), g.int(3, 6));
        random_case(&mut g, n, k, 0.6)
    }));
    let same = vec![
        case(vec![0.5, 0.5, 0.9, 0.1], vec![0.5, 0.5, 0.9, 0.1], 2),
        case(
            vec![0.2, 0.1, 0.2, 0.5, 0.25, 0.25, 0.25, 0.25],
            vec![0.2, 0.1, 0.2, 0.5, 0.25, 0.25, 0.25, 0.25],
            4,
        ),
    ];
    let one_row = vec![case(
        vec![0.05, 0.1, 0.15, 0.2, 0.2, 0.3],
        vec![0.5, 0.2, 0.1, 0.1, 0.05, 0.05],
        6,
    )];
    let empty = vec![
        case(Vec::new(), Vec::new(), 2),
        case(Vec::new(), Vec::new(), 5),
    ];
    vec![
        random,
        check(
            Text::new(
                "the old policy never takes some actions",
                "旧策略从不采取某些动作",
            ),
            zeros,
        ),
        check(
            Text::new(
                "rows where the two policies agree (0)",
                "两个策略一致的行（为 0）",
            ),
            same,
        ),
        check(Text::new("a single row", "只有一行"), one_row),
        check(
            Text::new(
                "PyTorch's kl_divergence of two Categoricals (recorded)",
                "PyTorch 对两个 Categorical 分布求 kl_divergence（录制）",
            ),
            torch_cases(),
        ),
        check(Text::new("no rows", "没有行"), empty),
    ]
}

fn case(old_probs: Vec<f32>, new_probs: Vec<f32>, n_actions: usize) -> Vec<Arg> {
    vec![
        Arg::F32s(old_probs),
        Arg::F32s(new_probs),
        Arg::Usize(n_actions),
    ]
}

/// One recorded case of the PyTorch fixture.
struct TorchCase {
    old: Vec<f32>,
    new: Vec<f32>,
    n_actions: usize,
    /// PyTorch's KL of each row (the unit test holds the reference to it).
    #[cfg_attr(not(test), allow(dead_code))]
    kl: Vec<f32>,
}

/// The fixture's cases.
fn torch_rows() -> Vec<TorchCase> {
    let Ok(json) = serde_json::from_str::<serde_json::Value>(TORCH_FIXTURE) else {
        return Vec::new();
    };
    let floats = |v: &serde_json::Value| -> Option<Vec<f32>> {
        v.as_array()?
            .iter()
            .map(|x| x.as_f64().map(|x| x as f32))
            .collect()
    };
    let cases = json["cases"].as_array().cloned().unwrap_or_default();
    cases
        .iter()
        .filter_map(|c| {
            let k = usize::try_from(c["n_actions"].as_u64()?).ok()?;
            Some(TorchCase {
                old: floats(&c["old_probs"])?,
                new: floats(&c["new_probs"])?,
                n_actions: k,
                kl: floats(&c["kl"])?,
            })
        })
        .collect()
}

/// Each recorded case as it is.
fn torch_cases() -> Vec<Vec<Arg>> {
    torch_rows()
        .into_iter()
        .map(|c| case(c.old, c.new, c.n_actions))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Provenance: `tests/fixtures/categorical_kl_pytorch.json`, made by
    /// `tests/fixtures/categorical_kl_pytorch.py` (torch 2.15.0, CPU, float32): 10 cases,
    /// 109 rows of 2 to 6 actions, 26 zero entries in old rows. The reference agrees with
    /// PyTorch's `kl_divergence` on every row within the exercise's tolerance, zeros
    /// included (PyTorch also counts 0 for them).
    #[test]
    fn the_reference_equals_pytorchs_kl_divergence() {
        let rows = torch_rows();
        assert_eq!(rows.len(), 10, "the PyTorch fixture is embedded");
        let tol = EXERCISE.tolerance;
        let mut zeros = 0;
        for TorchCase {
            old,
            new,
            n_actions: k,
            kl: want,
        } in &rows
        {
            zeros += old.iter().filter(|p| **p == 0.0).count();
            let got = sol::trust_region::categorical_kl(old, new, *k);
            assert_eq!(got.len(), want.len());
            for (i, (&g, &w)) in got.iter().zip(want).enumerate() {
                let (g, w) = (f64::from(g), f64::from(w));
                assert!(
                    (g - w).abs() <= tol.abs + tol.rel * w.abs(),
                    "{k} actions, row {i}: got {g}, PyTorch {w}"
                );
            }
        }
        assert_eq!(zeros, 26, "the fixture has old rows with zeros");
    }

    /// The reference is never negative, exactly 0 where the rows agree, and one value per
    /// row; the helpers' `kl` is the reference.
    #[test]
    fn the_reference_obeys_the_contract() {
        for check in checks() {
            for args in &check.cases {
                let a = Args(args);
                let (old, new, k) = (a.f32s(0), a.f32s(1), a.usize(2));
                let got = sol::trust_region::categorical_kl(old, new, k);
                assert_eq!(got.len(), old.len() / k, "{}", check.name);
                for (i, (&value, (p, q))) in
                    got.iter().zip(old.chunks(k).zip(new.chunks(k))).enumerate()
                {
                    assert!(value >= -1e-6, "{}: row {i} is {value}", check.name);
                    assert!(value.is_finite(), "{}: row {i}", check.name);
                    if p == q {
                        assert_eq!(value, 0.0, "{}: row {i}", check.name);
                    }
                    assert_eq!(value, kl(p, q), "{}: row {i}", check.name);
                }
            }
        }
    }

    /// Graded in place (a notebook cell), the reference passes and a learner-like answer
    /// without the convention for `π_old = 0` is diagnosed as such.
    #[test]
    fn in_place_grading_passes_the_reference_and_names_a_mistake() {
        let report = in_place(sol::trust_region::categorical_kl);
        assert!(report.passed(), "{}", report.render());
        fn no_convention(old: &[f32], new: &[f32], k: usize) -> Vec<f32> {
            let mut out = Vec::new();
            for (p, q) in old.chunks(k).zip(new.chunks(k)) {
                let mut kl = 0.0;
                for a in 0..k {
                    kl += p[a] * (p[a] / q[a]).ln();
                }
                out.push(kl);
            }
            out
        }
        let report = in_place(no_convention);
        assert!(!report.passed());
        assert_eq!(report.mistake.as_deref(), Some("no_zero_convention"));
    }

    /// Every mistake differs from the reference and from every other mistake on some
    /// case, so the judge can tell them apart.
    #[test]
    fn the_mistakes_are_told_apart() {
        let cases: Vec<Vec<Arg>> = checks().into_iter().flat_map(|c| c.cases).collect();
        let tol = EXERCISE.tolerance;
        let mut variants: Vec<(&str, Compute)> = vec![("reference", EXERCISE.reference)];
        variants.extend(EXERCISE.mistakes.iter().map(|m| (m.id, m.answer)));
        for (i, (a, fa)) in variants.iter().enumerate() {
            for (b, fb) in &variants[i + 1..] {
                let apart = cases
                    .iter()
                    .any(|c| fa(Args(c)).differs(&fb(Args(c)), tol).is_some());
                assert!(apart, "{a} and {b} agree on every case");
            }
        }
    }
}
