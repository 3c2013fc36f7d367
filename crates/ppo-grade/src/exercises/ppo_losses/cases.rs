//! The inputs `ppo_losses` is graded on, each with the networks they came from, so the
//! gradients of the losses can be carried on to the weights.
//!
//! - the recorded PyTorch episodes (`tests/fixtures/ppo_update_pytorch.json`) at epochs 0,
//!   4 and 9 of the seed's update, the networks replayed to that epoch;
//! - seeded random batches on freshly initialised networks: 1 to 50 steps, ratios spread
//!   over about [0.55, 1.8] (so outside 1 ± ε), advantages of both signs, varied ε;
//! - edge cases: a single step, only negative advantages with every ratio outside the band,
//!   and the first epoch, where every ratio is exactly 1.
//!
//! Everything is deterministic (seeded [`NumpyRng`]), so a failing input is the same on
//! every run.

use candle_core::{DType, Device, Tensor};

use super::protocol::Inputs;
use crate::env::seeding::NumpyRng;
use crate::ppo::replay::parse_replay;
use crate::ppo::{Agent, PolicyNet, PpoConfig, PpoError, Transitions, ValueNet};

/// How many random batches.
pub const RANDOM_CASES: usize = 60;
/// The epochs of the recorded updates graded (0-based).
pub const FIXTURE_EPOCHS: [usize; 3] = [0, 4, 9];

/// One graded input and where it came from.
#[derive(Debug, Clone)]
pub struct Case {
    /// The actor that gave `inputs.probs`.
    pub actor: PolicyNet,
    /// The critic that gave `inputs.values` (and, through `V(s_{t+1})`, `inputs.td_target`).
    pub critic: ValueNet,
    /// `s_t`, `(n, 4)`.
    pub states: Tensor,
    /// `s_{t+1}`, `(n, 4)`.
    pub next_states: Tensor,
    /// `γ·(1 − done_t)`, `(n, 1)`: how `td_target` depends on `V(s_{t+1})`.
    pub bootstrap: Tensor,
    /// What the function is given.
    pub inputs: Inputs,
}

/// The checks' cases, in report order.
#[derive(Debug, Clone)]
pub struct LossesCases {
    /// The recorded PyTorch episodes at [`FIXTURE_EPOCHS`].
    pub fixture: Vec<Case>,
    /// [`RANDOM_CASES`] seeded random batches.
    pub random: Vec<Case>,
    /// Hand-picked edge cases.
    pub edge: Vec<Case>,
}

/// One episode's columns before the networks are applied.
struct Episode<'a> {
    states: &'a [[f32; 4]],
    next_states: &'a [[f32; 4]],
    actions: &'a [usize],
    dones: &'a [bool],
    gamma: f64,
    eps: f64,
}

/// The rest of an epoch's inputs: given, or derived from the networks.
struct Columns {
    /// `old_log_probs[t] = log π(a_t|s_t) + shift[t]` (a zero shift: the first epoch).
    log_prob_shift: Vec<f32>,
    advantage: Vec<f32>,
    /// `None`: `r_t + γ·V(s_{t+1})·(1 − done_t)` with rewards 1, from the critic.
    td_target: Option<Vec<f32>>,
    /// Given old log-probabilities (the fixture's), overriding the shift.
    old_log_probs: Option<Vec<f32>>,
}

fn rows(v: &[[f32; 4]]) -> candle_core::Result<Tensor> {
    let flat: Vec<f32> = v.iter().flatten().copied().collect();
    Tensor::from_vec(flat, (v.len(), 4), &Device::Cpu)
}

fn to_vec(t: &Tensor) -> candle_core::Result<Vec<f32>> {
    t.to_dtype(DType::F32)?.flatten_all()?.to_vec1::<f32>()
}

fn case(agent: &Agent, e: &Episode<'_>, c: Columns) -> candle_core::Result<Case> {
    let n = e.actions.len();
    let dev = &Device::Cpu;
    let (actor, critic) = (agent.actor().clone(), agent.critic().clone());
    let states = rows(e.states)?;
    let next_states = rows(e.next_states)?;
    let not_done: Vec<f32> = e
        .dones
        .iter()
        .map(|&d| if d { 0.0 } else { e.gamma as f32 })
        .collect();
    let bootstrap = Tensor::from_vec(not_done.clone(), (n, 1), dev)?;
    let probs = actor.forward(&states)?;
    let actions: Vec<u32> = e.actions.iter().map(|&a| a as u32).collect();
    let index = Tensor::from_vec(actions.clone(), (n, 1), dev)?;
    let log_probs = to_vec(&probs.gather(&index, 1)?.log()?)?;
    let values = to_vec(&critic.forward(&states)?)?;
    let td_target = match c.td_target {
        Some(t) => t,
        None => {
            let next = to_vec(&critic.forward(&next_states)?)?;
            next.iter()
                .zip(&not_done)
                .map(|(v, k)| 1.0 + k * v)
                .collect()
        }
    };
    let old_log_probs = c.old_log_probs.unwrap_or_else(|| {
        log_probs
            .iter()
            .zip(&c.log_prob_shift)
            .map(|(l, s)| l + s)
            .collect()
    });
    let inputs = Inputs {
        probs: to_vec(&probs)?,
        actions,
        old_log_probs,
        advantage: c.advantage,
        values,
        td_target,
        eps: e.eps,
    };
    Ok(Case {
        actor,
        critic,
        states,
        next_states,
        bootstrap,
        inputs,
    })
}

