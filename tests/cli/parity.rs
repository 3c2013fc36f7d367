//! The command line reproduces the recorded references: `ppo-tutor cartpole --json` every
//! Gymnasium CartPole trace and reset (`tests/fixtures/cartpole_gymnasium.json`), and
//! `ppo-tutor replay` the book's `PPOContinuous` update in the fixture's key names and
//! shapes (`tests/fixtures/ppo_continuous_update_pytorch.json`). The numbers themselves are
//! checked in the RL core's own tests (`cargo test -p ppo-rl`).

use std::process::{Command, Output};

use ppo_tutor::env::Trajectory;
use serde::Deserialize;
use serde_json::Value;

type TestResult = Result<(), Box<dyn std::error::Error>>;

#[derive(Debug, Deserialize)]
struct Fixture {
    traces: Vec<Trajectory>,
    resets: Vec<ResetCase>,
}

#[derive(Debug, Deserialize)]
struct ResetCase {
    seed: u64,
    state: [f64; 4],
    obs: [f64; 4],
    next_resets: Vec<[f64; 4]>,
}

fn fixture() -> Result<Fixture, Box<dyn std::error::Error>> {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/fixtures/cartpole_gymnasium.json"
    );
    Ok(serde_json::from_str(&std::fs::read_to_string(path)?)?)
}

/// Bitwise equality for f64 arrays, with a message naming where they differ.
fn assert_bits(what: &str, got: &[f64], want: &[f64]) {
    assert_eq!(got.len(), want.len(), "{what}: length");
    for (i, (g, w)) in got.iter().zip(want).enumerate() {
        assert_eq!(
            g.to_bits(),
            w.to_bits(),
            "{what}[{i}]: got {g:?}, Gymnasium {w:?}"
        );
    }
}

fn assert_trajectory_eq(got: &Trajectory, want: &Trajectory) {
    let seed = want.seed;
    assert_bits(
        &format!("seed {seed} reset_state"),
        &got.reset_state,
        &want.reset_state,
    );
    assert_bits(
        &format!("seed {seed} reset_obs"),
        &got.reset_obs,
        &want.reset_obs,
    );
    assert_eq!(got.actions, want.actions, "seed {seed} actions");
    assert_eq!(
        got.states.len(),
        want.states.len(),
        "seed {seed}: episode length"
    );
    for (step, (g, w)) in got.states.iter().zip(&want.states).enumerate() {
        assert_bits(&format!("seed {seed} step {step} state"), g, w);
    }
    for (step, (g, w)) in got.obs.iter().zip(&want.obs).enumerate() {
        assert_bits(&format!("seed {seed} step {step} obs"), g, w);
    }
    assert_bits(&format!("seed {seed} rewards"), &got.rewards, &want.rewards);
    assert_eq!(got.terminated, want.terminated, "seed {seed} terminated");
    assert_eq!(got.truncated, want.truncated, "seed {seed} truncated");
}

fn cli_json(args: &[&str]) -> Result<serde_json::Value, Box<dyn std::error::Error>> {
    cli_json_env(args, &[])
}

fn cli_json_env(
    args: &[&str],
    env: &[(&str, &str)],
) -> Result<serde_json::Value, Box<dyn std::error::Error>> {
    let out = Command::new(env!("CARGO_BIN_EXE_ppo-tutor"))
        .args(args)
        .envs(env.iter().copied())
        .output()?;
    assert!(
        out.status.success(),
        "ppo-tutor {args:?} failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    Ok(serde_json::from_slice(&out.stdout)?)
}

#[test]
fn cli_json_reproduces_every_trace() -> TestResult {
    let fx = fixture()?;
    // Both ways of computing sin and cos: inline where this machine allows it, and libm.
    let libm = [("PPO_TUTOR_LIBM_SINCOS", "1")];
    for (want, env) in fx
        .traces
        .iter()
        .flat_map(|t| [(t, &[][..]), (t, &libm[..])])
    {
        let actions: Vec<String> = want.actions.iter().map(ToString::to_string).collect();
        let seed = want.seed.to_string();
        let value = cli_json_env(
            &[
                "cartpole",
                "--seed",
                &seed,
                "--actions",
                &actions.join(","),
                "--json",
            ],
            env,
        )?;
        for key in [
            "reset_state",
            "reset_obs",
            "actions",
            "states",
            "obs",
            "rewards",
            "terminated",
            "truncated",
        ] {
            assert!(value.get(key).is_some(), "--json output lacks '{key}'");
        }
        let got: Trajectory = serde_json::from_value(value)?;
        assert_trajectory_eq(&got, want);
    }
    Ok(())
}

#[test]
fn cli_json_reproduces_resets() -> TestResult {
    let fx = fixture()?;
    // Every tenth seed plus the large ones keeps the number of processes small.
    let cases = fx
        .resets
        .iter()
        .enumerate()
        .filter(|(i, r)| i % 10 == 0 || r.seed > 1000);
    for (_, case) in cases {
        let seed = case.seed.to_string();
        let value = cli_json(&[
            "cartpole",
            "--seed",
            &seed,
            "--actions",
            "",
            "--json",
            "--resets",
            "3",
        ])?;
        let got: Trajectory = serde_json::from_value(value)?;
        assert!(got.actions.is_empty(), "--actions '' must only reset");
        assert_bits(
            &format!("seed {seed} reset_state"),
            &got.reset_state,
            &case.state,
        );
        assert_bits(&format!("seed {seed} reset_obs"), &got.reset_obs, &case.obs);
        assert_eq!(got.next_resets.len(), 3);
        for (g, w) in got.next_resets.iter().zip(&case.next_resets) {
            assert_bits(&format!("seed {seed} next_resets"), g, w);
        }
    }
    Ok(())
}

const FIXTURE_PATH: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/tests/fixtures/ppo_continuous_update_pytorch.json"
);
const FIXTURE: &str = include_str!("../fixtures/ppo_continuous_update_pytorch.json");

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

