//! `zero_gradient_rows` (lesson 11): which rows of dual-clip PPO's objective (Ye et al.
//! 2020) have a zero gradient with respect to the ratio. It applies the idea of the clip (a
//! row stops learning where the term the objective picks is flat in r) to an objective the
//! lesson does not show: for Â < 0 the term is `max(min(r·Â, clip(r)·Â), c·Â)`, for Â ≥ 0
//! PPO's usual `min(r·Â, clip(r)·Â)`. Its signature, reference, typical mistakes and cases;
//! the hints that name the mistakes are in the lesson's `exercise.toml`.

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
        ("c", Kind::F32),
    ],
    output: OutKind::Bools,
    tolerance: F32_TOL,
    reference: |a| {
        Output::Bools(sol::clipping::zero_gradient_rows(
            a.f32s(0),
            a.f32s(1),
            a.f32(2),
            a.f32(3),
        ))
    },
    mistakes: &[
        Mistake {
            id: "dual_clip_ignored",
            answer: |a| {
                rows(a, |r, adv, b| {
                    adv == 0.0 || (adv > 0.0 && r > b.hi) || (adv < 0.0 && r < b.lo)
                })
            },
        },
        Mistake {
            id: "dual_clip_on_positive",
            answer: |a| rows(a, |r, adv, b| adv >= 0.0 || r < b.lo || r > b.c),
        },
        Mistake {
            id: "tie_at_c_flat",
            answer: |a| {
                rows(a, |r, adv, b| {
                    adv == 0.0 || (adv > 0.0 && r > b.hi) || (adv < 0.0 && (r < b.lo || r >= b.c))
                })
            },
        },
        Mistake {
            id: "c_as_distance_from_one",
            answer: |a| {
                rows(a, |r, adv, b| {
                    adv == 0.0
                        || (adv > 0.0 && r > b.hi)
                        || (adv < 0.0 && (r < b.lo || r > 1.0 + b.c))
                })
            },
        },
        Mistake {
            id: "sides_swapped",
            answer: |a| {
                rows(a, |r, adv, b| {
                    adv == 0.0 || (adv > 0.0 && r < b.lo) || (adv < 0.0 && r > b.hi)
                })
            },
        },
        Mistake {
            id: "inverted",
            answer: |a| {
                rows(a, |r, adv, b| {
                    !(adv == 0.0 || (adv > 0.0 && r > b.hi) || (adv < 0.0 && (r < b.lo || r > b.c)))
                })
            },
        },
    ],
    checks,
};

/// The signature of `zero_gradient_rows`.
pub type Signature = fn(&[f32], &[f32], f32, f32) -> Vec<bool>;

/// Grades a `zero_gradient_rows` running in this process (a notebook cell): the cases,
/// diagnosis and hints of `ppo-tutor grade zero_gradient_rows`.
#[must_use]
pub fn in_place(f: Signature) -> crate::Report {
    EXERCISE.grade_in_place(std::sync::Arc::new(move |a: Args<'_>| {
        Output::Bools(f(a.f32s(0), a.f32s(1), a.f32(2), a.f32(3)))
    }))
}

/// A case's bounds: the band's `1 − ε` and `1 + ε` (in f32) and the dual clip's `c`.
#[derive(Clone, Copy)]
struct Bounds {
    lo: f32,
    hi: f32,
    c: f32,
}

/// Row by row `f(r, Â, bounds)`.
fn rows(a: Args<'_>, f: impl Fn(f32, f32, Bounds) -> bool) -> Output {
    let eps = a.f32(2);
    let b = Bounds {
        lo: 1.0 - eps,
        hi: 1.0 + eps,
        c: a.f32(3),
    };
    Output::Bools(
        a.f32s(0)
            .iter()
            .zip(a.f32s(1))
            .map(|(&r, &adv)| f(r, adv, b))
            .collect(),
    )
}

