//! What the plain exercises' cases are made from: a seeded source of inputs, and the
//! recorded PyTorch episodes (`tests/fixtures/ppo_update_pytorch.json`, embedded) replayed
//! by the library's agent.
//!
//! Everything is deterministic: the random batches come from [`NumpyRng`] with fixed seeds,
//! so a failing input is the same on every run and every machine.

use std::sync::OnceLock;

use crate::env::seeding::NumpyRng;
use crate::ppo::replay::parse_replay;
use crate::ppo::{Agent, PpoConfig};

/// The PyTorch fixture: three recorded episodes with the weights before their update.
pub const PPO_FIXTURE: &str = include_str!("../../../tests/fixtures/ppo_update_pytorch.json");

/// A seeded source of test inputs.
pub struct Gen(NumpyRng);

impl Gen {
    /// A generator seeded with `seed`.
    pub fn new(seed: u64) -> Self {
        Self(NumpyRng::from_seed(seed))
    }
    /// Uniform in `[lo, hi)`.
    pub fn f(&mut self, lo: f32, hi: f32) -> f32 {
        self.0.uniform(f64::from(lo), f64::from(hi)) as f32
    }
    /// Uniform in `lo..=hi`.
    pub fn int(&mut self, lo: usize, hi: usize) -> usize {
        lo + (self.0.next_u64() % (hi - lo + 1) as u64) as usize
    }
    /// True with probability `p`.
    pub fn chance(&mut self, p: f64) -> bool {
        self.0.next_f64() < p
    }
    /// `n` uniform numbers in `[lo, hi)`.
    pub fn f32s(&mut self, n: usize, lo: f32, hi: f32) -> Vec<f32> {
        (0..n).map(|_| self.f(lo, hi)).collect()
    }
    /// `n` flags, each true with probability `p`.
    pub fn bools(&mut self, n: usize, p: f64) -> Vec<bool> {
        (0..n).map(|_| self.chance(p)).collect()
    }
}

/// What the grader takes from one recorded PyTorch episode, replayed by the library's agent
/// from the recorded weights.
#[derive(Debug, Clone)]
pub struct FixtureBatch {
    /// `r_t`.
    pub rewards: Vec<f32>,
    /// `done_t`.
    pub dones: Vec<bool>,
    /// `a_t`.
    pub actions: Vec<usize>,
    /// `π(·|s_t)` before the update.
    pub probs: Vec<[f32; 2]>,
    /// `V(s_t)` before the update.
    pub values: Vec<f32>,
    /// `V(s_{t+1})` before the update.
    pub next_values: Vec<f32>,
    /// The TD targets.
    pub td_target: Vec<f32>,
    /// The TD errors.
    pub td_delta: Vec<f32>,
    /// The advantages.
    pub advantage: Vec<f32>,
    /// `log π_old(a_t|s_t)`.
    pub old_log_probs: Vec<f32>,
    /// Per epoch: `log π(a_t|s_t)` and the ratio.
    pub epochs: Vec<(Vec<f32>, Vec<f32>)>,
    /// The run's hyper-parameters.
    pub config: PpoConfig,
}

/// The recorded PyTorch episodes, replayed once per process (empty if the embedded fixture
/// cannot be replayed, which the test suite rules out).
pub fn fixture_batches() -> &'static [FixtureBatch] {
    static BATCHES: OnceLock<Vec<FixtureBatch>> = OnceLock::new();
    BATCHES.get_or_init(|| load_fixture().unwrap_or_default())
}

fn load_fixture() -> Result<Vec<FixtureBatch>, crate::ppo::PpoError> {
    let file = "ppo_update_pytorch.json";
    parse_replay(PPO_FIXTURE, file)?
        .into_iter()
        .map(|case| {
            let mut agent = Agent::from_weights(&case.config, &case.weights_before, 0, file)?;
            let probs = case
                .batch
                .states
                .iter()
                .map(|s| {
                    let p = agent.probs(s);
                    [
                        p.first().copied().unwrap_or(0.5),
                        p.get(1).copied().unwrap_or(0.5),
                    ]
                })
                .collect();
            let trace = agent.update(&case.batch)?;
            Ok(FixtureBatch {
                rewards: case.batch.rewards.clone(),
                dones: trace.dones.clone(),
                actions: case.batch.actions.clone(),
                probs,
                values: trace.values,
                next_values: trace.next_values,
                td_target: trace.td_target,
                td_delta: trace.td_delta,
                advantage: trace.advantage,
                old_log_probs: trace.old_log_probs,
                epochs: trace
                    .epochs
                    .into_iter()
                    .map(|e| (e.log_probs, e.ratio))
                    .collect(),
                config: case.config,
            })
        })
        .collect()
}
