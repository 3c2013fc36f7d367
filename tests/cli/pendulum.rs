//! `ppo-tutor pendulum` as a user runs it: both spellings of negative torques, the JSON
//! keys, Gymnasium's numbers through the binary, the table, and bad torques.
//!
//! Reference data: `tests/fixtures/pendulum_gymnasium.json` (Gymnasium 1.4.0
//! `Pendulum-v1`, numpy 2.4.6; see `tests/parity_pendulum.rs`).

use std::process::Output;

use ppo_tutor::env::PendulumTrajectory;
use serde::Deserialize;

type TestResult = Result<(), Box<dyn std::error::Error>>;

#[derive(Debug, Deserialize)]
struct Fixture {
    traces: Vec<PendulumTrajectory>,
}

fn fixture() -> Result<Fixture, Box<dyn std::error::Error>> {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/fixtures/pendulum_gymnasium.json"
    );
    Ok(serde_json::from_str(&std::fs::read_to_string(path)?)?)
}

use crate::common;
use common::english;

fn run(args: &[&str]) -> std::io::Result<Output> {
    run_env(args, &[])
}

fn run_env(args: &[&str], env: &[(&str, &str)]) -> std::io::Result<Output> {
    english().args(args).envs(env.iter().copied()).output()
}

fn json(args: &[&str]) -> Result<serde_json::Value, Box<dyn std::error::Error>> {
    let out = run(args)?;
    assert!(
        out.status.success(),
        "ppo-tutor {args:?} failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    Ok(serde_json::from_slice(&out.stdout)?)
}

fn same_bits(got: &[f64], want: &[f64]) -> bool {
    got.len() == want.len()
        && got
            .iter()
            .zip(want)
            .all(|(g, w)| g.to_bits() == w.to_bits())
}

#[test]
fn json_has_the_cartpole_keys() -> TestResult {
    let v = json(&[
        "pendulum",
        "--seed",
        "7",
        "--actions",
        "0.5,-1",
        "--resets",
        "2",
        "--json",
    ])?;
    for key in [
        "reset_state",
        "reset_obs",
        "actions",
        "states",
        "obs",
        "rewards",
        "terminated",
        "truncated",
        "next_resets",
    ] {
        assert!(v.get(key).is_some(), "--json output lacks '{key}': {v}");
    }
    assert_eq!(v["env"], "Pendulum-v1");
    let t: PendulumTrajectory = serde_json::from_value(v)?;
    assert_eq!(t.seed, 7);
    assert_eq!(t.actions, vec![0.5, -1.0]);
    assert_eq!((t.states.len(), t.obs.len(), t.rewards.len()), (2, 2, 2));
    assert_eq!(t.next_resets.len(), 2);
    Ok(())
}

/// `--actions=-0.5,1.25` and `--actions -0.5,1.25` are the same list.
#[test]
fn negative_torques_work_in_both_spellings() -> TestResult {
    let joined = json(&["pendulum", "--seed", "3", "--actions=-0.5,1.25", "--json"])?;
    let spaced = json(&[
        "pendulum",
        "--seed",
        "3",
        "--actions",
        "-0.5,1.25",
        "--json",
    ])?;
    assert_eq!(joined, spaced);
    let t: PendulumTrajectory = serde_json::from_value(joined)?;
    assert_eq!(t.actions, vec![-0.5, 1.25]);
    // A lone negative torque, and --json after it, still parse.
    let lone = json(&["pendulum", "--actions", "-2", "--json"])?;
    assert_eq!(lone["actions"], serde_json::json!([-2.0]));
    Ok(())
}

/// Every fixture trace through the binary, with the inline sin/cos and with libm.
#[test]
fn json_reproduces_every_trace() -> TestResult {
    let fx = fixture()?;
    let libm = [("PPO_TUTOR_LIBM_SINCOS", "1")];
    for (want, env) in fx
        .traces
        .iter()
        .flat_map(|t| [(t, &[][..]), (t, &libm[..])])
    {
        // Rust's shortest round-trip formatting: parsing gives the same f64 back.
        let torques: Vec<String> = want.actions.iter().map(ToString::to_string).collect();
        let actions = format!("--actions={}", torques.join(","));
        let seed = want.seed.to_string();
        let out = run_env(&["pendulum", "--seed", &seed, &actions, "--json"], env)?;
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let got: PendulumTrajectory = serde_json::from_slice(&out.stdout)?;
        let what = format!("seed {seed} {env:?}");
        assert!(same_bits(&got.actions, &want.actions), "{what} actions");
        assert!(same_bits(&got.reset_state, &want.reset_state), "{what}");
        assert!(same_bits(&got.reset_obs, &want.reset_obs), "{what}");
        assert!(same_bits(&got.rewards, &want.rewards), "{what} rewards");
        assert_eq!(got.states.len(), want.states.len(), "{what}");
        for (i, (g, w)) in got.states.iter().zip(&want.states).enumerate() {
            assert!(same_bits(g, w), "{what} step {i} state {g:?} vs {w:?}");
        }
        for (i, (g, w)) in got.obs.iter().zip(&want.obs).enumerate() {
            assert!(same_bits(g, w), "{what} step {i} obs {g:?} vs {w:?}");
        }
        assert_eq!(got.terminated, want.terminated, "{what}");
        assert_eq!(got.truncated, want.truncated, "{what}");
    }
    Ok(())
}

#[test]
fn torques_past_the_time_limit_are_noted_not_applied() -> TestResult {
    let torques = vec!["0.1"; 205].join(",");
    let out = run(&["pendulum", "--actions", &torques, "--json"])?;
    assert!(out.status.success());
    let t: PendulumTrajectory = serde_json::from_slice(&out.stdout)?;
    assert_eq!(t.actions.len(), 200);
    assert_eq!(t.truncated.last(), Some(&true));
    let err = String::from_utf8(out.stderr)?;
    assert!(err.contains("200 of the 205 torques"), "{err}");
    Ok(())
}

#[test]
fn table_output_is_readable() -> TestResult {
    let out = run(&[
        "pendulum",
        "--seed",
        "0",
        "--actions=-0.5,1.25,3",
        "--resets",
        "1",
    ])?;
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout)?;
    assert!(text.starts_with("Pendulum-v1, reset(seed=0)"), "{text}");
    for column in [
        "torque",
        "theta",
        "cos_theta",
        "sin_theta",
        "theta_dot",
        "reward",
    ] {
        assert!(text.contains(column), "no {column}: {text}");
    }
    // The header, the reset row, three steps, the return line and one next reset.
    assert_eq!(text.lines().count(), 1 + 1 + 1 + 3 + 1 + 1, "{text}");
    assert!(text.contains("  -0.5000"), "{text}");
    assert!(text.contains("over 3 steps"), "{text}");
    assert!(text.contains("next reset 1: ["), "{text}");
    Ok(())
}

