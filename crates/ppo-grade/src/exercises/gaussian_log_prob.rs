//! `gaussian_log_prob` (lesson 16): the log-density of the Gaussian policy at the actions
//! taken, PyTorch's `Normal(mu, std).log_prob(actions)`. Its signature, reference, typical
//! mistakes and cases; the hints that name the mistakes are in the lesson's `exercise.toml`.

use crate::plain::*;
use crate::solutions as sol;
use crate::value::{Arg, Kind, OutKind, Output};
use crate::ppo::continuous::softplus_f32;

/// PyTorch's `Normal.log_prob` on seeded inputs shaped like the book's policy (μ = 2·tanh,
/// σ = softplus), recorded by `tests/fixtures/gaussian_log_prob_pytorch.py`.
const TORCH_FIXTURE: &str = include_str!("../../../../tests/fixtures/gaussian_log_prob_pytorch.json");

/// `log √(2π)` rounded to f32, as the reference subtracts it.
const LOG_SQRT_2PI: f32 = 0.918_938_5;

/// The exercise.
pub const EXERCISE: Plain = Plain {
    name: "gaussian_log_prob",
    lesson: "16-continuous-actions",
    params: &[
        ("mu", Kind::F32s),
        ("std", Kind::F32s),
        ("actions", Kind::F32s),
    ],
    output: OutKind::F32s,
    tolerance: F32_TOL,
    reference: |a| {
        Output::F32s(sol::continuous::gaussian_log_prob(
            a.f32s(0),
            a.f32s(1),
            a.f32s(2),
        ))
    },
    mistakes: &[
        Mistake {
            id: "sigma_as_variance",
            answer: |a| {
                per_row(a, |d, s| {
                    -(d * d) / (2.0 * s) - 0.5 * (2.0 * std::f32::consts::PI * s).ln()
                })
            },
        },
        Mistake {
            id: "no_constant",
            answer: |a| per_row(a, |d, s| -(d * d) / (2.0 * s * s) - s.ln()),
        },
        Mistake {
            id: "density_not_log",
            answer: |a| {
                per_row(a, |d, s| {
                    (-(d * d) / (2.0 * s * s) - s.ln() - LOG_SQRT_2PI).exp()
                })
            },
        },
        Mistake {
            id: "plus_log_std",
            answer: |a| per_row(a, |d, s| -(d * d) / (2.0 * s * s) + s.ln() - LOG_SQRT_2PI),
        },
        Mistake {
            id: "no_half",
            answer: |a| per_row(a, |d, s| -(d * d) / (s * s) - s.ln() - LOG_SQRT_2PI),
        },
        Mistake {
            id: "log_two_pi_not_halved",
            answer: |a| {
                per_row(a, |d, s| {
                    -(d * d) / (2.0 * s * s) - s.ln() - 2.0 * LOG_SQRT_2PI
                })
            },
        },
        Mistake {
            id: "std_not_squared",
            answer: |a| per_row(a, |d, s| -(d * d) / (2.0 * s) - s.ln() - LOG_SQRT_2PI),
        },
    ],
    checks,
};

/// The signature of `gaussian_log_prob`.
pub type Signature = fn(&[f32], &[f32], &[f32]) -> Vec<f32>;

/// Grades a `gaussian_log_prob` running in this process (a notebook cell): the cases,
/// diagnosis and hints of `ppo-tutor grade gaussian_log_prob`.
#[must_use]
pub fn in_place(f: Signature) -> crate::Report {
    EXERCISE.grade_in_place(std::sync::Arc::new(move |a: Args<'_>| {
        Output::F32s(f(a.f32s(0), a.f32s(1), a.f32s(2)))
    }))
}

/// `f(a − μ, σ)` for each row.
fn per_row(a: Args<'_>, f: impl Fn(f32, f32) -> f32) -> Output {
    let rows = a.f32s(0).iter().zip(a.f32s(1)).zip(a.f32s(2));
    Output::F32s(
        rows.map(|((&mu, &std), &action)| f(action - mu, std))
            .collect(),
    )
}

