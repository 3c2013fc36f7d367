//! The candle `PpoContinuous` against the book's PyTorch `PPOContinuous`, number by number.
//!
//! Provenance: `tests/fixtures/ppo_continuous_update_pytorch.json` was recorded by
//! `shared/peer/ppo_continuous_fixtures.py` (PyTorch 2.15, float32,
//! `torch.set_num_threads(1)`): two cases (seeds 0 and 1), each the book's `update()` on one
//! 200-step Pendulum-v1 episode from weights warmed up by 30 episodes of training, with
//! fresh Adam state. `expected` holds every intermediate of that update, `weights_after` the
//! weights after its 10 epochs.
//!
//! Tolerances (fair for float32 rounding over these reductions): every tensor
//! (scaled_rewards, td_target, td_delta, advantage, mu, std, old_log_probs; per epoch
//! log_probs, ratio, surr1, surr2) within 1e-5 relative; the losses within 1e-4 relative;
//! the weights after the update within 1e-5 absolute.
//!
//! "Relative" is entry by entry, against `max(|value|, floor)`. For the values that are
//! sums of larger terms the floor is the size of those terms: td_target (`scaled_r + γV'`),
//! td_delta (`td_target - V`), the advantage (GAE sums the td_delta terms), the log-densities
//! (three terms) and the surrogates (ratio · advantage). A td_target of -0.009, the sum of
//! two terms of size ~1, carries their f32 rounding (2.4e-7 absolute: PyTorch's and
//! candle's matrix products add in different orders), which is 2.7e-5 of the small result;
//! measured against its own value alone, the worst such entry is 6.4e-5 (an advantage of
//! -0.007, 4.5e-7 off). Elsewhere the floor is 1e-3 of the tensor's largest entry, as in
//! `parity_ppo.rs`.

use ppo_rl::ppo::PpoContinuous;
use ppo_rl::ppo::continuous::replay::{parse_continuous_replay, replay_continuous_case};
use serde_json::Value;

type TestResult = Result<(), Box<dyn std::error::Error>>;

const FIXTURE: &str = include_str!("../../../../tests/fixtures/ppo_continuous_update_pytorch.json");

/// Flattens nested JSON lists of numbers.
fn flat(v: &Value) -> Vec<f64> {
    match v {
        Value::Array(a) => a.iter().flat_map(flat).collect(),
        Value::Number(n) => vec![n.as_f64().unwrap_or(f64::NAN)],
        _ => vec![f64::NAN],
    }
}

/// The shape of nested JSON lists (`[]` for a number).
fn shape(v: &Value) -> Vec<usize> {
    match v {
        Value::Array(a) => {
            let mut s = vec![a.len()];
            s.extend(a.first().map(shape).unwrap_or_default());
            s
        }
        _ => vec![],
    }
}

/// Largest magnitude in a tensor.
fn scale(v: &Value) -> f64 {
    flat(v).iter().fold(0.0_f64, |m, x| m.max(x.abs()))
}

/// Largest relative error `|got - want| / max(|want|, floor_i)` and its index.
fn max_rel(got: &[f64], want: &[f64], floors: &[f64]) -> (f64, usize) {
    assert_eq!(got.len(), want.len(), "lengths differ");
    assert_eq!(floors.len(), want.len(), "one floor per entry");
    got.iter()
        .zip(want)
        .zip(floors)
        .map(|((g, w), floor)| (g - w).abs() / w.abs().max(*floor))
        .enumerate()
        .fold((0.0, 0), |best, (i, e)| {
            if e > best.0 || e.is_nan() {
                (e, i)
            } else {
                best
            }
        })
}

fn max_abs(got: &[f64], want: &[f64]) -> f64 {
    assert_eq!(got.len(), want.len(), "lengths differ");
    got.iter()
        .zip(want)
        .map(|(g, w)| (g - w).abs())
        .fold(0.0, f64::max)
}

/// The plain floor: 1e-3 of the tensor's largest entry, for every entry.
fn plain_floor(want: &Value) -> Vec<f64> {
    vec![1e-3 * scale(want); flat(want).len()]
}

/// Per-entry magnitude of the two operands of a sum or difference `c = a ± b`, given `c`
/// and `a`: `|a| + |c - a|`. A result near zero made by cancelling two numbers of size 1
/// carries their rounding (~1e-7), so its error is measured against them, not itself.
fn operand_scale(result: &[f64], first: &[f64]) -> Vec<f64> {
    result
        .iter()
        .zip(first)
        .map(|(c, a)| a.abs() + (c - a).abs())
        .collect()
}

