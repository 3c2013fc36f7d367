//! `diag_gaussian_log_prob` (lesson 17): the log-density of a diagonal Gaussian policy at the
//! actions taken, one number per row however many dimensions an action has (CleanRL's
//! `Normal(action_mean, action_logstd.exp()).log_prob(action).sum(1)`). Its signature,
//! reference, typical mistakes and cases; the hints that name the mistakes are in the
//! lesson's `exercise.toml`.

use crate::plain::*;
use crate::solutions as sol;
use crate::value::{Arg, Kind, OutKind, Output, Tolerance};

/// PyTorch's `Normal.log_prob` on seeded inputs shaped like the book's policy (μ = 2·tanh,
/// σ = softplus), recorded by `tests/fixtures/gaussian_log_prob_pytorch.py`. Each recorded
/// case becomes one row whose dimensions are the case's rows.
const TORCH_FIXTURE: &str =
    include_str!("../../../../tests/fixtures/gaussian_log_prob_pytorch.json");

/// `log √(2π)` rounded to f32, as the reference subtracts it.
const LOG_SQRT_2PI: f32 = 0.918_938_5;

/// The exercise.
pub const EXERCISE: Plain = Plain {
    name: "diag_gaussian_log_prob",
    lesson: "17-continuous-actions",
    params: &[
        ("actions", Kind::F32s),
        ("mu", Kind::F32s),
        ("log_std", Kind::F32s),
        ("dim", Kind::Usize),
    ],
    output: OutKind::F32s,
    // A row sums up to `dim` terms that can be large (a far action under a narrow σ), and
    // a right answer may order its f32 operations differently (σ² as exp(2·log σ), the
    // distance in units of σ): 1e-4 absolute, 1e-5 relative. Every mistake is off by far
    // more on some case.
    tolerance: Tolerance {
        abs: 1e-4,
        rel: 1e-5,
    },
    reference: |a| call(a, sol::continuous::diag_gaussian_log_prob),
    mistakes: &[
        Mistake {
            id: "mean_over_dims",
            answer: |a| rows(a, Rule::MEAN),
        },
        Mistake {
            id: "first_dim_only",
            answer: |a| {
                rows(
                    a,
                    Rule {
                        dims: Dims::First,
                        ..Rule::RIGHT
                    },
                )
            },
        },
        Mistake {
            id: "wrong_row_stride",
            answer: |a| {
                rows(
                    a,
                    Rule {
                        column_major: true,
                        ..Rule::RIGHT
                    },
                )
            },
        },
        Mistake {
            id: "log_std_as_std",
            answer: |a| {
                rows(
                    a,
                    Rule {
                        term: log_std_as_std,
                        ..Rule::RIGHT
                    },
                )
            },
        },
        Mistake {
            id: "variance_as_std",
            answer: |a| {
                rows(
                    a,
                    Rule {
                        term: log_variance,
                        ..Rule::RIGHT
                    },
                )
            },
        },
        Mistake {
            id: "missing_normaliser",
            answer: |a| {
                rows(
                    a,
                    Rule {
                        constant: Constant::None,
                        ..Rule::RIGHT
                    },
                )
            },
        },
        Mistake {
            id: "constant_once",
            answer: |a| {
                rows(
                    a,
                    Rule {
                        constant: Constant::OncePerRow,
                        ..Rule::RIGHT
                    },
                )
            },
        },
    ],
    checks,
};

/// The signature of `diag_gaussian_log_prob`.
pub type Signature = fn(&[f32], &[f32], &[f32], usize) -> Vec<f32>;