/// The checks, with their cases (deterministic: seeded).
fn checks() -> Vec<CheckCases> {
    let random = random(16, |g| {
        let n = g.int(1, 60);
        let mu: Vec<f32> = (0..n).map(|_| 2.0 * g.f(-3.0, 3.0).tanh()).collect();
        let std: Vec<f32> = (0..n).map(|_| softplus_f32(g.f(-7.0, 3.0))).collect();
        let actions = mu
            .iter()
            .zip(&std)
            .map(|(m, s)| {
                if g.chance(0.3) {
                    g.f(-2.0, 2.0)
                } else {
                    m + s * g.f(-3.0, 3.0)
                }
            })
            .collect();
        case(mu, std, actions)
    });
    let single = vec![
        case(vec![0.0], vec![1.0], vec![0.5]),
        case(vec![-1.2], vec![0.3], vec![-1.2]),
    ];
    let narrow = vec![case(
        vec![0.5, -1.0, 1.9, 0.0],
        vec![1e-3, 2e-3, 1e-3, 1e-3],
        vec![0.5005, -1.0, 1.899, -2.0],
    )];
    let wide = vec![case(
        vec![0.0, 1.5, -2.0],
        vec![3.0, 10.0, 50.0],
        vec![4.0, -20.0, 100.0],
    )];
    let far = vec![case(
        vec![-2.0, 2.0, 0.0, 0.3],
        vec![0.3, 0.5, 1.0, 0.05],
        vec![2.0, -2.0, 6.0, -1.7],
    )];
    let empty = vec![case(Vec::new(), Vec::new(), Vec::new())];
    vec![
        random,
        check("PyTorch's Normal.log_prob (recorded)", torch_cases()),
        check("a single row", single),
        check("σ near 1e-3 (a nearly certain policy)", narrow),
        check("σ large", wide),
        check("actions far from μ", far),
        check("no rows", empty),
    ]
}

fn case(mu: Vec<f32>, std: Vec<f32>, actions: Vec<f32>) -> Vec<Arg> {
    vec![Arg::F32s(mu), Arg::F32s(std), Arg::F32s(actions)]
}

/// The fixture's cases: `(mu, std, actions, PyTorch's log_prob)`.
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

fn torch_cases() -> Vec<Vec<Arg>> {
    torch_rows()
        .into_iter()
        .map(|[mu, std, actions, _]| case(mu, std, actions))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ppo::continuous::{log_prob, normal_log_prob};

    /// Provenance: `tests/fixtures/gaussian_log_prob_pytorch.json`, made by
    /// `tests/fixtures/gaussian_log_prob_pytorch.py` (torch 2.15.0, CPU, float32): 298 rows
    /// in 9 cases. The reference agrees within one float32 ulp of the largest magnitude
    /// among the three terms and the result (`ε·max(|(a − μ)²/(2σ²)|, |log σ|, log √(2π),
    /// |log_prob|)`, ε = 2⁻²³): PyTorch's vectorised `log` rounds `log σ` one ulp away from
    /// Rust's on some rows, and the sum carries that ulp. 288 of the 298 rows are equal bit
    /// for bit.
    #[test]
    fn the_reference_equals_pytorch() {
        let rows = torch_rows();
        assert_eq!(rows.len(), 9, "the PyTorch fixture is embedded");
        let (mut n, mut exact) = (0, 0);
        for [mu, std, actions, want] in &rows {
            let got = sol::continuous::gaussian_log_prob(mu, std, actions);
            assert_eq!(got.len(), want.len());
            for (i, (&g, &w)) in got.iter().zip(want).enumerate() {
                let (m, s, a) = (mu[i], std[i], actions[i]);
                let largest = ((a - m) * (a - m) / (2.0 * s * s))
                    .max(s.ln().abs())
                    .max(LOG_SQRT_2PI)
                    .max(w.abs());
                assert!(
                    (g - w).abs() <= largest * f32::EPSILON,
                    "row {i}: mu {m} std {s} action {a}: got {g}, PyTorch {w}"
                );
                n += 1;
                exact += usize::from(g == w);
            }
        }
        assert_eq!(n, 298);
        eprintln!("{exact} of {n} rows equal to PyTorch's bit for bit");
    }

    /// The reference computes exactly what the crate's Gaussian policy computes:
    /// `ppo::continuous::normal_log_prob` and the candle `log_prob`, bit for bit.
    #[test]
    fn the_reference_equals_the_crates_log_prob() -> candle_core::Result<()> {
        let dev = &candle_core::Device::Cpu;
        let cases = torch_cases();
        for args in cases.iter().chain(&(checks()[0].cases)) {
            let a = Args(args);
            let (mu, std, actions) = (a.f32s(0), a.f32s(1), a.f32s(2));
            let got = sol::continuous::gaussian_log_prob(mu, std, actions);
            for (i, &g) in got.iter().enumerate() {
                assert_eq!(g, normal_log_prob(actions[i], mu[i], std[i]));
            }
            let tensor = |x: &[f32]| candle_core::Tensor::new(x, dev);
            let candle = log_prob(&tensor(actions)?, &tensor(mu)?, &tensor(std)?)?;
            assert_eq!(got, candle.to_vec1::<f32>()?);
        }
        Ok(())
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
