//! The inputs each exercise is graded on: seeded random batches, the recorded PyTorch
//! episodes (`tests/fixtures/ppo_update_pytorch.json`, embedded), numpy's moving averages
//! (`tests/fixtures/moving_average.json`, embedded), and hand-picked edge cases.
//!
//! Everything is deterministic: the random batches come from [`NumpyRng`] with fixed seeds,
//! so a failing input is the same on every run and every machine.

use std::sync::OnceLock;

use super::catalog::CheckCases;
use super::value::Arg;
use crate::env::seeding::NumpyRng;
use crate::ppo::replay::parse_replay;
use crate::ppo::{Agent, PpoConfig};

/// The PyTorch fixture: three recorded episodes with the weights before their update.
pub(crate) const PPO_FIXTURE: &str = include_str!("../../tests/fixtures/ppo_update_pytorch.json");
/// numpy's `rl_utils.moving_average` on five series (the first: the seed's 500 returns).
const MA_FIXTURE: &str = include_str!("../../tests/fixtures/moving_average.json");

/// How many random cases each exercise gets.
const RANDOM_CASES: usize = 100;

/// A seeded source of test inputs.
struct Gen(NumpyRng);

impl Gen {
    fn new(seed: u64) -> Self {
        Self(NumpyRng::from_seed(seed))
    }
    fn f(&mut self, lo: f32, hi: f32) -> f32 {
        self.0.uniform(f64::from(lo), f64::from(hi)) as f32
    }
    fn int(&mut self, lo: usize, hi: usize) -> usize {
        lo + (self.0.next_u64() % (hi - lo + 1) as u64) as usize
    }
    fn chance(&mut self, p: f64) -> bool {
        self.0.next_f64() < p
    }
    fn f32s(&mut self, n: usize, lo: f32, hi: f32) -> Vec<f32> {
        (0..n).map(|_| self.f(lo, hi)).collect()
    }
    fn bools(&mut self, n: usize, p: f64) -> Vec<bool> {
        (0..n).map(|_| self.chance(p)).collect()
    }
}

fn check(name: &str, cases: Vec<Vec<Arg>>) -> CheckCases {
    CheckCases {
        name: name.to_string(),
        cases,
    }
}