/// Grades a `diag_gaussian_log_prob` running in this process (a notebook cell): the cases,
/// diagnosis and hints of `ppo-tutor grade diag_gaussian_log_prob`.
#[must_use]
pub fn in_place(f: Signature) -> crate::Report {
    EXERCISE.grade_in_place(std::sync::Arc::new(move |a: Args<'_>| call(a, f)))
}

/// `f` on a case's four arguments.
fn call(a: Args<'_>, f: Signature) -> Output {
    Output::F32s(f(a.f32s(0), a.f32s(1), a.f32s(2), a.usize(3)))
}

/// Which dimensions a row's value takes in.
#[derive(Clone, Copy)]
enum Dims {
    /// Their sum, right.
    Sum,
    /// Their mean.
    Mean,
    /// Dimension 0 alone.
    First,
}

/// Where `−log √(2π)` is subtracted.
#[derive(Clone, Copy)]
enum Constant {
    /// Once per dimension, right.
    PerDimension,
    /// Once per row.
    OncePerRow,
    /// Nowhere.
    None,
}

/// One way of computing a row's log-density, right or wrong.
#[derive(Clone, Copy)]
struct Rule {
    /// One dimension's log-density without the constant, from `(a − μ, log_std[d])`.
    term: fn(f32, f32) -> f32,
    dims: Dims,
    constant: Constant,
    /// Reads element `(i, d)` at `d·N + i` instead of `i·dim + d`.
    column_major: bool,
}

impl Rule {
    const RIGHT: Self = Self {
        term: right_term,
        dims: Dims::Sum,
        constant: Constant::PerDimension,
        column_major: false,
    };
    const MEAN: Self = Self {
        dims: Dims::Mean,
        ..Self::RIGHT
    };
}

/// `−(a − μ)²/(2σ²) − log σ`, `σ = exp(log_std)`.
fn right_term(diff: f32, log_std: f32) -> f32 {
    let std = log_std.exp();
    -(diff * diff) / (2.0 * std * std) - log_std
}

/// The 1-D log-density with `log_std` taken for σ itself.
fn log_std_as_std(diff: f32, log_std: f32) -> f32 {
    let std = log_std;
    -(diff * diff) / (2.0 * std * std) - std.ln()
}

/// `−log σ²` where the density has `−log σ`.
fn log_variance(diff: f32, log_std: f32) -> f32 {
    let std = log_std.exp();
    let var = std * std;
    -(diff * diff) / (2.0 * var) - var.ln()
}

fn rows(a: Args<'_>, rule: Rule) -> Output {
    let (actions, mu, log_std, dim) = (a.f32s(0), a.f32s(1), a.f32s(2), a.usize(3));
    let n = actions.len() / dim;
    let out = (0..n)
        .map(|i| {
            let dims = match rule.dims {
                Dims::First => 1,
                Dims::Sum | Dims::Mean => dim,
            };
            let mut total = 0.0_f32;
            for (d, &s) in log_std.iter().enumerate().take(dims) {
                let at = if rule.column_major {
                    d * n + i
                } else {
                    i * dim + d
                };
                total += (rule.term)(actions[at] - mu[at], s);
                if let Constant::PerDimension = rule.constant {
                    total -= LOG_SQRT_2PI;
                }
            }
            if let Constant::OncePerRow = rule.constant {
                total -= LOG_SQRT_2PI;
            }
            match rule.dims {
                Dims::Mean => total / dim as f32,
                Dims::Sum | Dims::First => total,
            }
        })
        .collect();
    Output::F32s(out)
}

/// The checks, with their cases (deterministic: seeded).
fn checks() -> Vec<CheckCases> {
    let random = random(16, |g| {
        let n = g.int(1, 30);
        let dim = g.int(1, 6);
        let mu: Vec<f32> = (0..n * dim).map(|_| 2.0 * g.f(-3.0, 3.0).tanh()).collect();
        let log_std = g.f32s(dim, -3.0, 1.0);
        let actions = (0..n * dim)
            .map(|k| {
                if g.chance(0.3) {
                    g.f(-3.0, 3.0)
                } else {
                    mu[k] + log_std[k % dim].exp() * g.f(-3.0, 3.0)
                }
            })
            .collect();
        case(actions, mu, log_std, dim)
    });
    let one_dim = vec![
        case(vec![0.5], vec![0.0], vec![0.0], 1),
        case(vec![-1.2, 0.4, 2.7], vec![-1.2, 0.1, 1.9], vec![-1.2], 1),
        case(
            vec![0.3, -1.7, 2.0, 0.0],
            vec![0.1, -0.2, 1.9, 1.0],
            vec![0.7],
            1,
        ),
    ];
    let initial = vec![case(
        vec![0.5, -1.0, 0.2, 1.5, -0.3, 0.0],
        vec![0.0, 0.0, 0.1, 1.0, -0.5, 0.2],
        vec![0.0, 0.0, 0.0],
        3,
    )];
    let one_row = vec![case(
        vec![0.9, -0.4, 1.1, -2.2, 0.05, 1.7],
        vec![1.0, -0.5, 0.8, -1.9, 0.0, 1.9],
        vec![-0.5, 0.3, -1.2, 0.8, -2.5, 0.1],
        6,
    )];
    let far = vec![case(
        vec![6.0, -4.0, -2.0, 9.5, 0.3, -7.0],
        vec![-2.0, 2.0, 1.5, 0.0, 0.3, 1.0],
        vec![-2.0, 0.5],
        2,
    )];
    let empty = vec![case(Vec::new(), Vec::new(), vec![0.1, -0.7, 0.0], 3)];
    vec![
        random,
        check(
            Text::new("dim = 1: the one-dimensional density", "dim = 1：一维密度"),
            one_dim,
        ),
        check(
            Text::new(
                "log σ = 0 in every dimension (CleanRL's initial policy)",
                "每个维度 log σ = 0（CleanRL 的初始策略）",
            ),
            initial,
        ),
        check(
            Text::new("a single row of six dimensions", "只有一行，六个维度"),
            one_row,
        ),
        check(
            Text::new("actions many σ from μ", "离 μ 有许多个 σ 的动作"),
            far,
        ),
        check(
            Text::new(
                "PyTorch's Normal.log_prob, recorded: each case one row of its dimensions",
                "录制的 PyTorch Normal.log_prob：每个用例是一行，含其各个维度",
            ),
            torch_cases(),
        ),
        check(Text::new("no rows", "没有行"), empty),
    ]
}

fn case(actions: Vec<f32>, mu: Vec<f32>, log_std: Vec<f32>, dim: usize) -> Vec<Arg> {
    vec![
        Arg::F32s(actions),
        Arg::F32s(mu),
        Arg::F32s(log_std),
        Arg::Usize(dim),
    ]
}

/// The fixture's cases: `(mu, std, actions, PyTorch's log_prob)`, one value per entry.
fn torch_rows() -> Vec<[Vec<f32>; 4]> {
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
            Some([
                floats(&c["mu"])?,
                floats(&c["std"])?,
                floats(&c["actions"])?,
                floats(&c["log_prob"])?,
            ])
        })
        .collect()
}

