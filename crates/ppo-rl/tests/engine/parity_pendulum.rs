//! The native Pendulum-v1 against Gymnasium 1.4.0, bit for bit.
//!
//! Reference data: `tests/fixtures/pendulum_gymnasium.json`, recorded from Gymnasium
//! 1.4.0 `Pendulum-v1` with numpy 2.4.6 by `shared/peer/pendulum_traces.py` (8 traces of
//! 200 steps: random, pump and gauss policies, torques as Python floats, some outside
//! [-2, 2], angles that wrap many times, the speed clip at 8 reached) and
//! `gym_resets.py --env Pendulum-v1` (52 reset seeds, 2^32 and 2^64-1 among them, each
//! with three further unseeded resets).

use ppo_rl::env::pendulum::MAX_EPISODE_STEPS;
use ppo_rl::env::seeding::NumpyRng;
use ppo_rl::env::{Pendulum, PendulumConfig, PendulumTrajectory, PendulumVec};
use serde::Deserialize;

type TestResult = Result<(), Box<dyn std::error::Error>>;

#[derive(Debug, Deserialize)]
struct Fixture {
    traces: Vec<Trace>,
    resets: Vec<ResetCase>,
}

/// A recorded trajectory and the policy that chose its torques.
#[derive(Debug, Deserialize)]
struct Trace {
    policy: String,
    #[serde(flatten)]
    trajectory: PendulumTrajectory,
}

#[derive(Debug, Deserialize)]
struct ResetCase {
    seed: u64,
    state: [f64; 2],
    obs: [f64; 3],
    next_resets: Vec<[f64; 2]>,
}

fn fixture() -> Result<Fixture, Box<dyn std::error::Error>> {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../tests/fixtures/pendulum_gymnasium.json"
    );
    Ok(serde_json::from_str(&std::fs::read_to_string(path)?)?)
}

/// Bitwise equality for f64 slices, with a message naming where they differ.
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

/// f32 observations against the fixture's (f32 values widened to f64 by Python).
fn assert_obs(what: &str, got: &[f32; 3], want: &[f64; 3]) {
    assert_bits(what, &got.map(f64::from), want);
    for (g, w) in got.iter().zip(want) {
        // The fixture's values are f32s: narrowing them loses nothing.
        assert_eq!(g.to_bits(), (*w as f32).to_bits(), "{what}");
    }
}

fn assert_trajectory_eq(label: &str, got: &PendulumTrajectory, want: &PendulumTrajectory) {
    let seed = want.seed;
    let at = |what: &str| format!("{label} seed {seed} {what}");
    assert_bits(&at("reset_state"), &got.reset_state, &want.reset_state);
    assert_bits(&at("reset_obs"), &got.reset_obs, &want.reset_obs);
    assert_bits(&at("actions"), &got.actions, &want.actions);
    assert_eq!(got.states.len(), want.states.len(), "{}", at("length"));
    for (step, (g, w)) in got.states.iter().zip(&want.states).enumerate() {
        assert_bits(&at(&format!("step {step} state")), g, w);
    }
    for (step, (g, w)) in got.obs.iter().zip(&want.obs).enumerate() {
        assert_bits(&at(&format!("step {step} obs")), g, w);
    }
    assert_bits(&at("rewards"), &got.rewards, &want.rewards);
    assert_eq!(got.terminated, want.terminated, "{}", at("terminated"));
    assert_eq!(got.truncated, want.truncated, "{}", at("truncated"));
}

/// The fixture covers what makes Pendulum hard to match: clipped torques, the speed
/// clip, angles far outside [-π, π], and the 200-step truncation.
#[test]
fn the_fixture_covers_the_edge_cases() -> TestResult {
    let fx = fixture()?;
    let traces: Vec<_> = fx.traces.iter().map(|t| &t.trajectory).collect();
    assert!(
        traces
            .iter()
            .any(|t| t.actions.iter().any(|u| u.abs() > 2.0))
    );
    let states = || traces.iter().flat_map(|t| &t.states);
    assert!(states().any(|s| s[1].abs() == 8.0));
    assert!(states().any(|s| s[0].abs() > 20.0));
    for t in &traces {
        assert_eq!(t.actions.len(), MAX_EPISODE_STEPS as usize);
        assert_eq!(t.truncated.last(), Some(&true));
        assert!(t.terminated.iter().all(|&x| !x));
    }
    assert!(fx.resets.iter().any(|r| r.seed > u64::from(u32::MAX)));
    Ok(())
}

#[test]
fn every_trace_matches_gymnasium_bit_for_bit() -> TestResult {
    let fx = fixture()?;
    for trace in &fx.traces {
        let want = &trace.trajectory;
        let got =
            PendulumTrajectory::record(PendulumConfig::default(), want.seed, &want.actions, 0)?;
        assert_trajectory_eq(&trace.policy, &got, want);
    }
    Ok(())
}

