//! The native CartPole against Gymnasium 1.4.0, bit for bit.
//!
//! Reference data: `tests/fixtures/cartpole_gymnasium.json`, recorded from Gymnasium
//! 1.4.0 `CartPole-v1` with numpy 2.4.6 by `shared/peer/gym_traces.py` and
//! `gym_resets.py` (random and "lean" policies, 500-step truncations, 103 reset seeds
//! including seeds of 2^32 and above).

use ppo_rl::env::{CartPole, CartPoleConfig, EnvId, Policy, Trajectory};
use serde::Deserialize;

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
        "/../../tests/fixtures/cartpole_gymnasium.json"
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

#[test]
fn every_trace_matches_gymnasium_bit_for_bit() -> TestResult {
    let fx = fixture()?;
    assert!(fx.traces.iter().any(|t| t.truncated.last() == Some(&true)));
    for want in &fx.traces {
        let got = Trajectory::record(
            CartPoleConfig::new(EnvId::CartPoleV1),
            want.seed,
            &Policy::Actions(want.actions.clone()),
            want.actions.len(),
            0,
        )?;
        assert_trajectory_eq(&got, want);
    }
    Ok(())
}

#[test]
fn every_reset_seed_matches_gymnasium() -> TestResult {
    let fx = fixture()?;
    assert!(fx.resets.iter().any(|r| r.seed > u64::from(u32::MAX)));
    for case in &fx.resets {
        let mut env = CartPole::new(EnvId::CartPoleV1);
        let obs = env.reset(Some(case.seed));
        let state = env.state().ok_or("no state after reset")?;
        assert_bits(&format!("seed {} state", case.seed), &state, &case.state);
        assert_bits(
            &format!("seed {} obs", case.seed),
            &obs.map(f64::from),
            &case.obs,
        );
        for (k, want) in case.next_resets.iter().enumerate() {
            env.reset(None);
            let state = env.state().ok_or("no state after reset")?;
            assert_bits(
                &format!("seed {} unseeded reset {k}", case.seed),
                &state,
                want,
            );
        }
    }
    Ok(())
}
