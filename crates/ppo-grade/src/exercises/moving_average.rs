//! `moving_average` (lesson 13): the seed's centred moving average of the returns. Its signature, reference, typical mistakes
//! and cases; the hints that name the mistakes are in the lesson's `exercise.toml`.

use crate::plain::*;
use crate::solutions as sol;
use crate::value::{Arg, Kind, OutKind, Output};

/// numpy's `rl_utils.moving_average` on five series (the first: the seed's 500 returns).
const MA_FIXTURE: &str = include_str!("../../../../tests/fixtures/moving_average.json");

/// The exercise.
pub const EXERCISE: Plain = Plain {
    name: "moving_average",
    lesson: "13-training",
    params: &[("a", Kind::F64s), ("window_size", Kind::Usize)],
    output: OutKind::F64s,
    tolerance: F64_TOL,
    reference: |a| Output::F64s(sol::training::moving_average(a.f64s(0), a.usize(1))),
    mistakes: &[
        Mistake {
            id: "no_edges",
            answer: |a| {
                let (xs, w) = (a.f64s(0), a.usize(1));
                let n = xs.len();
                Output::F64s(
                    (0..(n + 1).saturating_sub(w))
                        .map(|i| xs[i..i + w].iter().sum::<f64>() / w as f64)
                        .collect(),
                )
            },
        },
        Mistake {
            id: "edges_copied",
            answer: |a| {
                let (xs, w) = (a.f64s(0), a.usize(1));
                let n = xs.len();
                let h = w / 2;
                let full = centred(xs, |_, _| h);
                Output::F64s(
                    (0..n)
                        .map(|i| if i < h || i + h >= n { xs[i] } else { full[i] })
                        .collect(),
                )
            },
        },
        Mistake {
            id: "truncated_edges",
            answer: |a| Output::F64s(clipped(a.f64s(0), a.usize(1), |count| count as f64)),
        },
        Mistake {
            id: "edges_divided_by_window",
            answer: |a| {
                let w = a.usize(1);
                Output::F64s(clipped(a.f64s(0), w, |_| w as f64))
            },
        },
        Mistake {
            id: "window_too_wide",
            answer: |a| {
                let w = a.usize(1);
                Output::F64s(centred(a.f64s(0), |_, _| w / 2 + 1))
            },
        },
        Mistake {
            id: "window_too_narrow",
            answer: |a| {
                let w = a.usize(1);
                Output::F64s(centred(a.f64s(0), |_, _| (w / 2).saturating_sub(1)))
            },
        },
        Mistake {
            id: "exclusive_end",
            answer: |a| {
                let (xs, w) = (a.f64s(0), a.usize(1));
                let n = xs.len();
                Output::F64s(
                    (0..n)
                        .map(|i| {
                            let h = (w / 2).min(i).min(n - 1 - i);
                            xs[i - h..i + h].iter().sum::<f64>() / (2 * h + 1) as f64
                        })
                        .collect(),
                )
            },
        },
    ],
    checks,
};

/// Grades a `moving_average` running in this process (a notebook cell): the cases, diagnosis and
/// hints of `ppo-tutor grade moving_average`.
#[must_use]
pub fn in_place(f: fn(&[f64], usize) -> Vec<f64>) -> crate::Report {
    EXERCISE.grade_in_place(std::sync::Arc::new(move |a: Args<'_>| Output::F64s(f(a.f64s(0), a.usize(1)))))
}

/// The mean of `a[i - h ..= i + h]` for each `i`, with `h` from `half(i, n)`.
fn centred(a: &[f64], half: impl Fn(usize, usize) -> usize) -> Vec<f64> {
    let n = a.len();
    (0..n)
        .map(|i| {
            let h = half(i, n).min(i).min(n - 1 - i);
            a[i - h..=i + h].iter().sum::<f64>() / (2 * h + 1) as f64
        })
        .collect()
}

fn clipped(a: &[f64], w: usize, div: impl Fn(usize) -> f64) -> Vec<f64> {
    let n = a.len();
    let h = w / 2;
    (0..n)
        .map(|i| {
            let (lo, hi) = (i.saturating_sub(h), (i + h).min(n - 1));
            a[lo..=hi].iter().sum::<f64>() / div(hi - lo + 1)
        })
        .collect()
}

/// The checks, with their cases (deterministic: seeded).
fn checks() -> Vec<CheckCases> {
    let random = random(13, |g| {
        let n = g.int(1, 80);
        let max_half = n.div_ceil(2).min(10);
        let window = 2 * g.int(0, max_half) + 1;
        let window = if window > n + 1 { window - 2 } else { window };
        let a = (0..n).map(|_| f64::from(g.f(0.0, 500.0)).round()).collect();
        ma_case(a, window)
    });
    let numpy = numpy_cases();
    let single = vec![ma_case(vec![42.0], 1)];
    let wide = vec![
        ma_case((1..=8).map(f64::from).collect(), 9),
        ma_case(vec![3.0, 9.0], 3),
        ma_case(vec![10.0, 20.0, 40.0, 80.0], 5),
    ];
    let equal = vec![
        ma_case(vec![1.0, 2.0, 4.0, 8.0, 16.0], 5),
        ma_case((0..9).map(|i| f64::from(i * i)).collect(), 9),
    ];
    vec![
        random,
        check("numpy's rl_utils.moving_average (recorded)", numpy),
        check("a single value", single),
        check("a window larger than the input", wide),
        check("a window as long as the input", equal),
    ]
}

fn ma_case(a: Vec<f64>, window: usize) -> Vec<Arg> {
    vec![Arg::F64s(a), Arg::Usize(window)]
}

fn numpy_cases() -> Vec<Vec<Arg>> {
    let Ok(json) = serde_json::from_str::<serde_json::Value>(MA_FIXTURE) else {
        return Vec::new();
    };
    let cases = json["cases"].as_array().cloned().unwrap_or_default();
    cases
        .iter()
        .filter_map(|c| {
            let window = usize::try_from(c["window"].as_u64()?).ok()?;
            let a = c["input"]
                .as_array()?
                .iter()
                .map(serde_json::Value::as_f64)
                .collect::<Option<Vec<f64>>>()?;
            Some(ma_case(a, window))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The numpy fixture's recorded outputs, in the order of the numpy check.
    fn numpy_outputs() -> Vec<Vec<f64>> {
        let Ok(json) = serde_json::from_str::<serde_json::Value>(MA_FIXTURE) else {
            return Vec::new();
        };
        let cases = json["cases"].as_array().cloned().unwrap_or_default();
        cases
            .iter()
            .filter_map(|c| {
                c["output"]
                    .as_array()?
                    .iter()
                    .map(serde_json::Value::as_f64)
                    .collect()
            })
            .collect()
    }

    /// Provenance: `tests/fixtures/moving_average.json`, numpy's `rl_utils.moving_average`
    /// on five series (the first: the seed's 500 returns).
    #[test]
    fn the_reference_equals_numpy() {
        let numpy = numpy_cases();
        assert_eq!(numpy.len(), 5, "the numpy fixture is embedded");
        for (case, want) in numpy.iter().zip(numpy_outputs()) {
            assert_eq!((EXERCISE.reference)(Args(case)), Output::F64s(want));
        }
    }
}
