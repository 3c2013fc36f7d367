//! How far the surrogate's prediction can be trusted, measured from the live agent's batch.
//!
//! The performance-difference lemma gives the exact change in the discounted return
//! `J_γ` between two policies, with `A_old` the advantage of `π_old`:
//!
//! ```text
//! J(θ) − J(θ_old) = E_{τ ~ π_θ}   [ Σ_t γ^t A_old(s_t, a_t) ]             exact
//! L(θ)            = E_{τ ~ π_old} [ Σ_t γ^t (r_t(θ) − 1) A_old(s_t, a_t) ]  the surrogate
//! r_t(θ)          = π_θ(a_t|s_t) / π_old(a_t|s_t)
//! ```
//!
//! The ratio re-weights the *actions* to `π_θ`'s, but the *states* stay those `π_old`
//! visits, so `L` is right only to first order: `L(θ_old) = 0` and `∇L(θ_old) = ∇J(θ_old)`.
//! The bound behind TRPO says the error grows with the KL between the two policies (its
//! maximum over states, or in practice its mean). (The `− 1` is a control variate: its
//! expectation under `π_old` is 0 with the true advantage, and it makes the estimate
//! exactly 0 at `θ_old`.)
//!
//! [`probe`] measures this. From `θ_old` it steps along the unit direction `d = g / ‖g‖`
//! (`g` the batch's surrogate gradient, [`surrogate_gradients`](super::gradient::surrogate_gradients),
//! PyTorch's parameter order): `θ_α = θ_old + α · d`, `α` the step's L2 length in parameter
//! space. At each `α`, over `E` fresh **held-out** episodes of `π_old` (not the batch `g`
//! came from, which separates "the surrogate keeps `π_old`'s states" from over-fitting one
//! batch):
//!
//! ```text
//! kl        = mean over the held-out states s of KL(π_old(·|s) ‖ π_θα(·|s))       exact, 2 actions
//! predicted = mean_e Σ_t γ^t (r_t(θ_α) − 1) Â_t        Â: GAE(γ, λ) of the config, unnormalised
//! truth     = mean_e [G_γ(θ_α; e) − G_γ(θ_old; e)]     G_γ = Σ_t γ^t r_t of a fresh episode
//! ```
//!
//! each with its standard error over the `E` episodes. `Â` uses the critic the caller gives
//! (the course's `probe_snapshot`: the snapshot's critic *after* the update, which has just been fitted
//! to `π_old`'s latest batch) and the config's done mask (the seed's: terminated or
//! truncated); it is not normalised even when the config normalises it, since the
//! prediction is in units of return. The truth uses common random numbers: episode `e` of
//! every policy starts from the same reset seed and draws its actions from the same stream
//! of uniforms (one per step, `a = 0` if `u < π(0|s)`, as the agent samples), so the paired
//! difference has far less variance than two independent means, and at `α = 0` it is
//! exactly 0. The undiscounted change (CartPole's score) is kept for display.
//!
//! The forward passes run on plain `f32` weights (4 → hidden → 2), with the log-softmax
//! and everything after it in `f64`.
//!
//! ```
//! use ppo_rl::ppo::discrete::trust_region::{ProbeSettings, probe};
//! use ppo_rl::ppo::{Agent, PpoConfig, model::ActorSnapshot};
//!
//! let config = PpoConfig::default();
//! let agent = Agent::new(&config, 0)?;
//! let old = ActorSnapshot::of(agent.actor())?;
//! let critic = agent.weights()?; // the critic by PyTorch name (critic.fc1.weight, ...)
//! let direction = vec![1.0_f32; old.parameters().len()];
//! let settings = ProbeSettings { steps: vec![0.0, 0.5], episodes: 4, seed: 1 };
//! let probe = probe(&old, &critic, &direction, &config, &settings)?;
//! assert_eq!(probe.points[0].truth, 0.0); // the same episodes: no change at all
//! assert_eq!(probe.points[0].kl, 0.0);
//! assert!(probe.points[1].kl > 0.0);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use serde::Serialize;

use super::PpoConfig;
use crate::env::CartPole;
use crate::env::seeding::NumpyRng;
use crate::i18n::t;
use crate::ppo::PpoError;
use crate::ppo::advantage::compute_advantage;
use crate::ppo::model::{ActorSnapshot, NamedWeights};
use crate::tr;