/// Each bad torque list gives one line on stderr naming the flag, the bad value and the
/// fix, exit code 2, no panic.
#[test]
fn bad_torques_are_one_line_and_exit_2() -> TestResult {
    let cases: [(&[&str], &[&str]); 6] = [
        (
            &["--actions", "0.5,x"],
            &["--actions", "'x'", "not a number"],
        ),
        (
            &["--actions=1,,2"],
            &["--actions", "torque 2", "not a number"],
        ),
        (
            &["--actions", "NaN"],
            &["--actions", "'NaN'", "not a finite number"],
        ),
        (
            &["--actions=-inf"],
            &["--actions", "'-inf'", "not a finite number"],
        ),
        (
            &["--actions", "1,2,1e999"],
            &["--actions", "'1e999'", "finite"],
        ),
        (&["--seed", "3"], &["--actions", "like --actions=-0.5,1.25"]),
    ];
    for (args, says) in cases {
        let args: Vec<&str> = std::iter::once("pendulum")
            .chain(args.iter().copied())
            .collect();
        let out = run(&args)?;
        let err = String::from_utf8(out.stderr)?;
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(out.stdout.is_empty(), "{args:?} printed output");
        assert_eq!(
            err.trim_end().lines().count(),
            1,
            "{args:?}: not one line: {err}"
        );
        for s in says {
            assert!(err.contains(s), "{args:?}: does not say {s}: {err}");
        }
        if args
            .iter()
            .any(|a| a.contains(',') || a.contains("NaN") || a.contains("inf"))
        {
            assert!(err.contains("like -0.5,1.25"), "{args:?}: no fix: {err}");
        }
        assert!(!err.contains("panicked"), "{args:?}: {err}");
    }
    Ok(())
}
