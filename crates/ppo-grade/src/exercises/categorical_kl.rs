//! `categorical_kl` (lesson 10): the exact `KL(π_old(·|s) ‖ π_new(·|s))` of each state,
//! computed from the two policies' logits (what a policy network outputs), with illegal
//! actions masked by a logit of −∞ as games mask them. It applies what the lesson says the
//! divergence is (an expectation under the old policy over every action, never negative, 0
//! only where the two agree, not symmetric, nothing for an action the old policy never
//! takes) where the page did not go: from logits, through a log-softmax that must not
//! overflow on large logits, and with masks on either side (0 for an action the old policy
//! masks, +∞ for one it takes that the new policy masks, PyTorch's convention). Its
//! signature, reference, typical mistakes and cases; the hints that name the mistakes are in
//! the lesson's `exercise.toml`.

use crate::plain::*;
use crate::solutions as sol;
use crate::value::{Arg, Kind, OutKind, Output};

/// PyTorch's `kl_divergence(Categorical(probs=old), Categorical(probs=new))` on seeded
/// softmax rows of 2 to 6 actions, some old rows with exact zeros, recorded by
/// `tests/fixtures/categorical_kl_pytorch.py`; replayed with the logarithms of the
/// probabilities as logits (a zero becomes −∞, a masked action).
const PROBS_FIXTURE: &str = include_str!("../../../../tests/fixtures/categorical_kl_pytorch.json");

/// PyTorch's `kl_divergence(Categorical(logits=old), Categorical(logits=new))` on logits
/// shifted by constants, near 100 and ±1000, and with masks in both, the old and the new
/// policy, recorded by `tests/fixtures/categorical_kl_logits_pytorch.py`.
const LOGITS_FIXTURE: &str =
    include_str!("../../../../tests/fixtures/categorical_kl_logits_pytorch.json");