/// What [`probe`] measures: the step lengths and how many held-out episodes.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ProbeSettings {
    /// The step lengths `α` (L2 norm of `θ_α − θ_old` in parameter space), in the order
    /// reported; 0 is `θ_old` itself. Any finite value (a negative one steps against the
    /// gradient).
    pub steps: Vec<f32>,
    /// Held-out episodes per step (at least 2, for a standard error).
    pub episodes: usize,
    /// Seeds the held-out episodes (their resets and action draws).
    pub seed: u64,
}

impl Default for ProbeSettings {
    /// Twelve steps from 0 to 3.2 and 150 episodes: on the seed's agent after 20–60
    /// training episodes the mean KL runs from about 1e-4 to well above 0.3, the truth's
    /// standard error stays small next to the gap it opens, and the whole probe takes
    /// about a second on one core (release build).
    fn default() -> Self {
        Self {
            steps: DEFAULT_STEPS.to_vec(),
            episodes: 150,
            seed: 0,
        }
    }
}

/// The default step lengths (see [`ProbeSettings::default`]).
pub const DEFAULT_STEPS: [f32; 12] = [
    0.0, 0.025, 0.05, 0.1, 0.2, 0.3, 0.4, 0.6, 0.8, 1.2, 1.6, 3.2,
];

impl ProbeSettings {
    /// Checks the settings before any episode is played.
    ///
    /// # Errors
    /// [`PpoError::InvalidConfig`] naming `steps` (empty, or a step that is not finite)
    /// or `episodes` (fewer than 2).
    pub fn validate(&self) -> Result<(), PpoError> {
        if self.steps.is_empty() {
            return Err(PpoError::InvalidConfig {
                field: "steps",
                value: "[]".into(),
                expected: "at least one step length, e.g. 0,0.1,0.4,1.6",
            });
        }
        if let Some(bad) = self.steps.iter().find(|s| !s.is_finite()) {
            return Err(PpoError::InvalidConfig {
                field: "steps",
                value: bad.to_string(),
                expected: "finite step lengths (the L2 length of θ − θ_old)",
            });
        }
        if self.episodes < 2 {
            return Err(PpoError::InvalidConfig {
                field: "episodes",
                value: self.episodes.to_string(),
                expected: "at least 2 held-out episodes (a standard error needs two)",
            });
        }
        Ok(())
    }
}

/// What one step length gave.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ProbePoint {
    /// `α`, the step's L2 length in parameter space.
    pub step: f32,
    /// Mean over the held-out states of `KL(π_old(·|s) ‖ π_θα(·|s))`.
    pub kl: f64,
    /// The largest of those KLs.
    pub kl_max: f64,
    /// The surrogate's predicted change in `J_γ`: mean over episodes of
    /// `Σ_t γ^t (r_t − 1) Â_t`.
    pub predicted: f64,
    /// Its standard error over the held-out episodes.
    pub predicted_se: f64,
    /// The measured change in `J_γ`: mean of the paired `G_γ(θ_α) − G_γ(θ_old)`.
    pub truth: f64,
    /// Its standard error over the episodes.
    pub truth_se: f64,
    /// The measured change in the undiscounted return (CartPole's score), paired likewise.
    pub return_change: f64,
    /// Its standard error.
    pub return_change_se: f64,
}

/// The probe's result: one [`ProbePoint`] per step length, and where `π_old` stands.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TrustRegionProbe {
    /// One point per step, in the settings' order.
    pub points: Vec<ProbePoint>,
    /// The mean discounted return `G_γ` of `π_old` over the held-out episodes.
    pub old_return: f64,
    /// The mean undiscounted return (score) of `π_old` over them.
    pub old_score: f64,
    /// Held-out episodes per step.
    pub episodes: usize,
    /// Held-out states of `π_old` (over all its episodes) the KL is averaged over.
    pub states: usize,
    /// `‖g‖`, the L2 norm of the direction before it was normalised.
    pub gradient_norm: f64,
}

/// Where held-out episode `e` starts and how its actions are drawn: the same for every
/// policy the probe compares (common random numbers).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct EpisodeSeeds {
    /// The seed of the environment's `reset(seed=...)`.
    pub reset: u64,
    /// The seed of the stream of uniforms the actions are drawn from.
    pub actions: u64,
}