/// All cases (built in a fraction of a second).
///
/// # Errors
/// Only if the embedded fixture cannot be replayed, which the tests rule out.
pub fn all() -> Result<LossesCases, PpoError> {
    Ok(LossesCases {
        fixture: fixture()?,
        random: (0..RANDOM_CASES)
            .map(|i| random(1000 + i as u64))
            .collect::<Result<_, _>>()?,
        edge: edge()?,
    })
}

/// The recorded PyTorch updates at [`FIXTURE_EPOCHS`].
///
/// # Errors
/// The fixture cannot be replayed.
pub fn fixture() -> Result<Vec<Case>, PpoError> {
    let file = "ppo_update_pytorch.json";
    let mut out = Vec::new();
    for rc in parse_replay(crate::fixture::PPO_FIXTURE, file)? {
        let mut agent = Agent::from_weights(&rc.config, &rc.weights_before, 0, file)?;
        let trace = agent.update(&rc.batch)?;
        for k in FIXTURE_EPOCHS {
            let weights = if k == 0 {
                rc.weights_before.clone()
            } else {
                let config = PpoConfig {
                    epochs: k,
                    ..rc.config.clone()
                };
                let mut replayed = Agent::from_weights(&config, &rc.weights_before, 0, file)?;
                replayed.update(&rc.batch)?;
                replayed.weights()?
            };
            let at_epoch = Agent::from_weights(&rc.config, &weights, 0, file)?;
            let episode = Episode {
                states: &rc.batch.states,
                next_states: &rc.batch.next_states,
                actions: &rc.batch.actions,
                dones: &trace.dones,
                gamma: rc.config.gamma,
                eps: rc.config.eps,
            };
            let columns = Columns {
                log_prob_shift: Vec::new(),
                advantage: trace.advantage.clone(),
                td_target: Some(trace.td_target.clone()),
                old_log_probs: Some(trace.old_log_probs.clone()),
            };
            out.push(case(&at_epoch, &episode, columns)?);
        }
    }
    Ok(out)
}

/// A CartPole-like batch of `n` steps drawn from `g`.
fn draw_batch(g: &mut NumpyRng, n: usize) -> Transitions {
    let state = |g: &mut NumpyRng| {
        [
            g.uniform(-2.4, 2.4) as f32,
            g.uniform(-2.0, 2.0) as f32,
            g.uniform(-0.21, 0.21) as f32,
            g.uniform(-2.0, 2.0) as f32,
        ]
    };
    let mut batch = Transitions::default();
    for t in 0..n {
        let s = state(g);
        let next = state(g);
        let action = (g.next_u64() % 2) as usize;
        let done = if t + 1 == n {
            g.next_f64() < 0.5
        } else {
            g.next_f64() < 0.05
        };
        batch.push(s, action, 1.0, next, done, done);
    }
    batch
}

/// One seeded random batch on networks initialised from `seed`.
///
/// # Errors
/// Only if candle fails.
pub fn random(seed: u64) -> Result<Case, PpoError> {
    let mut g = NumpyRng::from_seed(seed);
    let n = if seed.is_multiple_of(10) {
        1
    } else {
        1 + (g.next_u64() % 50) as usize
    };
    let eps = if g.next_f64() < 0.5 {
        0.2
    } else {
        g.uniform(0.05, 0.4)
    };
    let batch = draw_batch(&mut g, n);
    let shift = (0..n).map(|_| g.uniform(-0.6, 0.6) as f32).collect();
    let advantage = (0..n).map(|_| g.uniform(-3.0, 3.0) as f32).collect();
    let agent = Agent::new(&PpoConfig::default(), seed)?;
    Ok(case(
        &agent,
        &episode(&batch, eps),
        Columns {
            log_prob_shift: shift,
            advantage,
            td_target: None,
            old_log_probs: None,
        },
    )?)
}

fn episode(batch: &Transitions, eps: f64) -> Episode<'_> {
    Episode {
        states: &batch.states,
        next_states: &batch.next_states,
        actions: &batch.actions,
        dones: &batch.dones,
        gamma: 0.98,
        eps,
    }
}

/// A single step (one inside the band, one outside with a negative advantage), only
/// negative advantages with every ratio outside 1 ± ε, and a first epoch (ratios exactly 1).
///
/// # Errors
/// Only if candle fails.
pub fn edge() -> Result<Vec<Case>, PpoError> {
    let agent = Agent::new(&PpoConfig::default(), 7)?;
    let mut g = NumpyRng::from_seed(7);
    let one = draw_batch(&mut g, 1);
    let eight = draw_batch(&mut g, 8);
    let twenty = draw_batch(&mut g, 20);
    let spec = [
        (&one, vec![0.05], vec![1.5]),
        (&one, vec![-0.7], vec![-2.0]),
        (
            &eight,
            vec![0.5, -0.5, 0.4, -0.4, 0.6, -0.6, 0.3, -0.3],
            vec![-1.0, -0.5, -2.0, -0.1, -3.0, -1.5, -0.7, -0.2],
        ),
        (
            &twenty,
            vec![0.0; 20],
            (0..20).map(|t| (t as f32 - 9.5) / 4.0).collect(),
        ),
    ];
    spec.into_iter()
        .map(|(batch, shift, advantage)| {
            let columns = Columns {
                log_prob_shift: shift,
                advantage,
                td_target: None,
                old_log_probs: None,
            };
            Ok(case(&agent, &episode(batch, 0.2), columns)?)
        })
        .collect()
}
