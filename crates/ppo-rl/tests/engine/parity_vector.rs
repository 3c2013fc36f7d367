//! The vector CartPole against Gymnasium's `SyncVectorEnv`, bit for bit, in both autoreset
//! modes.
//!
//! Reference data: `tests/fixtures/cartpole_vector_same_step_gymnasium.json` (gymnasium
//! 0.29.1, what CleanRL pins) and `cartpole_vector_next_step_gymnasium.json` (Gymnasium
//! 1.x's default), recorded by `shared/peer/vector_traces.py`: 4 CartPole-v1 environments,
//! `reset(seed=S)` for S = 0 and 1, then 1200 recorded steps each.

use ppo_rl::env::{
    Autoreset, CartPole, CartPoleConfig, CartPoleVec, EnvId, SyncVectorEnv, VecStep, VectorEnv,
};
use serde::Deserialize;

type TestResult = Result<(), Box<dyn std::error::Error>>;

#[derive(Debug, Deserialize)]
struct Fixture {
    traces: Vec<Trace>,
}

#[derive(Debug, Deserialize)]
struct Trace {
    seed: u64,
    num_envs: usize,
    autoreset: Autoreset,
    reset_obs: Vec<[f64; 4]>,
    actions: Vec<Vec<usize>>,
    obs: Vec<Vec<[f64; 4]>>,
    rewards: Vec<Vec<f64>>,
    terminated: Vec<Vec<bool>>,
    truncated: Vec<Vec<bool>>,
    final_obs: Vec<FinalObs>,
}

#[derive(Debug, Deserialize)]
struct FinalObs {
    step: usize,
    env: usize,
    obs: [f64; 4],
}

fn fixture(mode: &str) -> Result<Fixture, Box<dyn std::error::Error>> {
    let path = format!(
        "{}/../../tests/fixtures/cartpole_vector_{mode}_gymnasium.json",
        env!("CARGO_MANIFEST_DIR")
    );
    Ok(serde_json::from_str(&std::fs::read_to_string(path)?)?)
}

/// Gymnasium's float32 observation, read back from the JSON's float64.
fn f32s(v: &[f64; 4]) -> [f32; 4] {
    v.map(|x| x as f32)
}

fn assert_obs(what: &str, got: &[f32; 4], want: &[f64; 4]) {
    let want = f32s(want);
    assert_eq!(
        got.map(f32::to_bits),
        want.map(f32::to_bits),
        "{what}: got {got:?}, Gymnasium {want:?}"
    );
}

/// Plays `trace`'s actions on `envs` and checks every number of every step.
fn check(envs: &mut impl VectorEnv<Obs = [f32; 4], Action = usize>, trace: &Trace) {
    let name = format!("{} seed {}", trace.autoreset, trace.seed);
    assert_eq!(envs.num_envs(), trace.num_envs, "{name}: num_envs");
    assert_eq!(envs.autoreset(), trace.autoreset, "{name}: autoreset");
    let first = envs.reset(Some(trace.seed)).to_vec();
    for (i, (g, w)) in first.iter().zip(&trace.reset_obs).enumerate() {
        assert_obs(&format!("{name} reset env {i}"), g, w);
    }
    let mut finals = Vec::new();
    for (t, actions) in trace.actions.iter().enumerate() {
        let out: VecStep = match envs.step(actions) {
            Ok(out) => out.clone(),
            Err(e) => panic!("{name} step {t}: {e}"),
        };
        for i in 0..trace.num_envs {
            let at = format!("{name} step {t} env {i}");
            assert_obs(&at, &out.obs[i], &trace.obs[t][i]);
            assert_eq!(
                out.rewards[i].to_bits(),
                trace.rewards[t][i].to_bits(),
                "{at} reward"
            );
            assert_eq!(out.terminated[i], trace.terminated[t][i], "{at} terminated");
            assert_eq!(out.truncated[i], trace.truncated[t][i], "{at} truncated");
            if let Some(last) = out.final_obs[i] {
                finals.push((t, i, last));
            }
        }
    }
    assert_eq!(
        finals.len(),
        trace.final_obs.len(),
        "{name}: final observations"
    );
    for ((t, i, got), want) in finals.iter().zip(&trace.final_obs) {
        assert_eq!(
            (*t, *i),
            (want.step, want.env),
            "{name}: where an episode ended"
        );
        assert_obs(
            &format!("{name} final_obs step {t} env {i}"),
            got,
            &want.obs,
        );
    }
}

fn sync(n: usize, autoreset: Autoreset) -> Result<SyncVectorEnv<CartPole>, ppo_rl::env::EnvError> {
    SyncVectorEnv::new(
        (0..n).map(|_| CartPole::new(EnvId::CartPoleV1)).collect(),
        autoreset,
    )
}

#[test]
fn same_step_matches_gymnasium_0_29_bit_for_bit() -> TestResult {
    let fx = fixture("same_step")?;
    assert_eq!(fx.traces.len(), 2);
    // The traces cross ends by both the pole and the time limit.
    let any = |f: fn(&Trace) -> &Vec<Vec<bool>>| {
        fx.traces.iter().any(|t| f(t).iter().flatten().any(|&d| d))
    };
    assert!(any(|t| &t.terminated) && any(|t| &t.truncated));
    for trace in &fx.traces {
        assert_eq!(trace.autoreset, Autoreset::SameStep);
        check(&mut sync(trace.num_envs, Autoreset::SameStep)?, trace);
        let config = CartPoleConfig::new(EnvId::CartPoleV1);
        check(&mut CartPoleVec::new(config, trace.num_envs, 0), trace);
    }
    Ok(())
}

#[test]
fn next_step_matches_gymnasium_1_bit_for_bit() -> TestResult {
    let fx = fixture("next_step")?;
    assert_eq!(fx.traces.len(), 2);
    for trace in &fx.traces {
        assert_eq!(trace.autoreset, Autoreset::NextStep);
        assert!(
            trace.final_obs.is_empty(),
            "next-step keeps no final observations"
        );
        // Reset steps: reward 0 where an episode ended on the step before.
        let resets = trace
            .rewards
            .iter()
            .flatten()
            .filter(|&&r| r == 0.0)
            .count();
        assert!(resets > 0, "the trace crosses autoresets");
        check(&mut sync(trace.num_envs, Autoreset::NextStep)?, trace);
    }
    Ok(())
}