/// The seeds of `episodes` held-out episodes, drawn from `seed`.
#[must_use]
pub fn episode_seeds(seed: u64, episodes: usize) -> Vec<EpisodeSeeds> {
    let mut rng = NumpyRng::from_seed(seed);
    (0..episodes)
        .map(|_| EpisodeSeeds {
            reset: rng.next_u64(),
            actions: rng.next_u64(),
        })
        .collect()
}

/// A 4 → hidden → 2 softmax actor on plain `f32` weights.
#[derive(Debug, Clone)]
struct Actor {
    /// `fc1.weight`, `(hidden, 4)` row-major.
    w1: Vec<f32>,
    b1: Vec<f32>,
    /// `fc2.weight`, `(2, hidden)` row-major.
    w2: Vec<f32>,
    b2: [f32; 2],
}

impl Actor {
    /// The actor whose parameters, in PyTorch's order, are `params` (`hidden` wide).
    fn from_parameters(params: &[f32], hidden: usize) -> Option<Self> {
        if params.len() != 7 * hidden + 2 || hidden == 0 {
            return None;
        }
        let (w1, rest) = params.split_at(4 * hidden);
        let (b1, rest) = rest.split_at(hidden);
        let (w2, b2) = rest.split_at(2 * hidden);
        Some(Self {
            w1: w1.to_vec(),
            b1: b1.to_vec(),
            w2: w2.to_vec(),
            b2: [b2[0], b2[1]],
        })
    }

    /// `(log π(0|s), log π(1|s))`: the logits in `f32`, the log-softmax in `f64`.
    fn log_probs(&self, s: &[f32; 4]) -> [f64; 2] {
        let h = self.b1.len();
        let (w20, w21) = self.w2.split_at(h);
        let (mut z0, mut z1) = (self.b2[0], self.b2[1]);
        for (((row, &b), &a0), &a1) in self.w1.chunks_exact(4).zip(&self.b1).zip(w20).zip(w21) {
            let x = (row[0] * s[0] + row[1] * s[1] + row[2] * s[2] + row[3] * s[3] + b).max(0.0);
            z0 += a0 * x;
            z1 += a1 * x;
        }
        // log π(0) = −softplus(z1 − z0), log π(1) = −softplus(z0 − z1)
        let d = f64::from(z1) - f64::from(z0);
        [-softplus(d), -softplus(-d)]
    }
}

/// `ln(1 + e^x)` without overflow.
fn softplus(x: f64) -> f64 {
    x.max(0.0) + (-x.abs()).exp().ln_1p()
}

/// The critic `V(s) = fc2(relu(fc1(s)))` on plain `f32` weights.
#[derive(Debug, Clone)]
struct Critic {
    w1: Vec<f32>,
    b1: Vec<f32>,
    w2: Vec<f32>,
    b2: f32,
}

impl Critic {
    /// The critic in `weights` (`critic.fc1.weight`, ..., as a live snapshot holds it).
    fn from_weights(weights: &NamedWeights) -> Result<Self, PpoError> {
        let get = |name: &str| {
            weights.get(name).ok_or_else(|| PpoError::MissingKey {
                file: t("the critic's weights", "价值网络的权重").into(),
                key: name.into(),
                expected: t(
                    "the critic's parameters by PyTorch name; pass the agent's weights()",
                    "按 PyTorch 名称排列的价值网络参数；请传入智能体的 weights()",
                )
                .into(),
            })
        };
        let (w1, b1, w2, b2) = (
            get("critic.fc1.weight")?,
            get("critic.fc1.bias")?,
            get("critic.fc2.weight")?,
            get("critic.fc2.bias")?,
        );
        let h = b1.data.len();
        for (name, w, want) in [
            ("critic.fc1.weight", w1, 4 * h),
            ("critic.fc2.weight", w2, h),
            ("critic.fc2.bias", b2, 1),
        ] {
            if w.data.len() != want || h == 0 {
                return Err(PpoError::WrongShape {
                    file: t("the critic's weights", "价值网络的权重").into(),
                    key: name.into(),
                    expected: tr!(
                        "{want} values (hidden layer {h}, 4 inputs, 1 output)",
                        "{want} 个值（隐藏层 {h}，4 个输入，1 个输出）"
                    ),
                    got: {
                        let got = w.data.len();
                        tr!("{got} values", "{got} 个值")
                    },
                });
            }
        }
        Ok(Self {
            w1: w1.data.clone(),
            b1: b1.data.clone(),
            w2: w2.data.clone(),
            b2: b2.data[0],
        })
    }