/// The magnitudes GAE adds up: `Σ_l (γλ)^l · scale_{t+l}` within the episode.
fn gae_scale(coef: f64, scales: &[f64]) -> Vec<f64> {
    let mut out = vec![0.0; scales.len()];
    let mut acc = 0.0;
    for (o, s) in out.iter_mut().zip(scales).rev() {
        acc = coef * acc + s;
        *o = acc;
    }
    out
}

/// The three terms of `log N(a; μ, σ)` in magnitude: `(a-μ)²/(2σ²) + |log σ| + log √(2π)`.
fn log_prob_scale(actions: &[f64], mu: &[f64], std: &[f64]) -> Vec<f64> {
    actions
        .iter()
        .zip(mu)
        .zip(std)
        .map(|((a, m), s)| (a - m).powi(2) / (2.0 * s * s) + s.ln().abs() + 0.918_938_533)
        .collect()
}

/// Tensors: relative 1e-5. Losses: relative 1e-4. Weights after the update: absolute 1e-5.
const RTOL: f64 = 1e-5;
const LOSS_RTOL: f64 = 1e-4;
const WEIGHT_ATOL: f64 = 1e-5;

/// Every comparison's error: the largest of each kind, and the ones over their tolerance
/// (all listed when the test fails, not only the first).
#[derive(Default)]
struct Report {
    tensor_rel: f64,
    tensor_abs: f64,
    loss_rel: f64,
    weight_abs: f64,
    failures: Vec<String>,
}

impl Report {
    /// Same shape, and relative error at most [`RTOL`] against `max(|want|, floor)` entry
    /// by entry.
    fn tensor(&mut self, what: &str, got: &Value, want: &Value, floors: &[f64]) {
        assert_eq!(shape(got), shape(want), "{what}: shapes differ");
        let (g, w) = (flat(got), flat(want));
        let (err, i) = max_rel(&g, &w, floors);
        let abs = max_abs(&g, &w);
        eprintln!("{what}: max relative error {err:.2e} (at {i}), max abs error {abs:.2e}");
        if err > RTOL || err.is_nan() {
            self.failures.push(format!(
                "{what}[{i}]: got {} want {} (relative error {err:.2e} > {RTOL:e})",
                g[i], w[i]
            ));
        }
        self.tensor_rel = self.tensor_rel.max(err);
        self.tensor_abs = self.tensor_abs.max(abs);
    }

    /// Relative error at most [`LOSS_RTOL`].
    fn loss(&mut self, what: &str, got: f64, want: f64) {
        let err = (got - want).abs() / want.abs();
        eprintln!("{what}: {got} vs {want}, relative error {err:.2e}");
        if err > LOSS_RTOL || err.is_nan() {
            self.failures
                .push(format!("{what}: {got} vs {want} ({err:.2e})"));
        }
        self.loss_rel = self.loss_rel.max(err);
    }

    /// Same shape, absolute error at most [`WEIGHT_ATOL`].
    fn weight(&mut self, what: &str, got: &Value, want: &Value) -> f64 {
        assert_eq!(shape(got), shape(want), "{what}: shapes differ");
        let err = max_abs(&flat(got), &flat(want));
        if err > WEIGHT_ATOL || err.is_nan() {
            self.failures
                .push(format!("{what}: max abs error {err:.2e}"));
        }
        self.weight_abs = self.weight_abs.max(err);
        err
    }
}