fn random(seed: u64, mut case: impl FnMut(&mut Gen) -> Vec<Arg>) -> CheckCases {
    let mut g = Gen::new(seed);
    let cases = (0..RANDOM_CASES).map(|_| case(&mut g)).collect();
    check(&format!("{RANDOM_CASES} seeded random inputs"), cases)
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

fn fixture(cases: impl Fn(&FixtureBatch) -> Vec<Vec<Arg>>) -> CheckCases {
    let all = fixture_batches().iter().flat_map(cases).collect();
    check("the recorded PyTorch episodes", all)
}

/// `sample_action`'s checks.
pub fn sample_action() -> Vec<CheckCases> {
    // u is kept away from the cumulative sums, where f32 and f64 sums could disagree.
    fn away_from_edges(g: &mut Gen, probs: &[f32]) -> f32 {
        loop {
            let u = g.f(0.0, 1.0);
            let mut c = 0.0_f32;
            let near = probs.iter().any(|&p| {
                c += p;
                (u - c).abs() < 1e-4
            });
            if !near {
                return u;
            }
        }
    }
    let random = random(6, |g| {
        let n = if g.chance(0.7) { 2 } else { g.int(3, 5) };
        let raw = g.f32s(n, 0.05, 1.0);
        let total: f32 = raw.iter().sum();
        let probs: Vec<f32> = raw.iter().map(|p| p / total).collect();
        let u = away_from_edges(g, &probs);
        vec![Arg::F32s(probs), Arg::F32(u)]
    });
    let policy = fixture(|b| {
        b.probs
            .iter()
            .take(40)
            .map(|p| {
                let u = away_from_edges(&mut Gen::for_pair(p), p);
                vec![Arg::F32s(p.to_vec()), Arg::F32(u)]
            })
            .collect()
    });
    let zero = vec![
        vec![Arg::F32s(vec![0.0, 1.0]), Arg::F32(0.0)],
        vec![Arg::F32s(vec![1.0, 0.0]), Arg::F32(0.999_9)],
        vec![Arg::F32s(vec![0.5, 0.0, 0.5]), Arg::F32(0.5)],
        vec![Arg::F32s(vec![0.25, 0.75]), Arg::F32(0.0)],
    ];
    let near_one = vec![
        vec![Arg::F32s(vec![0.3, 0.699_99]), Arg::F32(0.999_995)],
        vec![Arg::F32s(vec![0.2, 0.2, 0.599_9]), Arg::F32(0.999_95)],
    ];
    vec![
        random,
        policy,
        check("an action of probability 0 is never chosen", zero),
        check("probabilities summing a hair below u", near_one),
    ]
}

impl Gen {
    /// A generator seeded from a probability pair, so fixture cases do not depend on order.
    fn for_pair(p: &[f32; 2]) -> Self {
        Self::new(u64::from(p[0].to_bits()) ^ (u64::from(p[1].to_bits()) << 17))
    }
}

fn td_target_case(rewards: Vec<f32>, next_values: Vec<f32>, dones: Vec<bool>, g: f32) -> Vec<Arg> {
    vec![
        Arg::F32s(rewards),
        Arg::F32s(next_values),
        Arg::Bools(dones),
        Arg::F32(g),
    ]
}

/// `td_target`'s checks.
pub fn td_target() -> Vec<CheckCases> {
    let random = random(7, |g| {
        let n = g.int(2, 60);
        let rewards = if g.chance(0.6) {
            vec![1.0; n]
        } else {
            g.f32s(n, -2.0, 2.0)
        };
        let mut dones = g.bools(n, 0.15);
        if let Some(last) = dones.last_mut() {
            *last = true;
        }
        let gamma = if g.chance(0.5) { 0.98 } else { g.f(0.5, 1.0) };
        td_target_case(rewards, g.f32s(n, -5.0, 60.0), dones, gamma)
    });
    let recorded = fixture(|b| {
        vec![td_target_case(
            b.rewards.clone(),
            b.next_values.clone(),
            b.dones.clone(),
            b.config.gamma as f32,
        )]
    });
    let single = vec![
        td_target_case(vec![1.0], vec![30.0], vec![false], 0.98),
        td_target_case(vec![1.0], vec![30.0], vec![true], 0.98),
        td_target_case(vec![-0.5], vec![-2.0], vec![false], 0.9),
    ];
    let all_done = vec![
        td_target_case(
            vec![1.0; 4],
            vec![10.0, 20.0, -3.0, 40.0],
            vec![true; 4],
            0.98,
        ),
        td_target_case(vec![0.5, -1.0], vec![7.0, 8.0], vec![true; 2], 0.9),
    ];
    vec![
        random,
        recorded,
        check("a single step", single),
        check("every step done", all_done),
    ]
}

/// `td_delta`'s checks.
pub fn td_delta() -> Vec<CheckCases> {
    let random = random(70, |g| {
        let n = g.int(1, 60);
        vec![
            Arg::F32s(g.f32s(n, -5.0, 60.0)),
            Arg::F32s(g.f32s(n, -5.0, 60.0)),
        ]
    });
    let recorded = fixture(|b| {
        vec![vec![
            Arg::F32s(b.td_target.clone()),
            Arg::F32s(b.values.clone()),
        ]]
    });
    let single = vec![vec![Arg::F32s(vec![20.4]), Arg::F32s(vec![19.0])]];
    let negative = vec![vec![
        Arg::F32s(vec![1.0, 10.0, 20.0]),
        Arg::F32s(vec![5.0, 12.5, 20.5]),
    ]];
    vec![
        random,
        recorded,
        check("a single step", single),
        check("negative TD errors (the critic overestimates)", negative),
    ]
}

fn gae_case(gamma: f32, lmbda: f32, td_delta: Vec<f32>) -> Vec<Arg> {
    vec![Arg::F32(gamma), Arg::F32(lmbda), Arg::F32s(td_delta)]
}

/// `compute_advantage`'s checks.
pub fn compute_advantage() -> Vec<CheckCases> {
    let random = random(8, |g| {
        let n = g.int(2, 80);
        let (gamma, lmbda) = if g.chance(0.5) {
            (0.98, 0.95)
        } else {
            (g.f(0.5, 1.0), g.f(0.3, 1.0))
        };
        gae_case(gamma, lmbda, g.f32s(n, -3.0, 3.0))
    });
    let recorded = fixture(|b| {
        vec![gae_case(
            b.config.gamma as f32,
            b.config.lmbda as f32,
            b.td_delta.clone(),
        )]
    });
    let single = vec![
        gae_case(0.98, 0.95, vec![0.7]),
        gae_case(0.98, 0.95, vec![-1.5]),
    ];
    let negative = vec![gae_case(0.98, 0.95, vec![-1.0, -0.5, -2.0, -0.25, -1.0])];
    let extremes = vec![
        gae_case(0.98, 0.0, vec![1.0, -2.0, 3.0]),
        gae_case(0.98, 1.0, vec![1.0, -2.0, 3.0]),
        gae_case(1.0, 1.0, vec![1.0, 1.0, 1.0, 1.0]),
    ];
    vec![
        random,
        recorded,
        check("a single step", single),
        check("negative TD errors", negative),
        check("λ = 0 and λ = 1", extremes),
    ]
}

/// `log_prob_of_actions`' checks.
pub fn log_prob_of_actions() -> Vec<CheckCases> {
    let random = random(9, |g| {
        let n = g.int(1, 60);
        let probs: Vec<[f32; 2]> = (0..n)
            .map(|_| {
                let p = g.f(0.01, 0.99);
                [p, 1.0 - p]
            })
            .collect();
        let actions = (0..n).map(|_| g.int(0, 1)).collect();
        vec![Arg::Pairs(probs), Arg::Usizes(actions)]
    });
    let recorded = fixture(|b| {
        vec![vec![
            Arg::Pairs(b.probs.clone()),
            Arg::Usizes(b.actions.clone()),
        ]]
    });
    let single = vec![
        vec![Arg::Pairs(vec![[0.3, 0.7]]), Arg::Usizes(vec![0])],
        vec![Arg::Pairs(vec![[0.3, 0.7]]), Arg::Usizes(vec![1])],
    ];
    let sure = vec![vec![
        Arg::Pairs(vec![[0.999, 0.001], [0.001, 0.999], [0.999, 0.001]]),
        Arg::Usizes(vec![0, 0, 1]),
    ]];
    vec![
        random,
        recorded,
        check("a single step", single),
        check("near-certain and near-impossible actions", sure),
    ]
}

/// `ratio`'s checks.
pub fn ratio() -> Vec<CheckCases> {
    let random = random(10, |g| {
        let n = g.int(1, 60);
        let old: Vec<f32> = (0..n).map(|_| g.f(0.05, 1.0).ln()).collect();
        let new = old.iter().map(|o| o + g.f(-0.5, 0.5)).collect();
        vec![Arg::F32s(new), Arg::F32s(old)]
    });
    let recorded = fixture(|b| {
        b.epochs
            .iter()
            .map(|(log_probs, _)| {
                vec![
                    Arg::F32s(log_probs.clone()),
                    Arg::F32s(b.old_log_probs.clone()),
                ]
            })
            .collect()
    });
    let single = vec![vec![Arg::F32s(vec![-0.6]), Arg::F32s(vec![-0.7])]];
    let first_epoch = vec![vec![
        Arg::F32s(vec![-0.69, -0.1, -2.3]),
        Arg::F32s(vec![-0.69, -0.1, -2.3]),
    ]];
    let outside = vec![vec![
        Arg::F32s(vec![-0.2, -1.5, -0.05, -3.0]),
        Arg::F32s(vec![-0.9, -0.4, -1.2, -1.0]),
    ]];
    vec![
        random,
        recorded,
        check("a single step", single),
        check("the first epoch (equal log-probabilities)", first_epoch),
        check("ratios outside 1 ± ε", outside),
    ]
}

fn loss_case(ratio: Vec<f32>, advantage: Vec<f32>, eps: f32) -> Vec<Arg> {
    vec![Arg::F32s(ratio), Arg::F32s(advantage), Arg::F32(eps)]
}

/// `actor_loss`'s checks.
pub fn actor_loss() -> Vec<CheckCases> {
    let random = random(11, |g| {
        let n = g.int(2, 60);
        let eps = if g.chance(0.5) { 0.2 } else { g.f(0.1, 0.3) };
        loss_case(g.f32s(n, 0.6, 1.4), g.f32s(n, -3.0, 3.0), eps)
    });
    let recorded = fixture(|b| {
        b.epochs
            .iter()
            .map(|(_, ratio)| loss_case(ratio.clone(), b.advantage.clone(), b.config.eps as f32))
            .collect()
    });
    let single = vec![
        loss_case(vec![1.5], vec![2.0], 0.2),
        loss_case(vec![0.5], vec![-2.0], 0.2),
    ];
    let negative = vec![loss_case(
        vec![0.5, 0.9, 1.1, 1.6],
        vec![-1.0, -2.0, -0.5, -3.0],
        0.2,
    )];
    let outside = vec![
        loss_case(vec![0.5, 1.5, 0.7, 1.3], vec![1.0, 1.0, -1.0, -1.0], 0.2),
        loss_case(vec![1.0, 2.0, 0.1], vec![0.5, 0.5, 0.5], 0.2),
    ];
    vec![
        random,
        recorded,
        check("a single step", single),
        check("negative advantages", negative),
        check("ratios outside 1 ± ε", outside),
    ]
}

/// `critic_loss`'s checks.
pub fn critic_loss() -> Vec<CheckCases> {
    let random = random(12, |g| {
        let n = g.int(2, 60);
        vec![
            Arg::F32s(g.f32s(n, -5.0, 60.0)),
            Arg::F32s(g.f32s(n, -5.0, 60.0)),
        ]
    });
    let recorded = fixture(|b| {
        vec![vec![
            Arg::F32s(b.values.clone()),
            Arg::F32s(b.td_target.clone()),
        ]]
    });
    let single = vec![vec![Arg::F32s(vec![3.0]), Arg::F32s(vec![5.0])]];
    let both_sides = vec![vec![
        Arg::F32s(vec![1.0, 3.0, 10.0, 10.0]),
        Arg::F32s(vec![2.0, 2.0, 12.0, 8.0]),
    ]];
    vec![
        random,
        recorded,
        check("a single step", single),
        check("errors of both signs", both_sides),
    ]
}

fn ma_case(a: Vec<f64>, window: usize) -> Vec<Arg> {
    vec![Arg::F64s(a), Arg::Usize(window)]
}

/// `moving_average`'s checks.
pub fn moving_average() -> Vec<CheckCases> {
    let random = random(13, |g| {
        let n = g.int(1, 80);
        let max_half = n.div_ceil(2).min(10);
        let window = 2 * g.int(0, max_half) + 1;
        let window = if window > n + 1 { window - 2 } else { window };
        let a = (0..n).map(|_| f64::from(g.f(0.0, 500.0)).round()).collect();
        ma_case(a, window)
    });
    let numpy = numpy_cases();
    let single = vec![ma_case(vec![42.0], 1)];
    let wide = vec![
        ma_case((1..=8).map(f64::from).collect(), 9),
        ma_case(vec![3.0, 9.0], 3),
        ma_case(vec![10.0, 20.0, 40.0, 80.0], 5),
    ];
    let equal = vec![
        ma_case(vec![1.0, 2.0, 4.0, 8.0, 16.0], 5),
        ma_case((0..9).map(|i| f64::from(i * i)).collect(), 9),
    ];
    vec![
        random,
        check("numpy's rl_utils.moving_average (recorded)", numpy),
        check("a single value", single),
        check("a window larger than the input", wide),
        check("a window as long as the input", equal),
    ]
}

/// The embedded numpy cases as `(a, window)` (expected values come from the reference,
/// which equals numpy's; the test suite checks that).
fn numpy_cases() -> Vec<Vec<Arg>> {
    let Ok(json) = serde_json::from_str::<serde_json::Value>(MA_FIXTURE) else {
        return Vec::new();
    };
    let cases = json["cases"].as_array().cloned().unwrap_or_default();
    cases
        .iter()
        .filter_map(|c| {
            let window = usize::try_from(c["window"].as_u64()?).ok()?;
            let a = c["input"]
                .as_array()?
                .iter()
                .map(serde_json::Value::as_f64)
                .collect::<Option<Vec<f64>>>()?;
            Some(ma_case(a, window))
        })
        .collect()
}

/// The numpy fixture's recorded outputs, in the order of [`moving_average`]'s numpy check.
#[must_use]
pub fn numpy_outputs() -> Vec<Vec<f64>> {
    let Ok(json) = serde_json::from_str::<serde_json::Value>(MA_FIXTURE) else {
        return Vec::new();
    };
    let cases = json["cases"].as_array().cloned().unwrap_or_default();
    cases
        .iter()
        .filter_map(|c| {
            c["output"]
                .as_array()?
                .iter()
                .map(serde_json::Value::as_f64)
                .collect()
        })
        .collect()
}