fn ppo_tutor(args: &[&str]) -> Result<Output, std::io::Error> {
    Command::new(env!("CARGO_BIN_EXE_ppo-tutor"))
        .args(args)
        .output()
}

/// `ppo-tutor replay FILE --json` recognises the continuous fixture by its keys and prints
/// our numbers in its key names and shapes; without `--json`, a table of the losses.
#[test]
fn cli_replay_prints_the_continuous_fixture_schema() -> TestResult {
    let out = ppo_tutor(&["replay", FIXTURE_PATH, "--json"])?;
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let ours: Value = serde_json::from_slice(&out.stdout)?;
    let fixture: Value = serde_json::from_str(FIXTURE)?;
    let cases = ours["cases"].as_array().ok_or("no cases")?;
    let want_cases = fixture["cases"].as_array().ok_or("no cases")?;
    assert_eq!(cases.len(), want_cases.len());
    for (case, want) in cases.iter().zip(want_cases) {
        let expected = &want["expected"];
        let keys: Vec<&String> = expected.as_object().ok_or("no expected")?.keys().collect();
        for key in keys {
            if key == "epochs" {
                continue;
            }
            assert_eq!(shape(&case[key]), shape(&expected[key]), "{key}");
        }
        let epochs = case["epochs"].as_array().ok_or("no epochs")?;
        assert_eq!(epochs.len(), 10);
        let want_epoch = expected["epochs"][0].as_object().ok_or("no epoch")?;
        for (key, want_value) in want_epoch {
            assert_eq!(shape(&epochs[0][key]), shape(want_value), "epochs[0].{key}");
        }
        assert!(epochs[0]["actor_loss"].is_number());
        for (name, want_w) in want["weights_after"].as_object().ok_or("no weights")? {
            assert_eq!(shape(&case["weights_after"][name]), shape(want_w), "{name}");
        }
        // and the numbers are PyTorch's (the parity test above checks them all)
        let got = case["epochs"][9]["critic_loss"].as_f64().ok_or("no loss")?;
        let w = expected["epochs"][9]["critic_loss"]
            .as_f64()
            .ok_or("no loss")?;
        assert!((got - w).abs() <= 1e-4 * w.abs(), "{got} vs {w}");
    }

    let out = ppo_tutor(&["replay", FIXTURE_PATH])?;
    assert!(out.status.success());
    let table = String::from_utf8(out.stdout)?;
    assert!(
        table.contains("case 0: 200 transitions, 10 epochs"),
        "{table}"
    );
    assert!(table.contains("case 1: 200 transitions, 10 epochs"));
    Ok(())
}

/// A malformed continuous file names the key and the expected shape.
#[test]
fn cli_replay_names_a_wrong_shape_in_the_continuous_fixture() -> TestResult {
    let dir = tempfile::tempdir()?;
    let mut fixture: Value = serde_json::from_str(FIXTURE)?;
    fixture["cases"][0]["weights_before"]["actor.fc_std.bias"] = serde_json::json!([0.0, 1.0]);
    let bad = dir.path().join("bad.json");
    std::fs::write(&bad, fixture.to_string())?;
    let out = ppo_tutor(&["replay", bad.to_str().ok_or("non-UTF-8 path")?])?;
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    assert!(
        err.contains("cases[0].weights_before.actor.fc_std.bias") && err.contains("[1]"),
        "{err}"
    );
    Ok(())
}