/// Step by step through `Pendulum` itself: the f32 observations and the flags.
#[test]
fn every_step_matches_gymnasium() -> TestResult {
    let fx = fixture()?;
    for trace in &fx.traces {
        let want = &trace.trajectory;
        let mut env = Pendulum::new();
        let obs = env.reset(Some(want.seed));
        assert_obs(
            &format!("{} reset obs", trace.policy),
            &obs,
            &want.reset_obs,
        );
        for (i, &torque) in want.actions.iter().enumerate() {
            let what = format!("{} seed {} step {i}", trace.policy, want.seed);
            let step = env.step(torque)?;
            assert_obs(&what, &step.obs, &want.obs[i]);
            assert_eq!(
                step.reward.to_bits(),
                want.rewards[i].to_bits(),
                "{what} reward"
            );
            assert_eq!(step.terminated, want.terminated[i], "{what}");
            assert_eq!(step.truncated, want.truncated[i], "{what}");
            let state = env.state().ok_or("no state")?;
            assert_bits(&what, &state, &want.states[i]);
        }
    }
    Ok(())
}

#[test]
fn every_reset_seed_matches_gymnasium() -> TestResult {
    let fx = fixture()?;
    for case in &fx.resets {
        let mut env = Pendulum::new();
        let obs = env.reset(Some(case.seed));
        let state = env.state().ok_or("no state after reset")?;
        assert_bits(&format!("seed {} state", case.seed), &state, &case.state);
        assert_obs(&format!("seed {} obs", case.seed), &obs, &case.obs);
        assert_eq!(case.next_resets.len(), 3);
        for (k, want) in case.next_resets.iter().enumerate() {
            env.reset(None);
            let state = env.state().ok_or("no state after reset")?;
            assert_bits(
                &format!("seed {} unseeded reset {k}", case.seed),
                &state,
                want,
            );
        }
        // Recording with further resets gives the same states.
        let t = PendulumTrajectory::record(PendulumConfig::default(), case.seed, &[], 3)?;
        assert_bits(
            &format!("seed {} record", case.seed),
            &t.reset_state,
            &case.state,
        );
        for (g, w) in t.next_resets.iter().zip(&case.next_resets) {
            assert_bits(&format!("seed {} record next_resets", case.seed), g, w);
        }
    }
    Ok(())
}

/// One `PendulumVec` environment per trace: the same rewards and observations, and the
/// truncation's automatic reset starts the next episode from the continued generator.
#[test]
fn the_vector_env_matches_gymnasium() -> TestResult {
    let fx = fixture()?;
    let resets = |seed: u64| fx.resets.iter().find(|r| r.seed == seed);
    for trace in &fx.traces {
        let want = &trace.trajectory;
        let mut envs = PendulumVec::new(PendulumConfig::default(), 1, want.seed);
        assert_obs("vec reset", &envs.obs()[0], &want.reset_obs);
        for (i, &torque) in want.actions.iter().enumerate() {
            let what = format!("vec {} seed {} step {i}", trace.policy, want.seed);
            let out = envs.step(&[torque])?;
            assert_eq!(
                out.rewards[0].to_bits(),
                want.rewards[i].to_bits(),
                "{what}"
            );
            assert_eq!(out.truncated[0], want.truncated[i], "{what}");
            assert!(!out.terminated[0]);
            match out.final_obs[0] {
                Some(last) => assert_obs(&what, &last, &want.obs[i]),
                None => {
                    assert_obs(&what, &out.obs[0], &want.obs[i]);
                    let state = envs.state(0).ok_or("no state")?;
                    assert_bits(&what, &state, &want.states[i]);
                }
            }
        }
        if let Some(case) = resets(want.seed) {
            let state = envs.state(0).ok_or("no state")?;
            assert_bits("vec autoreset", &state, &case.next_resets[0]);
        }
    }
    Ok(())
}

/// Environment `i` of a `PendulumVec` equals a `Pendulum` reset with `seed + i`, across
/// two truncations.
#[test]
fn the_vector_env_equals_single_envs() -> TestResult {
    let n = 5;
    let mut envs = PendulumVec::new(PendulumConfig::default(), n, 40);
    let mut singles: Vec<Pendulum> = (0..n as u64)
        .map(|i| {
            let mut env = Pendulum::new();
            env.reset(Some(40 + i));
            env
        })
        .collect();
    let mut rng = NumpyRng::from_seed(1);
    for _ in 0..450 {
        let torques: Vec<f64> = (0..n).map(|_| rng.uniform(-3.0, 3.0)).collect();
        let out = envs.step(&torques)?.clone();
        for (i, env) in singles.iter_mut().enumerate() {
            let step = env.step(torques[i])?;
            assert_eq!(out.rewards[i].to_bits(), step.reward.to_bits());
            assert_eq!(out.truncated[i], step.truncated);
            if step.truncated {
                assert_eq!(out.final_obs[i], Some(step.obs));
                assert_eq!(out.obs[i], env.reset(None));
            } else {
                assert_eq!(out.obs[i], step.obs);
            }
            let (got, want) = (envs.state(i), env.state());
            assert_eq!(
                got.map(|s| s.map(f64::to_bits)),
                want.map(|s| s.map(f64::to_bits))
            );
        }
    }
    assert!(
        envs.step(&[0.0]).is_err(),
        "wrong torque count must be refused"
    );
    Ok(())
}