/// Each recorded case as one row of `K` dimensions (`K` its length), `log σ = ln(std)`.
fn torch_cases() -> Vec<Vec<Arg>> {
    torch_rows()
        .into_iter()
        .map(|[mu, std, actions, _]| {
            let dim = mu.len();
            let log_std = std.iter().map(|s| s.ln()).collect();
            case(actions, mu, log_std, dim)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ppo::continuous::normal_log_prob;

    /// Provenance: `tests/fixtures/gaussian_log_prob_pytorch.json`, made by
    /// `tests/fixtures/gaussian_log_prob_pytorch.py` (torch 2.15.0, CPU, float32): 9 cases,
    /// 298 one-dimensional log-densities. Read as one row of `K` dimensions per case, the
    /// reference agrees with the sum of PyTorch's values (CleanRL's `.sum(1)`) within the
    /// exercise's tolerance: `log σ` is given as `ln(std)` in f32, and the sums differ in
    /// the order of their f32 additions.
    #[test]
    fn the_reference_equals_pytorchs_sum() {
        let rows = torch_rows();
        assert_eq!(rows.len(), 9, "the PyTorch fixture is embedded");
        for ([mu, std, actions, want], args) in rows.iter().zip(torch_cases()) {
            let a = Args(&args);
            let got = sol::continuous::diag_gaussian_log_prob(
                a.f32s(0),
                a.f32s(1),
                a.f32s(2),
                a.usize(3),
            );
            let want: f64 = want.iter().map(|&w| f64::from(w)).sum();
            assert_eq!(got.len(), 1);
            let tol = EXERCISE.tolerance;
            assert!(
                (f64::from(got[0]) - want).abs() <= tol.abs + tol.rel * want.abs(),
                "{} dims (mu {mu:?}, std {std:?}, actions {actions:?}): got {}, PyTorch {want}",
                mu.len(),
                got[0]
            );
        }
    }

    /// On every case, each row is the sum over its dimensions of the crate's 1-D
    /// `normal_log_prob` with σ = exp(log σ), and with `dim = 1` each row is that density.
    #[test]
    fn the_reference_sums_the_crates_one_dimensional_density() {
        let tol = EXERCISE.tolerance;
        for check in checks() {
            for args in &check.cases {
                let a = Args(args);
                let (actions, mu, log_std, dim) = (a.f32s(0), a.f32s(1), a.f32s(2), a.usize(3));
                let got = sol::continuous::diag_gaussian_log_prob(actions, mu, log_std, dim);
                assert_eq!(got.len(), actions.len() / dim);
                for (i, &g) in got.iter().enumerate() {
                    let want: f32 = (0..dim)
                        .map(|d| {
                            let k = i * dim + d;
                            normal_log_prob(actions[k], mu[k], log_std[d].exp())
                        })
                        .sum();
                    let (g, w) = (f64::from(g), f64::from(want));
                    assert!(
                        (g - w).abs() <= tol.abs + tol.rel * w.abs(),
                        "{}: row {i}",
                        check.name
                    );
                }
            }
        }
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

    /// The right rule of the mistakes' engine is the reference.
    #[test]
    fn the_right_rule_is_the_reference() {
        for c in checks().into_iter().flat_map(|c| c.cases) {
            let (r, m) = ((EXERCISE.reference)(Args(&c)), rows(Args(&c), Rule::RIGHT));
            assert!(m.differs(&r, EXERCISE.tolerance).is_none());
        }
    }
}