#[test]
fn every_update_case_matches_pytorch() -> TestResult {
    let fixture: Value = serde_json::from_str(FIXTURE)?;
    let cases = parse_continuous_replay(FIXTURE, "ppo_continuous_update_pytorch.json")?;
    let expected_cases = fixture["cases"].as_array().ok_or("fixture has no cases")?;
    assert_eq!(cases.len(), 2);
    assert_eq!(expected_cases.len(), 2);
    let mut report = Report::default();
    for (k, (case, fixture_case)) in cases.iter().zip(expected_cases).enumerate() {
        assert_eq!(case.batch.len(), 200, "a Pendulum episode is 200 steps");
        let out = serde_json::to_value(replay_continuous_case(case)?)?;
        let expected = &fixture_case["expected"];
        let want = |key: &str| flat(&expected[key]);
        let tag = |what: &str| format!("case {k} {what}");

        for key in ["scaled_rewards", "mu", "std"] {
            report.tensor(
                &tag(key),
                &out[key],
                &expected[key],
                &plain_floor(&expected[key]),
            );
        }
        // td_target = scaled_r + γV(s') and td_delta = td_target - V(s) can cancel two
        // numbers of size ~1 into one near 0; GAE sums td_delta; the log-density sums three
        // terms. Each is measured against the size of what it was computed from.
        let td_target_floor = operand_scale(&want("td_target"), &want("scaled_rewards"));
        report.tensor(
            &tag("td_target"),
            &out["td_target"],
            &expected["td_target"],
            &td_target_floor,
        );
        let td_delta_floor = operand_scale(&want("td_delta"), &want("td_target"));
        report.tensor(
            &tag("td_delta"),
            &out["td_delta"],
            &expected["td_delta"],
            &td_delta_floor,
        );
        let coef = case.config.gamma * case.config.lmbda;
        let advantage_floor = gae_scale(coef, &td_delta_floor);
        report.tensor(
            &tag("advantage"),
            &out["advantage"],
            &expected["advantage"],
            &advantage_floor,
        );
        let actions: Vec<f64> = case.batch.actions.iter().map(|&a| f64::from(a)).collect();
        // the policy moves little in 10 epochs (lr 1e-4): μ, σ before the update give the
        // size of every epoch's terms
        let log_prob_floor = log_prob_scale(&actions, &want("mu"), &want("std"));
        let key = "old_log_probs";
        report.tensor(&tag(key), &out[key], &expected[key], &log_prob_floor);

        let epochs = expected["epochs"].as_array().ok_or("no epochs")?;
        assert_eq!(epochs.len(), 10);
        assert_eq!(out["epochs"].as_array().map(Vec::len), Some(epochs.len()));
        for (e, want_epoch) in epochs.iter().enumerate() {
            let got = &out["epochs"][e];
            let ratio = flat(&want_epoch["ratio"]);
            // surr = (clamped) ratio · advantage: the advantage's size times the ratio
            let surr_floor: Vec<f64> = ratio
                .iter()
                .zip(&advantage_floor)
                .map(|(r, a)| r.abs() * a)
                .collect();
            let floors = [
                ("log_probs", log_prob_floor.clone()),
                ("ratio", plain_floor(&want_epoch["ratio"])),
                ("surr1", surr_floor.clone()),
                ("surr2", surr_floor),
            ];
            for (key, floor) in floors {
                report.tensor(
                    &tag(&format!("epoch {e} {key}")),
                    &got[key],
                    &want_epoch[key],
                    &floor,
                );
            }
            for key in ["actor_loss", "critic_loss"] {
                let g = got[key].as_f64().ok_or("loss is not a number")?;
                let w = want_epoch[key]
                    .as_f64()
                    .ok_or("fixture loss is not a number")?;
                report.loss(&format!("case {k} epoch {e} {key}"), g, w);
            }
        }
        // the policy moved: the last epoch's ratio is not all 1
        let last_ratio = flat(&out["epochs"][9]["ratio"]);
        assert!(last_ratio.iter().any(|r| (r - 1.0).abs() > 1e-4));

        let want_w = fixture_case["weights_after"]
            .as_object()
            .ok_or("no weights_after")?;
        assert_eq!(want_w.len(), 10);
        let before = &fixture_case["weights_before"];
        for (name, want) in want_w {
            let what = format!("case {k} weights_after {name}");
            let err = report.weight(&what, &out["weights_after"][name], want);
            let moved = max_abs(&flat(&before[name]), &flat(want));
            eprintln!("{what}: max abs error {err:.2e} (the update moved it {moved:.2e})");
            assert!(moved > 10.0 * err, "{what}: the update did not move it");
        }
    }
    eprintln!(
        "worst: tensors {:.2e} relative ({:.2e} absolute), losses {:.2e} relative, weights {:.2e} absolute",
        report.tensor_rel, report.tensor_abs, report.loss_rel, report.weight_abs
    );
    assert!(report.failures.is_empty(), "{}", report.failures.join("\n"));
    Ok(())
}

/// The agent's own trace (what the lessons display) holds the replayed numbers, and an
/// update from the same weights twice gives the same numbers bit for bit.
#[test]
fn the_trace_is_the_replay_and_deterministic() -> TestResult {
    let cases = parse_continuous_replay(FIXTURE, "ppo_continuous_update_pytorch.json")?;
    let case = &cases[1];
    let run = || -> Result<_, ppo_rl::ppo::PpoError> {
        let mut agent = PpoContinuous::from_weights(&case.config, &case.weights_before, 7, "t")?;
        let trace = agent.update(&case.batch)?;
        Ok((trace, agent.weights()?))
    };
    let (trace, weights) = run()?;
    let (trace2, weights2) = run()?;
    assert_eq!(trace, trace2);
    assert_eq!(weights, weights2);
    let out = replay_continuous_case(case)?;
    let col = |v: &[f32]| v.iter().map(|&x| [x]).collect::<Vec<_>>();
    assert_eq!(out.mu, col(&trace.mu));
    assert_eq!(out.old_log_probs, col(&trace.old_log_probs));
    assert_eq!(out.epochs[3].surr2, col(&trace.epochs[3].surr2));
    assert_eq!(trace.actions, case.batch.actions);
    assert_eq!(trace.values.len(), 200);
    Ok(())
}