/// The exercise.
pub const EXERCISE: Plain = Plain {
    name: "categorical_kl",
    lesson: "10-trust-region",
    params: &[
        ("old_logits", Kind::F32s),
        ("new_logits", Kind::F32s),
        ("n_actions", Kind::Usize),
    ],
    output: OutKind::F32s,
    // A row sums up to six terms of either sign, and a right answer may take the
    // log-softmax as `l − max − ln Σ exp(l − max)` or as `l − (max + ln Σ exp(l − max))`,
    // whose rounding near ±1000 is up to 6.1e-5 (float32's spacing there): 1e-5 absolute,
    // 1e-4 relative, with the rows near ±1000 chosen with a KL of at least 0.9. An infinity
    // must be an infinity (`Tolerance` compares infinities exactly). Every mistake is off by
    // far more on some case.
    tolerance: LOSS_TOL,
    reference: |a| call(a, sol::trust_region::categorical_kl),
    mistakes: &[
        Mistake {
            id: "naive_softmax",
            answer: |a| rows(a, naive_softmax_kl),
        },
        Mistake {
            id: "logits_as_log_probs",
            answer: |a| {
                rows(a, |old, new| {
                    let log_p = log_softmax(old);
                    let mut kl = 0.0;
                    for ((&lp, &o), &n) in log_p.iter().zip(old).zip(new) {
                        if o != f32::NEG_INFINITY {
                            kl += lp.exp() * (o - n);
                        }
                    }
                    kl
                })
            },
        },
        Mistake {
            id: "reversed",
            answer: |a| call_swapped(a, sol::trust_region::categorical_kl),
        },
        Mistake {
            id: "old_masked_nan",
            answer: |a| {
                rows(a, |old, new| {
                    let (log_p, log_q) = (log_softmax(old), log_softmax(new));
                    log_p
                        .iter()
                        .zip(&log_q)
                        .map(|(lp, lq)| lp.exp() * (lp - lq))
                        .sum()
                })
            },
        },
        Mistake {
            id: "one_action_only",
            answer: |a| {
                rows(a, |old, new| {
                    let best = old
                        .iter()
                        .enumerate()
                        .fold(0, |best, (i, &l)| if l > old[best] { i } else { best });
                    log_softmax(old)[best] - log_softmax(new)[best]
                })
            },
        },
        Mistake {
            id: "symmetric",
            answer: |a| {
                let k = a.usize(2);
                let forward = sol::trust_region::categorical_kl(a.f32s(0), a.f32s(1), k);
                let backward = sol::trust_region::categorical_kl(a.f32s(1), a.f32s(0), k);
                map2(&forward, &backward, |f, b| 0.5 * (f + b))
            },
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

/// `f` with the old and the new logits swapped.
fn call_swapped(a: Args<'_>, f: Signature) -> Output {
    Output::F32s(f(a.f32s(1), a.f32s(0), a.usize(2)))
}

/// `f(old row, new row)` for each row of the case.
fn rows(a: Args<'_>, f: impl Fn(&[f32], &[f32]) -> f32) -> Output {
    let k = a.usize(2).max(1);
    Output::F32s(
        a.f32s(0)
            .chunks(k)
            .zip(a.f32s(1).chunks(k))
            .map(|(old, new)| f(old, new))
            .collect(),
    )
}

/// The log-softmax of one row, its largest logit subtracted first (the reference's).
fn log_softmax(logits: &[f32]) -> Vec<f32> {
    let max = logits.iter().copied().fold(f32::NEG_INFINITY, f32::max);
    let log_total = logits.iter().map(|&l| (l - max).exp()).sum::<f32>().ln();
    logits.iter().map(|&l| (l - max) - log_total).collect()
}

/// The reference's rules on probabilities taken as `exp(l) / Σ exp(l)`, without the
/// largest logit subtracted: `exp` overflows to ∞ above 88.7 (∞/∞ is NaN) and underflows to
/// 0 below −103 (0/0 is NaN).
fn naive_softmax_kl(old: &[f32], new: &[f32]) -> f32 {
    let softmax = |logits: &[f32]| -> Vec<f32> {
        let total: f32 = logits.iter().map(|l| l.exp()).sum();
        logits.iter().map(|l| l.exp() / total).collect()
    };
    let (p, q) = (softmax(old), softmax(new));
    let mut kl = 0.0;
    for a in 0..old.len() {
        if old[a] == f32::NEG_INFINITY {
            continue;
        }
        if new[a] == f32::NEG_INFINITY {
            return f32::INFINITY;
        }
        kl += p[a] * (p[a].ln() - q[a].ln());
    }
    kl
}

/// −∞, a masked action's logit.
const MASKED: f32 = f32::NEG_INFINITY;

/// A batch of `n` policy-like pairs of rows over `k` actions: old logits of scale up to
/// `scale` plus a constant of the row's own, the new ones moved by up to `spread` plus
/// another constant; a row has, with probability `masked_rows`, the same actions masked in
/// both (never the old policy's favourite).
fn random_case(g: &mut Gen, n: usize, k: usize, masked_rows: f64) -> Vec<Arg> {
    let scale = g.f(0.5, 4.0);
    let spread = g.f(0.05, 1.5);
    let (mut old, mut new) = (Vec::with_capacity(n * k), Vec::with_capacity(n * k));
    for _ in 0..n {
        let (c_old, c_new) = (g.f(-10.0, 10.0), g.f(-10.0, 10.0));
        let moves: Vec<f32> = (0..k).map(|_| g.f(-scale, scale)).collect();
        let mut o: Vec<f32> = moves.iter().map(|m| c_old + m).collect();
        let mut q: Vec<f32> = moves
            .iter()
            .map(|m| c_new + m + g.f(-spread, spread))
            .collect();
        if g.chance(masked_rows) {
            let favourite = o
                .iter()
                .enumerate()
                .fold(0, |best, (a, &l)| if l > o[best] { a } else { best });
            for a in 0..k {
                if a != favourite && g.chance(0.4) {
                    (o[a], q[a]) = (MASKED, MASKED);
                }
            }
        }
        old.extend(o);
        new.extend(q);
    }
    case(old, new, k)
}

/// Rows near 100, every logit in [88, 128): `exp` overflows `f32`, and the spacing of
/// `f32` there (7.6e-6) keeps any log-softmax within 1e-5.
fn near_100(g: &mut Gen) -> Vec<Arg> {
    let (n, k) = (g.int(1, 8), g.int(2, 6));
    let (mut old, mut new) = (Vec::with_capacity(n * k), Vec::with_capacity(n * k));
    for _ in 0..n {
        let (centre, shift) = (g.f(95.0, 118.0), g.f(-3.0, 3.0));
        for _ in 0..k {
            let l = centre + g.f(-3.0, 3.0);
            old.push(l);
            new.push(l + shift + g.f(-1.0, 1.0));
        }
    }
    case(old, new, k)
}

/// The checks, with their cases (deterministic: seeded).
fn checks() -> Vec<CheckCases> {
    let random = random(10, |g| {
        let n = g.int(1, 30);
        let k = g.int(2, 6);
        random_case(g, n, k, 0.3)
    });
    let masks = vec![
        // An action the old policy masks (0 of its own; the new one's 0.5 and 2 set π_new),
        // masks that agree (0), the new policy masking an action the old one takes (+∞),
        // both masking action 0, and an old policy with one action left (ln 3).
        case(
            vec![
                0.0, MASKED, 1.0, 1.0, 0.0, MASKED, 0.0, 0.0, 0.0, MASKED, 2.0, 0.0, MASKED, 3.0,
                MASKED,
            ],
            vec![
                0.5, 2.0, 1.0, 1.0, 0.0, MASKED, 0.0, 0.0, MASKED, MASKED, 0.0, 2.0, 1.0, 1.0, 1.0,
            ],
            3,
        ),
        // +∞ (the new policy masks the old one's only action), and ln(1 + e^−0.25).
        case(
            vec![0.0, MASKED, MASKED, 0.5],
            vec![MASKED, 0.0, 0.25, 0.5],
            2,
        ),
        // The new policy masks an action the old one takes, in every row.
        case(
            vec![1.0, 2.0, 0.5, MASKED, 3.0, -1.0, 0.0, 0.0],
            vec![1.0, MASKED, 0.5, MASKED, MASKED, -1.0, 0.0, 0.0],
            4,
        ),
    ];
    let same = vec![
        case(vec![0.5, -0.25, 3.0, 1.0], vec![0.5, -0.25, 3.0, 1.0], 2),
        case(
            vec![1.0, MASKED, 0.5, 2.0, MASKED, 0.0, MASKED, 3.0],
            vec![1.0, MASKED, 0.5, 2.0, MASKED, 0.0, MASKED, 3.0],
            4,
        ),
        // Logits that differ by 8 and by −100 in every action: the same policies (every
        // value exact in f32, so the differences to the row's largest logit are the same).
        case(
            vec![0.5, -1.25, 2.0, 0.5, -1.25, MASKED],
            vec![8.5, 6.75, 10.0, -99.5, -101.25, MASKED],
            3,
        ),
        case(
            vec![1000.0, 999.0, 998.0, -1000.0, -1000.5, -1003.0],
            vec![1000.0, 999.0, 998.0, -1000.0, -1000.5, -1003.0],
            3,
        ),
    ];
    let mut g = Gen::new(11);
    let mut large = vec![
        // Near 100, near 1000 and near −1000 (KL 1.415, 1.598, 1.112, 0.962).
        case(
            vec![
                100.0, 101.5, 99.0, 1000.0, 998.0, 1001.0, -1000.0, -1003.0, -999.0, -1000.0,
                -1000.5, -1002.0,
            ],
            vec![
                100.5, 100.0, 102.0, 997.0, 1001.0, 999.5, -1001.5, -999.0, -1000.0, -1002.0,
                -999.5, -1000.75,
            ],
            3,
        ),
    ];
    large.extend((0..6).map(|_| near_100(&mut g)));
    let underflow = vec![
        // exp(−900) is 0 in f32 but no action is masked: 900 exactly.
        case(vec![1000.0, 100.0], vec![100.0, 1000.0], 2),
        // The old policy's action 1 and the new policy's action 2 round to 0 (198.956),
        // then the old one's action 1 again, against uniform logits (ln 3).
        case(
            vec![0.0, -200.0, 5.0, 50.0, -60.0, 0.0],
            vec![0.0, 50.0, -150.0, 0.0, 0.0, 0.0],
            3,
        ),
    ];
    let empty = vec![
        case(Vec::new(), Vec::new(), 2),
        case(Vec::new(), Vec::new(), 5),
    ];
    vec![
        random,
        check(
            Text::new(
                "actions masked in the old policy only, in the new policy only, in both",
                "只在旧策略中、只在新策略中、在两者中都屏蔽的动作",
            ),
            masks,
        ),
        check(
            Text::new(
                "rows where the two policies agree, logits shifted by a constant included (0)",
                "两个策略一致的行，包括 logits 相差一个常数的行（为 0）",
            ),
            same,
        ),
        check(
            Text::new(
                "large logits: near 100 and ±1000, where exp overflows f32",
                "很大的 logits：100 与 ±1000 附近，这时 exp 在 f32 中上溢",
            ),
            large,
        ),
        check(
            Text::new(
                "a probability that rounds to 0 in f32, its action not masked (finite)",
                "某个概率在 f32 中舍入为 0、而它的动作并未被屏蔽（结果有限）",
            ),
            underflow,
        ),
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

fn case(old_logits: Vec<f32>, new_logits: Vec<f32>, n_actions: usize) -> Vec<Arg> {
    vec![
        Arg::F32s(old_logits),
        Arg::F32s(new_logits),
        Arg::Usize(n_actions),
    ]
}

/// One recorded case: logits (−∞ for a masked action) and PyTorch's KL of each row.
struct TorchCase {
    old: Vec<f32>,
    new: Vec<f32>,
    n_actions: usize,
    /// PyTorch's KL of each row (the unit test holds the reference to it).
    #[cfg_attr(not(test), allow(dead_code))]
    kl: Vec<f64>,
}

/// The numbers of `v`, `null` read as `none` (JSON has no infinities).
fn numbers(v: &serde_json::Value, none: f64) -> Option<Vec<f64>> {
    v.as_array()?
        .iter()
        .map(|x| if x.is_null() { Some(none) } else { x.as_f64() })
        .collect()
}

/// One case of either fixture: `old` and `new` are the fields holding the two tables,
/// `log` whether they hold probabilities whose logarithms are the logits.
fn torch_case(c: &serde_json::Value, old: &str, new: &str, log: bool) -> Option<TorchCase> {
    let table = |field: &str| -> Option<Vec<f32>> {
        let xs = numbers(&c[field], f64::NEG_INFINITY)?;
        Some(
            xs.iter()
                .map(|&x| if log { (x as f32).ln() } else { x as f32 })
                .collect(),
        )
    };
    Some(TorchCase {
        old: table(old)?,
        new: table(new)?,
        n_actions: usize::try_from(c["n_actions"].as_u64()?).ok()?,
        kl: numbers(&c["kl"], f64::INFINITY)?,
    })
}

/// The cases of `json` (a fixture) read by `read`.
fn fixture_cases(
    json: &str,
    read: impl Fn(&serde_json::Value) -> Option<TorchCase>,
) -> Vec<TorchCase> {
    let Ok(json) = serde_json::from_str::<serde_json::Value>(json) else {
        return Vec::new();
    };
    let cases = json["cases"].as_array().cloned().unwrap_or_default();
    cases.iter().filter_map(read).collect()
}

/// Both fixtures' cases: the probabilities' logarithms, then the logits.
fn torch_rows() -> Vec<TorchCase> {
    let mut rows = fixture_cases(PROBS_FIXTURE, |c| {
        torch_case(c, "old_probs", "new_probs", true)
    });
    rows.extend(fixture_cases(LOGITS_FIXTURE, |c| {
        torch_case(c, "old_logits", "new_logits", false)
    }));
    rows
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

    /// Provenance: `tests/fixtures/categorical_kl_pytorch.json` (made by
    /// `tests/fixtures/categorical_kl_pytorch.py`, torch 2.15.0, CPU, float32: 10 cases, 109
    /// rows of 2 to 6 actions, 26 zero entries in old rows), replayed as logits, and
    /// `tests/fixtures/categorical_kl_logits_pytorch.json` (made by
    /// `tests/fixtures/categorical_kl_logits_pytorch.py`, torch 2.15.0, CPU, float32 logits
    /// and the KL computed from them in float64: 13 cases, 86 rows, 41 masked old logits,
    /// 32 masked new ones, 4 rows of +∞). The reference agrees with PyTorch's
    /// `kl_divergence` on every row within the exercise's tolerance, and is +∞ exactly where
    /// PyTorch's is.
    #[test]
    fn the_reference_equals_pytorchs_kl_divergence() {
        let rows = torch_rows();
        assert_eq!(rows.len(), 23, "both PyTorch fixtures are embedded");
        let tol = EXERCISE.tolerance;
        let (mut rows_seen, mut masked_old, mut masked_new, mut infinite) = (0, 0, 0, 0);
        for TorchCase {
            old,
            new,
            n_actions: k,
            kl: want,
        } in &rows
        {
            masked_old += old.iter().filter(|l| **l == MASKED).count();
            masked_new += new.iter().filter(|l| **l == MASKED).count();
            let got = sol::trust_region::categorical_kl(old, new, *k);
            assert_eq!(got.len(), want.len());
            for (i, (&g, &w)) in got.iter().zip(want).enumerate() {
                rows_seen += 1;
                let g = f64::from(g);
                if w.is_infinite() {
                    infinite += 1;
                    assert_eq!(g, w, "{k} actions, row {i}");
                    continue;
                }
                assert!(
                    (g - w).abs() <= tol.abs + tol.rel * w.abs(),
                    "{k} actions, row {i}: got {g}, PyTorch {w}"
                );
            }
        }
        assert_eq!(rows_seen, 109 + 86);
        assert_eq!((masked_old, masked_new, infinite), (26 + 41, 32, 4));
    }

    /// Provenance: the `underflow` entry of `tests/fixtures/categorical_kl_logits_pytorch.json`.
    /// Where an action that is not masked has a probability that rounds to 0 (old logits
    /// [1000, 100], new [100, 1000]), PyTorch's `kl_divergence` tests `probs == 0` and
    /// returns +∞, in float32 and float64; the exact KL is 900 − 900·e^−900, and the
    /// reference returns 900.
    #[test]
    fn the_reference_is_exact_where_pytorch_says_infinity() {
        let json: serde_json::Value =
            serde_json::from_str(LOGITS_FIXTURE).unwrap_or(serde_json::Value::Null);
        let fact = torch_case(&json["underflow"], "old_logits", "new_logits", false);
        let Some(TorchCase {
            old,
            new,
            kl: torch,
            ..
        }) = fact
        else {
            panic!("the underflow fact is recorded");
        };
        assert_eq!(torch, vec![f64::INFINITY]);
        assert_eq!(json["underflow"]["kl_float32"][0], serde_json::Value::Null);
        assert_eq!(
            sol::trust_region::categorical_kl(&old, &new, 2),
            vec![900.0]
        );
    }

    /// The reference is never negative, exactly 0 where the rows are equal, one value per
    /// row, finite except where the new policy masks an action the old one takes, and +∞
    /// there.
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
                    let forbidden = p.iter().zip(q).any(|(&o, &n)| o > MASKED && n == MASKED);
                    if forbidden {
                        assert_eq!(value, f32::INFINITY, "{}: row {i}", check.name);
                        continue;
                    }
                    assert!(value.is_finite(), "{}: row {i} is {value}", check.name);
                    assert!(value >= -1e-6, "{}: row {i} is {value}", check.name);
                    if p == q {
                        assert_eq!(value, 0.0, "{}: row {i}", check.name);
                    }
                }
            }
        }
    }

    /// The hand-made cases hold the values their comments state, exactly where the comment
    /// says so: 0 for logits shifted by a constant, 900 and +∞.
    #[test]
    fn the_edge_cases_hold_their_stated_values() {
        let kl = |old: &[f32], new: &[f32], k| sol::trust_region::categorical_kl(old, new, k);
        let shifted = kl(
            &[0.5, -1.25, 2.0, 0.5, -1.25, MASKED],
            &[8.5, 6.75, 10.0, -99.5, -101.25, MASKED],
            3,
        );
        assert_eq!(shifted, vec![0.0, 0.0]);
        assert_eq!(kl(&[1000.0, 100.0], &[100.0, 1000.0], 2), vec![900.0]);
        let masks = kl(&[0.0, MASKED, MASKED, 0.5], &[MASKED, 0.0, 0.25, 0.5], 2);
        assert_eq!(masks[0], f32::INFINITY);
        assert!((masks[1] - (1.0 + (-0.25_f32).exp()).ln()).abs() < 1e-6);
    }

    /// Graded in place (a notebook cell), the reference passes and a learner-like answer
    /// that lets an action the old policy masks give NaN is diagnosed as such.
    #[test]
    fn in_place_grading_passes_the_reference_and_names_a_mistake() {
        let report = in_place(sol::trust_region::categorical_kl);
        assert!(report.passed(), "{}", report.render());
        fn unguarded(old: &[f32], new: &[f32], k: usize) -> Vec<f32> {
            let mut out = Vec::new();
            for (o, n) in old.chunks(k).zip(new.chunks(k)) {
                let (lp, lq) = (log_softmax(o), log_softmax(n));
                let mut kl = 0.0;
                for a in 0..k {
                    kl += lp[a].exp() * (lp[a] - lq[a]);
                }
                out.push(kl);
            }
            out
        }
        let report = in_place(unguarded);
        assert!(!report.passed());
        assert_eq!(report.mistake.as_deref(), Some("old_masked_nan"));
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