    fn value(&self, s: &[f32; 4]) -> f32 {
        let mut v = self.b2;
        for ((row, &b), &w) in self.w1.chunks_exact(4).zip(&self.b1).zip(&self.w2) {
            let x = (row[0] * s[0] + row[1] * s[1] + row[2] * s[2] + row[3] * s[3] + b).max(0.0);
            v += w * x;
        }
        v
    }
}

/// One played episode: what the prediction needs of it, and its returns.
#[derive(Debug, Clone, Default, PartialEq)]
struct Episode {
    states: Vec<[f32; 4]>,
    actions: Vec<usize>,
    /// `log π(a_t|s_t)` under the policy that played.
    log_probs: Vec<f64>,
    rewards: Vec<f32>,
    next_states: Vec<[f32; 4]>,
    /// The config's done mask (terminated, or terminated or truncated).
    dones: Vec<bool>,
    /// `G_γ = Σ_t γ^t r_t`.
    discounted: f64,
    /// `Σ_t r_t`.
    score: f64,
}

/// Plays one episode of `actor` from `seeds` (the config's env and done mask).
fn play(actor: &Actor, seeds: EpisodeSeeds, config: &PpoConfig) -> Result<Episode, PpoError> {
    let mut env = CartPole::new(config.env_id);
    let mut uniforms = NumpyRng::from_seed(seeds.actions);
    let mut state = env.reset(Some(seeds.reset));
    let mut episode = Episode::default();
    let mut discount = 1.0;
    loop {
        let log_probs = actor.log_probs(&state);
        if !log_probs.iter().all(|l| l.is_finite()) {
            return Err(PpoError::NonFinite(tr!(
                "the probe's action log-probabilities {log_probs:?}",
                "探测中的动作对数概率 {log_probs:?}"
            )));
        }
        let action = usize::from(uniforms.next_f64() >= log_probs[0].exp());
        let step = env.step(action)?;
        episode.discounted += discount * step.reward;
        episode.score += step.reward;
        discount *= config.gamma;
        let done = step.terminated || step.truncated;
        episode.states.push(state);
        episode.actions.push(action);
        episode.log_probs.push(log_probs[action]);
        episode.rewards.push(step.reward as f32);
        episode.next_states.push(step.obs);
        episode.dones.push(if config.bootstrap_on_truncation {
            step.terminated
        } else {
            done
        });
        state = step.obs;
        if done {
            return Ok(episode);
        }
    }
}

/// GAE of one episode under `critic`, as the agent computes it (unnormalised).
fn advantage(episode: &Episode, critic: &Critic, config: &PpoConfig) -> Vec<f32> {
    let gamma = config.gamma as f32;
    let td_delta: Vec<f32> = (0..episode.states.len())
        .map(|t| {
            let next = critic.value(&episode.next_states[t]);
            let not_done = if episode.dones[t] { 0.0 } else { 1.0 };
            let td_target = episode.rewards[t] + gamma * next * not_done;
            td_target - critic.value(&episode.states[t])
        })
        .collect();
    compute_advantage(config.gamma, config.lmbda, &td_delta)
}

/// The mean of `xs` and its standard error (sample standard deviation / √n).
fn mean_se(xs: &[f64]) -> (f64, f64) {
    let n = xs.len() as f64;
    if xs.is_empty() {
        return (0.0, 0.0);
    }
    let mean = xs.iter().sum::<f64>() / n;
    if xs.len() < 2 {
        return (mean, 0.0);
    }
    let var = xs.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1.0);
    (mean, (var / n).sqrt())
}

