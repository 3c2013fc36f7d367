//! The candle PPO against the seed's PyTorch PPO, number by number.
//!
//! Provenance: `tests/fixtures/ppo_update_pytorch.json` was recorded by
//! `shared/peer/ppo_fixtures.py` (PyTorch 2.15, float32, `torch.set_num_threads(1)`): three
//! cases, each the seed's `update()` on one CartPole-v1 episode from mid-training weights
//! with fresh Adam state. `tests/fixtures/moving_average.json` is `rl_utils.moving_average`
//! in numpy float64, its first input being the 500 returns of one PyTorch run.
//!
//! Tolerances (fair for float32 rounding over these reductions): td_target, td_delta,
//! advantage, old_log_probs, ratio, surr1, surr2 within 1e-5 relative; losses within 1e-4
//! relative; weights after the 10 epochs within 1e-5 absolute; moving average within 1e-12.

use ppo_rl::ppo::moving_average;
use ppo_rl::ppo::replay::{parse_replay, replay_case};
use serde_json::Value;

type TestResult = Result<(), Box<dyn std::error::Error>>;

const PPO_FIXTURE: &str = include_str!("../../../../tests/fixtures/ppo_update_pytorch.json");
const MA_FIXTURE: &str = include_str!("../../../../tests/fixtures/moving_average.json");

/// Flattens nested JSON lists of numbers.
fn flat(v: &Value) -> Vec<f64> {
    match v {
        Value::Array(a) => a.iter().flat_map(flat).collect(),
        Value::Number(n) => vec![n.as_f64().unwrap_or(f64::NAN)],
        _ => vec![f64::NAN],
    }
}

/// Largest relative error `|got - want| / max(|want|, floor)` and its index. The floor (1e-3
/// of the tensor's largest entry) keeps entries that are zero up to rounding, such as surr
/// next to a near-zero advantage, from dividing by ~0.
fn max_rel(got: &[f64], want: &[f64], floor: f64) -> (f64, usize) {
    assert_eq!(got.len(), want.len(), "lengths differ");
    got.iter()
        .zip(want)
        .map(|(g, w)| (g - w).abs() / w.abs().max(floor))
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

/// Largest magnitude in a tensor.
fn scale(v: &Value) -> f64 {
    flat(v).iter().fold(0.0_f64, |m, x| m.max(x.abs()))
}

/// Relative error at most `rtol`, relative to each entry or, for entries smaller than
/// `floor`, to `floor`.
fn check_rel(what: &str, got: &Value, want: &Value, rtol: f64, floor: f64) {
    let (g, w) = (flat(got), flat(want));
    let (err, i) = max_rel(&g, &w, floor);
    eprintln!("{what}: max relative error {err:.2e} (at {i})");
    assert!(
        err <= rtol,
        "{what}[{i}]: got {} want {} (relative error {err:.2e} > {rtol:e})",
        g[i],
        w[i]
    );
}

#[test]
fn every_update_case_matches_pytorch() -> TestResult {
    let fixture: Value = serde_json::from_str(PPO_FIXTURE)?;
    let cases = parse_replay(PPO_FIXTURE, "ppo_update_pytorch.json")?;
    let expected_cases = fixture["cases"].as_array().ok_or("fixture has no cases")?;
    assert_eq!(cases.len(), 3);
    for (k, (case, fixture_case)) in cases.iter().zip(expected_cases).enumerate() {
        let out = serde_json::to_value(replay_case(case)?)?;
        let expected = &fixture_case["expected"];
        for key in ["td_target", "advantage", "old_log_probs"] {
            let floor = 1e-3 * scale(&expected[key]);
            check_rel(
                &format!("case {k} {key}"),
                &out[key],
                &expected[key],
                1e-5,
                floor,
            );
        }
        // td_delta = td_target - V(s) cancels two numbers near 20 to one near 0: its
        // rounding is that of its operands, so it is measured against td_target's scale.
        let floor = scale(&expected["td_target"]);
        check_rel(
            &format!("case {k} td_delta"),
            &out["td_delta"],
            &expected["td_delta"],
            1e-5,
            floor,
        );
        let epochs = expected["epochs"].as_array().ok_or("no epochs")?;
        assert_eq!(out["epochs"].as_array().map(Vec::len), Some(epochs.len()));
        for (e, want) in epochs.iter().enumerate() {
            let got = &out["epochs"][e];
            for key in ["ratio", "surr1", "surr2"] {
                let floor = 1e-3 * scale(&want[key]);
                check_rel(
                    &format!("case {k} epoch {e} {key}"),
                    &got[key],
                    &want[key],
                    1e-5,
                    floor,
                );
            }
            for key in ["actor_loss", "critic_loss"] {
                let (g, w) = (flat(&got[key])[0], flat(&want[key])[0]);
                let err = (g - w).abs() / w.abs();
                eprintln!("case {k} epoch {e} {key}: {g} vs {w}, relative error {err:.2e}");
                assert!(
                    err <= 1e-4,
                    "case {k} epoch {e} {key}: {g} vs {w} ({err:.2e})"
                );
            }
        }
        let want_w = fixture_case["weights_after"]
            .as_object()
            .ok_or("no weights_after")?;
        for (name, want) in want_w {
            let err = max_abs(&flat(&out["weights_after"][name]), &flat(want));
            eprintln!("case {k} weights_after {name}: max abs error {err:.2e}");
            assert!(err <= 1e-5, "case {k} {name}: max abs error {err:.2e}");
        }
    }
    Ok(())
}

#[test]
fn moving_average_matches_numpy() -> TestResult {
    let fixture: Value = serde_json::from_str(MA_FIXTURE)?;
    for case in fixture["cases"].as_array().ok_or("no cases")? {
        let window = case["window"].as_u64().ok_or("no window")? as usize;
        let got = moving_average(&flat(&case["input"]), window)?;
        let want = flat(&case["output"]);
        let err = max_abs(&got, &want);
        assert!(err <= 1e-12, "window {window}: max abs error {err:e}");
    }
    Ok(())
}