/// The checks, with their cases (deterministic: seeded). Every case has c > 1 + ε, as the
/// starter promises.
fn checks() -> Vec<CheckCases> {
    let random = random(14, |g| {
        let n = g.int(1, 40);
        // Ratios exactly on 1 ± ε and on c only where 1 ± ε, c, r − 1 and 1 − r are exact in
        // f32 and f64 (ε and c multiples of 1/8), so that every strict way of writing the
        // tests (r > 1 + ε, r − 1 > ε, r·Â < c·Â, in f32 or f64) gives the same answer.
        let on_edges = g.chance(0.4);
        let (eps, c) = if on_edges {
            (
                [0.125, 0.25, 0.375][g.int(0, 2)],
                [1.5, 2.0, 2.5, 3.0][g.int(0, 3)],
            )
        } else if g.chance(0.6) {
            (0.2, 3.0)
        } else {
            (g.f(0.05, 0.4), g.f(1.5, 4.0))
        };
        let ratio = (0..n)
            .map(|_| match g.int(0, 9) {
                0 if on_edges => 1.0 - eps,
                1 if on_edges => 1.0 + eps,
                2 if on_edges => c,
                // About the band, and out to twice c (past 1 + c too).
                k if k < 6 => g.f(0.4, 1.7),
                _ => g.f(1.0, 2.0 * c + 1.0),
            })
            .collect();
        let advantage = (0..n)
            .map(|_| if g.chance(0.1) { 0.0 } else { g.f(-3.0, 3.0) })
            .collect();
        case(ratio, advantage, eps, c)
    });
    // The recorded batches' ratios stay near the band, far below the paper's c = 3.
    let recorded = fixture(|b| {
        b.epochs
            .iter()
            .map(|(_, ratio)| case(ratio.clone(), b.advantage.clone(), b.config.eps as f32, 3.0))
            .collect()
    });
    let (eps, c) = (0.2_f32, 3.0_f32);
    let sides = vec![
        case(vec![0.5, 1.0, 1.5, 3.5, 4.5], vec![2.0; 5], eps, c),
        case(vec![0.5, 1.0, 1.5, 3.5, 4.5], vec![-2.0; 5], eps, c),
    ];
    let zero_advantage = vec![case(vec![1.0, 1.5, 0.5, 3.5], vec![0.0; 4], eps, c)];
    // At ε = 0.25 and c = 3 the edges are exact whichever way the test is written (at 0.2,
    // 1 + ε rounds to 1.2000000477 and (1 + ε) − 1 > ε).
    let exact = 0.25_f32;
    let band_edges = vec![case(
        vec![1.0 + exact, 1.0 - exact, 1.0 + exact, 1.0 - exact],
        vec![1.0, -1.0, -1.0, 1.0],
        exact,
        c,
    )];
    let at_c = vec![
        case(
            vec![3.0, 3.0, 2.875, 3.125],
            vec![-1.0, 1.0, -1.0, -1.0],
            exact,
            c,
        ),
        case(vec![2.0], vec![-0.5], exact, 2.0),
    ];
    vec![
        random,
        recorded,
        check(
            Text::new(
                "each side of the band and of c, each sign",
                "区间两侧和 c 两侧，正负都有",
            ),
            sides,
        ),
        check(Text::new("a zero advantage", "优势值为 0"), zero_advantage),
        check(
            Text::new("ratios exactly at 1 ± ε", "比率恰好等于 1 ± ε"),
            band_edges,
        ),
        check(Text::new("ratios exactly at c", "比率恰好等于 c"), at_c),
    ]
}

fn case(ratio: Vec<f32>, advantage: Vec<f32>, eps: f32, c: f32) -> Vec<Arg> {
    vec![
        Arg::F32s(ratio),
        Arg::F32s(advantage),
        Arg::F32(eps),
        Arg::F32(c),
    ]
}

#[cfg(test)]
mod tests {
    use candle_core::{Device, Tensor, Var};

    use super::*;

    /// The reference agrees with candle's autograd of dual-clip PPO's objective, row by row,
    /// on every case (candle's `clamp`, `minimum` and `maximum` follow PyTorch here: the
    /// gradient passes at the clamp's bounds, a tie passes half to each side). Rows with
    /// Â ≥ 0 get the bound −∞, which the maximum never picks.
    #[test]
    fn the_reference_agrees_with_autograd() -> candle_core::Result<()> {
        for c in checks().into_iter().flat_map(|c| c.cases) {
            let a = Args(&c);
            let (ratio, adv, eps, dual) = (a.f32s(0), a.f32s(1), a.f32(2), a.f32(3));
            assert!(dual > 1.0 + eps, "a case with c ≤ 1 + ε: {eps} {dual}");
            let n = ratio.len();
            let r = Var::from_slice(ratio, n, &Device::Cpu)?;
            let adv_t = Tensor::from_slice(adv, n, &Device::Cpu)?;
            let bound: Vec<f32> = adv
                .iter()
                .map(|&x| if x < 0.0 { dual * x } else { f32::NEG_INFINITY })
                .collect();
            let bound = Tensor::from_slice(&bound, n, &Device::Cpu)?;
            let eps = f64::from(eps);
            let surr1 = r.as_tensor().mul(&adv_t)?;
            let surr2 = r.as_tensor().clamp(1.0 - eps, 1.0 + eps)?.mul(&adv_t)?;
            let objective = surr1.minimum(&surr2)?.maximum(&bound)?.sum_all()?;
            let grads = objective.backward()?;
            let grad: Vec<f32> = grads
                .get(r.as_tensor())
                .map_or_else(|| Ok(vec![0.0; n]), |g| g.to_vec1())?;
            let zero: Vec<bool> = grad.iter().map(|&g| g == 0.0).collect();
            assert_eq!(
                Output::Bools(zero),
                (EXERCISE.reference)(a),
                "ratio {ratio:?} advantage {adv:?} eps {eps} c {dual}"
            );
        }
        Ok(())
    }
}