/// Probes the surrogate's trust region around `old` along `direction` (see the module
/// doc): `critic` holds the critic by PyTorch name (`critic.fc1.weight`, ...; other
/// entries are ignored), `direction` one value per actor parameter in PyTorch's order,
/// `config` gives γ, λ, the done mask and the environment.
///
/// # Errors
/// [`PpoError::InvalidConfig`] for bad settings or config; [`PpoError::InvalidBatch`] for a
/// direction of the wrong length, or one that is zero or not finite;
/// [`PpoError::MissingKey`] / [`PpoError::WrongShape`] for a critic that is not there or
/// does not fit; [`PpoError::NonFinite`] if a policy's probabilities turn NaN.
pub fn probe(
    old: &ActorSnapshot,
    critic: &NamedWeights,
    direction: &[f32],
    config: &PpoConfig,
    settings: &ProbeSettings,
) -> Result<TrustRegionProbe, PpoError> {
    settings.validate()?;
    config.validate()?;
    let theta_old = old.parameters();
    let hidden = old.hidden_dim();
    let actor_old = Actor::from_parameters(&theta_old, hidden).ok_or_else(|| {
        let got = theta_old.len();
        PpoError::InvalidBatch(tr!(
            "the probe needs CartPole's 4 → {hidden} → 2 actor, got {got} parameters",
            "探测需要 CartPole 的 4 → {hidden} → 2 策略网络，实际得到 {got} 个参数"
        ))
    })?;
    if direction.len() != theta_old.len() {
        let (len, parameters) = (direction.len(), theta_old.len());
        return Err(PpoError::InvalidBatch(tr!(
            "the direction has {len} values, the actor {parameters} parameters: pass the surrogate gradient of this actor",
            "方向有 {len} 个值，策略网络有 {parameters} 个参数：请传入这个策略网络的替代目标梯度"
        )));
    }
    let norm = direction
        .iter()
        .map(|&g| f64::from(g).powi(2))
        .sum::<f64>()
        .sqrt();
    if !(norm.is_finite() && norm > 0.0) {
        return Err(PpoError::InvalidBatch(tr!(
            "the direction's norm is {norm}: the batch gives no direction to step along; train on another episode",
            "方向的范数是 {norm}：这批数据给不出可迈步的方向；请再训练一个回合"
        )));
    }
    let critic = Critic::from_weights(critic)?;
    let seeds = episode_seeds(settings.seed, settings.episodes);
    let held_out = seeds
        .iter()
        .map(|&s| play(&actor_old, s, config))
        .collect::<Result<Vec<_>, _>>()?;
    let advantages: Vec<Vec<f32>> = held_out
        .iter()
        .map(|e| advantage(e, &critic, config))
        .collect();
    let states = held_out.iter().map(|e| e.states.len()).sum();
    let old_log_probs: Vec<Vec<[f64; 2]>> = held_out
        .iter()
        .map(|e| e.states.iter().map(|s| actor_old.log_probs(s)).collect())
        .collect();

    let mut points = Vec::with_capacity(settings.steps.len());
    for &step in &settings.steps {
        let scale = f64::from(step) / norm;
        let theta: Vec<f32> = theta_old
            .iter()
            .zip(direction)
            .map(|(&w, &g)| w + (scale * f64::from(g)) as f32)
            .collect();
        let actor = Actor::from_parameters(&theta, hidden).ok_or_else(|| {
            PpoError::InvalidBatch(
                t(
                    "the stepped actor lost its shape (a bug)",
                    "迈步后的策略网络形状不对（程序错误）",
                )
                .into(),
            )
        })?;
        let (mut kl_sum, mut kl_max) = (0.0, 0.0_f64);
        let mut predicted = Vec::with_capacity(held_out.len());
        let mut truth = Vec::with_capacity(held_out.len());
        let mut score = Vec::with_capacity(held_out.len());
        for (((episode, adv), old_lp), &s) in held_out
            .iter()
            .zip(&advantages)
            .zip(&old_log_probs)
            .zip(&seeds)
        {
            let mut gain = 0.0;
            let mut discount = 1.0;
            for (t, state) in episode.states.iter().enumerate() {
                let new_lp = actor.log_probs(state);
                let p = [old_lp[t][0].exp(), old_lp[t][1].exp()];
                let kl = p[0] * (old_lp[t][0] - new_lp[0]) + p[1] * (old_lp[t][1] - new_lp[1]);
                kl_sum += kl;
                kl_max = kl_max.max(kl);
                let a = episode.actions[t];
                let ratio = (new_lp[a] - old_lp[t][a]).exp();
                gain += discount * (ratio - 1.0) * f64::from(adv[t]);
                discount *= config.gamma;
            }
            predicted.push(gain);
            let fresh = play(&actor, s, config)?;
            truth.push(fresh.discounted - episode.discounted);
            score.push(fresh.score - episode.score);
        }
        let kl = kl_sum / states as f64;
        if !kl.is_finite() {
            return Err(PpoError::NonFinite(tr!(
                "the mean KL at step {step} (a probability underflowed)",
                "步长 {step} 处的平均 KL（某个概率下溢）"
            )));
        }
        let (predicted, predicted_se) = mean_se(&predicted);
        let (truth, truth_se) = mean_se(&truth);
        let (return_change, return_change_se) = mean_se(&score);
        points.push(ProbePoint {
            step,
            kl,
            kl_max,
            predicted,
            predicted_se,
            truth,
            truth_se,
            return_change,
            return_change_se,
        });
    }
    let returns: Vec<f64> = held_out.iter().map(|e| e.discounted).collect();
    let scores: Vec<f64> = held_out.iter().map(|e| e.score).collect();
    Ok(TrustRegionProbe {
        points,
        old_return: mean_se(&returns).0,
        old_score: mean_se(&scores).0,
        episodes: settings.episodes,
        states,
        gradient_norm: norm,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ppo::Agent;

    type TestResult = Result<(), Box<dyn std::error::Error>>;

    fn small(steps: &[f32]) -> ProbeSettings {
        ProbeSettings {
            steps: steps.to_vec(),
            episodes: 12,
            seed: 3,
        }
    }

    /// Common random numbers: episode `e` of every policy starts from the same reset seed
    /// and draws the same uniforms, so the same policy plays it identically; another
    /// episode index or another seed gives other episodes.
    #[test]
    fn the_same_seeds_replay_the_same_episode() -> TestResult {
        let agent = Agent::new(&PpoConfig::default(), 1)?;
        let old = ActorSnapshot::of(agent.actor())?;
        let actor = Actor::from_parameters(&old.parameters(), old.hidden_dim())
            .ok_or("not CartPole's actor")?;
        let config = PpoConfig::default();
        let seeds = episode_seeds(7, 3);
        assert_eq!(seeds, episode_seeds(7, 3));
        assert_ne!(seeds[0], seeds[1]);
        assert_ne!(episode_seeds(8, 1)[0], seeds[0]);
        let first = play(&actor, seeds[0], &config)?;
        assert_eq!(play(&actor, seeds[0], &config)?, first);
        assert_ne!(play(&actor, seeds[1], &config)?.states, first.states);
        // The actions follow the actor's probabilities: the agent's own forward pass.
        for ((s, &a), lp) in first
            .states
            .iter()
            .zip(&first.actions)
            .zip(&first.log_probs)
        {
            let want = f64::from(old.probs(s)[a]).ln();
            assert!((lp - want).abs() < 1e-5, "{lp} vs {want}");
        }
        // θ_old + 0 · d is θ_old: the probe's α = 0 episodes are the held-out ones.
        let d = vec![0.5_f32; old.parameters().len()];
        let p = probe(&old, &agent.weights()?, &d, &config, &small(&[0.0, 0.0]))?;
        assert!(
            p.points
                .iter()
                .all(|q| q.truth == 0.0 && q.return_change == 0.0)
        );
        Ok(())
    }

    /// The surrogate's gain uses the unnormalised GAE of the given critic: with a critic
    /// that is zero, `Â_t` is the discounted sum of (γλ)-weighted rewards, checked here on
    /// one episode against a direct sum.
    #[test]
    fn the_advantage_is_the_configs_gae() -> TestResult {
        let agent = Agent::new(&PpoConfig::default(), 2)?;
        let mut weights = agent.weights()?;
        for (name, w) in &mut weights {
            if name.starts_with("critic.") {
                w.data.iter_mut().for_each(|x| *x = 0.0);
            }
        }
        let critic = Critic::from_weights(&weights)?;
        let config = PpoConfig::default();
        let old = ActorSnapshot::of(agent.actor())?;
        let actor = Actor::from_parameters(&old.parameters(), old.hidden_dim())
            .ok_or("not CartPole's actor")?;
        let e = play(&actor, episode_seeds(0, 1)[0], &config)?;
        let adv = advantage(&e, &critic, &config);
        let n = e.rewards.len();
        let gl = config.gamma * config.lmbda;
        let want0: f64 = (0..n).map(|t| gl.powi(t as i32)).sum();
        assert!(
            (f64::from(adv[0]) - want0).abs() < 1e-4 * want0,
            "{} vs {want0}",
            adv[0]
        );
        assert_eq!(adv[n - 1], 1.0);
        Ok(())
    }
}
