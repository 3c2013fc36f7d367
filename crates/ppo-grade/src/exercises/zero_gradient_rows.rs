//! `zero_gradient_rows` (lesson 11): which rows of the clipped surrogate have a zero
//! gradient with respect to the ratio. It tests the idea of the clip, not a formula of the
//! seed. Its signature, reference, typical mistakes and cases; the hints that name the
//! mistakes are in the lesson's `exercise.toml`.

use crate::plain::*;
use crate::solutions as sol;
use crate::value::{Arg, Kind, OutKind, Output};

/// The exercise.
pub const EXERCISE: Plain = Plain {
    name: "zero_gradient_rows",
    lesson: "11-clipping",
    params: &[
        ("ratio", Kind::F32s),
        ("advantage", Kind::F32s),
        ("eps", Kind::F32),
    ],
    output: OutKind::Bools,
    tolerance: F32_TOL,
    reference: |a| {
        Output::Bools(sol::clipping::zero_gradient_rows(
            a.f32s(0),
            a.f32s(1),
            a.f32(2),
        ))
    },
    mistakes: &[
        Mistake {
            id: "zero_advantage_forgotten",
            answer: |a| {
                rows(a, |r, adv, lo, hi| {
                    (adv > 0.0 && r > hi) || (adv < 0.0 && r < lo)
                })
            },
        },
        Mistake {
            id: "sides_swapped",
            answer: |a| {
                rows(a, |r, adv, lo, hi| {
                    adv == 0.0 || (adv > 0.0 && r < lo) || (adv < 0.0 && r > hi)
                })
            },
        },
        Mistake {
            id: "every_clipped_row",
            answer: |a| rows(a, |r, adv, lo, hi| adv == 0.0 || r < lo || r > hi),
        },
        Mistake {
            id: "bounds_included",
            answer: |a| {
                rows(a, |r, adv, lo, hi| {
                    adv == 0.0 || (adv > 0.0 && r >= hi) || (adv < 0.0 && r <= lo)
                })
            },
        },
        Mistake {
            id: "inverted",
            answer: |a| {
                rows(a, |r, adv, lo, hi| {
                    !(adv == 0.0 || (adv > 0.0 && r > hi) || (adv < 0.0 && r < lo))
                })
            },
        },
    ],
    checks,
};

/// The signature of `zero_gradient_rows`.
pub type Signature = fn(&[f32], &[f32], f32) -> Vec<bool>;

/// Grades a `zero_gradient_rows` running in this process (a notebook cell): the cases,
/// diagnosis and hints of `ppo-tutor grade zero_gradient_rows`.
#[must_use]
pub fn in_place(f: Signature) -> crate::Report {
    EXERCISE.grade_in_place(std::sync::Arc::new(move |a: Args<'_>| {
        Output::Bools(f(a.f32s(0), a.f32s(1), a.f32(2)))
    }))
}

/// Row by row `f(r, Â, 1 − ε, 1 + ε)`, the bounds in f32.
fn rows(a: Args<'_>, f: impl Fn(f32, f32, f32, f32) -> bool) -> Output {
    let eps = a.f32(2);
    let (lo, hi) = (1.0 - eps, 1.0 + eps);
    Output::Bools(
        a.f32s(0)
            .iter()
            .zip(a.f32s(1))
            .map(|(&r, &adv)| f(r, adv, lo, hi))
            .collect(),
    )
}

/// The checks, with their cases (deterministic: seeded).
fn checks() -> Vec<CheckCases> {
    let random = random(14, |g| {
        let n = g.int(1, 40);
        // Ratios exactly on the band's edges only where 1 ± ε, r − 1 and 1 − r are exact in
        // f32 and f64 (ε a multiple of 1/8), so that every strict way of writing the test
        // (r > 1 + ε, r − 1 > ε, |r − 1| > ε, in f32 or f64) gives the same answer.
        let on_edges = g.chance(0.4);
        let eps = if on_edges {
            [0.125, 0.25, 0.375][g.int(0, 2)]
        } else if g.chance(0.6) {
            0.2
        } else {
            g.f(0.05, 0.4)
        };
        let ratio = (0..n)
            .map(|_| match g.int(0, 9) {
                0 if on_edges => 1.0 - eps,
                1 if on_edges => 1.0 + eps,
                _ => g.f(0.4, 1.7),
            })
            .collect();
        let advantage = (0..n)
            .map(|_| if g.chance(0.1) { 0.0 } else { g.f(-3.0, 3.0) })
            .collect();
        case(ratio, advantage, eps)
    });
    let recorded = fixture(|b| {
        b.epochs
            .iter()
            .map(|(_, ratio)| case(ratio.clone(), b.advantage.clone(), b.config.eps as f32))
            .collect()
    });
    let eps = 0.2_f32;
    let four_corners = vec![case(
        vec![1.5, 0.5, 1.5, 0.5, 1.0, 1.0],
        vec![2.0, 2.0, -2.0, -2.0, 2.0, -2.0],
        eps,
    )];
    let zero_advantage = vec![case(vec![1.0, 1.5, 0.5], vec![0.0; 3], eps)];
    // At ε = 0.25 the edges are exact whichever way the test is written (at 0.2, 1 + ε
    // rounds to 1.2000000477 and (1 + ε) − 1 > ε).
    let exact = 0.25_f32;
    let bounds = vec![case(
        vec![1.0 + exact, 1.0 - exact, 1.0 + exact, 1.0 - exact],
        vec![1.0, -1.0, -1.0, 1.0],
        exact,
    )];
    vec![
        random,
        recorded,
        check(
            Text::new("each side of the band, each sign", "区间两侧，正负都有"),
            four_corners,
        ),
        check(Text::new("a zero advantage", "优势值为 0"), zero_advantage),
        check(
            Text::new("ratios exactly at 1 ± ε", "比率恰好等于 1 ± ε"),
            bounds,
        ),
    ]
}

fn case(ratio: Vec<f32>, advantage: Vec<f32>, eps: f32) -> Vec<Arg> {
    vec![Arg::F32s(ratio), Arg::F32s(advantage), Arg::F32(eps)]
}

#[cfg(test)]
mod tests {
    use candle_core::{Device, Tensor, Var};

    use super::*;

    /// The reference agrees with candle's autograd of the seed's surrogate, row by row, on
    /// the recorded batches and on the band's edges (candle's `clamp` and `minimum` follow
    /// PyTorch here: the gradient passes at the bounds, a tie passes it on).
    #[test]
    fn the_reference_agrees_with_autograd() -> candle_core::Result<()> {
        let mut all: Vec<Vec<Arg>> = checks().into_iter().flat_map(|c| c.cases).collect();
        all.truncate(130);
        for c in &all {
            let a = Args(c);
            let (ratio, adv, eps) = (a.f32s(0), a.f32s(1), f64::from(a.f32(2)));
            let r = Var::from_slice(ratio, ratio.len(), &Device::Cpu)?;
            let adv_t = Tensor::from_slice(adv, adv.len(), &Device::Cpu)?;
            let surr1 = r.as_tensor().mul(&adv_t)?;
            let surr2 = r.as_tensor().clamp(1.0 - eps, 1.0 + eps)?.mul(&adv_t)?;
            let objective = surr1.minimum(&surr2)?.sum_all()?;
            let grads = objective.backward()?;
            let grad: Vec<f32> = grads
                .get(r.as_tensor())
                .map_or_else(|| Ok(vec![0.0; ratio.len()]), |g| g.to_vec1())?;
            let zero: Vec<bool> = grad.iter().map(|&g| g == 0.0).collect();
            assert_eq!(
                Output::Bools(zero),
                (EXERCISE.reference)(a),
                "ratio {ratio:?} advantage {adv:?} eps {eps}"
            );
        }
        Ok(())
    }
}
