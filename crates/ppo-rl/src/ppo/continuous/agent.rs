//! The book's `class PPOContinuous`: `take_action` and `update` with a Gaussian policy.
//!
//! One update on an episode of `N` transitions (shapes as PyTorch prints them):
//!
//! ```text
//! scaled_rewards = (rewards + 8) / 8                                     (N, 1)
//! td_target      = scaled_rewards + γ · V(next_states) · (1 - dones)      (N, 1), detached
//! td_delta       = td_target - V(states)                                 (N, 1)
//! advantage      = GAE(td_delta)                                         (N, 1), detached
//! μ, σ           = π(states), detached
//! old_log_probs  = log N(actions; μ, σ)                                  (N, 1), detached
//! repeat epochs times:
//!     μ, σ        = π(states)
//!     log_probs   = log N(actions; μ, σ)                                 (N, 1)
//!     ratio       = exp(log_probs - old_log_probs)                       (N, 1)
//!     surr1       = ratio · advantage
//!     surr2       = clamp(ratio, 1 - ε, 1 + ε) · advantage
//!     actor_loss  = mean(-min(surr1, surr2))                             scalar
//!     critic_loss = mean((V(states) - td_target)²)                       scalar
//!     one Adam step of each network on its own loss
//! ```
//!
//! The only differences from the discrete [`Agent`](crate::ppo::Agent): the rescaled
//! rewards, and `log π` from the Gaussian density instead of `log(gather(softmax))`.
//!
//! The code below, on candle tensors with autograd, is the update the lessons show
//! ([`UpdatePath::Candle`]). `update` runs the same IEEE operations in the same order on
//! plain `f32` slices instead ([`UpdatePath::Plain`], the private module `plain`, whose tests
//! compare both number for number) where [`update_path`](crate::ppo::update_path) says so
//! (Pendulum's 200-step batches and the book's widths qualify on a CPU with AVX2 and FMA);
//! [`ContinuousUpdateTrace::path`] records the path that ran. The plain path gives the same traces
//! and weights, bit for bit, about 20 times faster (measured on a loaded 2-core machine,
//! release build: 300 episodes in 6.0-6.7 s with the tensors, 0.31 s without; the book's
//! 2000 in 1.4-1.8 s). `PPO_TUTOR_UPDATE=candle` forces candle for every update.
//!
//! Acting samples `a = μ + σ·z`, `z ~ N(0, 1)` from `rand_distr`'s `StandardNormal` fed by
//! the agent's seeded PCG64 (numpy's generator, [`NumpyRng`]); μ and σ come from a plain-Rust
//! copy of the actor ([`ContinuousActorSnapshot`]). PyTorch's own sampler cannot be
//! reproduced, so runs are seeded but not PyTorch's draws; the update is PyTorch's.

use std::convert::Infallible;

use candle_core::{DType, Device, Tensor, Var};
use rand_distr::{Distribution, Normal};

use super::model::{ContinuousActorSnapshot, PolicyNetContinuous};
use super::normal::log_prob;
use super::params::{check_weights, parameter_names};
use super::trace::{ContinuousEpochTrace, ContinuousUpdateTrace};
use super::{ACTION_DIM, PpoContinuousConfig, REWARD_SCALE, REWARD_SHIFT, STATE_DIM};
use crate::env::seeding::NumpyRng;
use crate::ppo::PpoError;
use crate::ppo::adam::Adam;
use crate::ppo::advantage::compute_advantage;
use crate::ppo::kernels::isa;
use crate::ppo::model::{Linear, NamedWeights, ValueNet, WeightTensor};
use crate::ppo::on_policy::check_columns;
use crate::ppo::update_path::{UpdatePath, choose_path};

mod plain;

// ANCHOR: continuous_transitions
/// One episode's transitions, the book's `transition_dict`, column by column.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ContinuousTransitions {
    /// `s_t`, `(cos θ, sin θ, θ̇)`.
    pub states: Vec<[f32; 3]>,
    /// `a_t`, the sampled torque (the book's `action[0]`).
    pub actions: Vec<f32>,
    /// `r_t` as the environment gave it (rescaled inside the update).
    pub rewards: Vec<f32>,
    /// `s_{t+1}`.
    pub next_states: Vec<[f32; 3]>,
    /// `terminated or truncated`, the book's `done`.
    pub dones: Vec<bool>,
}

impl ContinuousTransitions {
    /// Appends one transition, as the book's five `transition_dict[...].append(...)`.
    pub fn push(
        &mut self,
        state: [f32; 3],
        action: f32,
        reward: f32,
        next_state: [f32; 3],
        done: bool,
    ) {
        self.states.push(state);
        self.actions.push(action);
        self.rewards.push(reward);
        self.next_states.push(next_state);
        self.dones.push(done);
    }
}
// ANCHOR_END: continuous_transitions

impl ContinuousTransitions {
    /// The number of transitions.
    #[must_use]
    pub fn len(&self) -> usize {
        self.actions.len()
    }

    /// Whether there are none.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.actions.is_empty()
    }

    fn check(&self) -> Result<(), PpoError> {
        check_columns(
            self.len(),
            &[
                ("states", self.states.len()),
                ("rewards", self.rewards.len()),
                ("next_states", self.next_states.len()),
                ("dones", self.dones.len()),
            ],
        )?;
        let numbers = [("actions", &self.actions), ("rewards", &self.rewards)];
        for (name, column) in numbers {
            if let Some(t) = column.iter().position(|x| !x.is_finite()) {
                let value = column[t];
                return Err(PpoError::InvalidBatch(crate::tr!(
                    "{name}[{t}] = {value} is not a finite number",
                    "{name}[{t}] = {value} 不是有限数"
                )));
            }
        }
        Ok(())
    }
}

/// numpy's PCG64 ([`NumpyRng`]) as a `rand` generator, so `rand_distr` can sample from it.
#[derive(Debug, Clone)]
struct Pcg64(NumpyRng);

impl rand::TryRng for Pcg64 {
    type Error = Infallible;

    fn try_next_u32(&mut self) -> Result<u32, Infallible> {
        Ok((self.0.next_u64() >> 32) as u32)
    }

    fn try_next_u64(&mut self) -> Result<u64, Infallible> {
        Ok(self.0.next_u64())
    }

    fn try_fill_bytes(&mut self, dst: &mut [u8]) -> Result<(), Infallible> {
        for chunk in dst.chunks_mut(8) {
            let bytes = self.0.next_u64().to_le_bytes();
            chunk.copy_from_slice(&bytes[..chunk.len()]);
        }
        Ok(())
    }
}

/// The book's `PPOContinuous`: Gaussian actor, critic, their optimizers, a seeded sampler.
#[derive(Debug, Clone)]
pub struct PpoContinuous {
    config: PpoContinuousConfig,
    actor: PolicyNetContinuous,
    critic: ValueNet,
    actor_optimizer: Adam,
    critic_optimizer: Adam,
    rng: Pcg64,
    acting: ContinuousActorSnapshot,
}

impl PpoContinuous {
    /// A fresh agent: networks initialised from `seed` (actor first: fc1, fc_mu, fc_std;
    /// then the critic), then torques sampled from the same generator.
    ///
    /// # Errors
    /// [`PpoError::InvalidConfig`] for a hyper-parameter out of range.
    pub fn new(config: &PpoContinuousConfig, seed: u64) -> Result<Self, PpoError> {
        config.validate()?;
        let mut rng = NumpyRng::from_seed(seed);
        let actor = PolicyNetContinuous::new(STATE_DIM, config.hidden_dim, ACTION_DIM, &mut rng)?;
        let critic = ValueNet::new(STATE_DIM, config.hidden_dim, &mut rng)?;
        Self::assemble(config, actor, critic, rng)
    }

    /// An agent holding `weights` (PyTorch names, see [`PpoContinuous::weights`]), with fresh
    /// Adam state and a sampler seeded by `seed`. `source` names where the weights came from
    /// in error messages.
    ///
    /// # Errors
    /// [`PpoError::MissingKey`] / [`PpoError::WrongShape`] naming the tensor and the shape
    /// `config.hidden_dim` requires; [`PpoError::InvalidConfig`].
    pub fn from_weights(
        config: &PpoContinuousConfig,
        weights: &NamedWeights,
        seed: u64,
        source: &str,
    ) -> Result<Self, PpoError> {
        config.validate()?;
        check_weights(weights, config.hidden_dim, source)?;
        let layer = |prefix: &str, in_dim: usize, out_dim: usize| -> Result<Linear, PpoError> {
            let get = |name: &str| {
                let key = format!("{prefix}.{name}");
                weights
                    .get(&key)
                    .map(|w| w.data.clone())
                    .ok_or_else(|| PpoError::MissingKey {
                        file: source.to_string(),
                        key,
                        expected: crate::i18n::t("a tensor", "张量").into(),
                    })
            };
            Ok(Linear::from_data(
                in_dim,
                out_dim,
                get("weight")?,
                get("bias")?,
            )?)
        };
        let h = config.hidden_dim;
        let actor = PolicyNetContinuous {
            fc1: layer("actor.fc1", STATE_DIM, h)?,
            fc_mu: layer("actor.fc_mu", h, ACTION_DIM)?,
            fc_std: layer("actor.fc_std", h, ACTION_DIM)?,
        };
        let critic = ValueNet {
            fc1: layer("critic.fc1", STATE_DIM, h)?,
            fc2: layer("critic.fc2", h, 1)?,
        };
        Self::assemble(config, actor, critic, NumpyRng::from_seed(seed))
    }

    fn assemble(
        config: &PpoContinuousConfig,
        actor: PolicyNetContinuous,
        critic: ValueNet,
        rng: NumpyRng,
    ) -> Result<Self, PpoError> {
        let critic_params = [&critic.fc1, &critic.fc2]
            .iter()
            .flat_map(|l| l.vars().map(Var::clone))
            .collect();
        let actor_optimizer = Adam::new(actor.vars(), config.actor_lr);
        let critic_optimizer = Adam::new(critic_params, config.critic_lr);
        let acting = ContinuousActorSnapshot::of(&actor)?;
        Ok(Self {
            config: config.clone(),
            actor,
            critic,
            actor_optimizer,
            critic_optimizer,
            rng: Pcg64(rng),
            acting,
        })
    }

    /// The hyper-parameters.
    #[must_use]
    pub fn config(&self) -> &PpoContinuousConfig {
        &self.config
    }

    /// The actor network (candle).
    #[must_use]
    pub fn actor(&self) -> &PolicyNetContinuous {
        &self.actor
    }

    /// The critic network (candle).
    #[must_use]
    pub fn critic(&self) -> &ValueNet {
        &self.critic
    }

    /// `(μ, σ)` of the policy in one observation.
    #[must_use]
    pub fn mu_std(&self, state: &[f32; 3]) -> (f32, f32) {
        self.acting.mu_std(state)
    }

    /// `V(state)` for one observation.
    ///
    /// # Errors
    /// Only if a candle operation fails.
    pub fn value(&self, state: &[f32; 3]) -> Result<f32, PpoError> {
        let s = Tensor::from_slice(state, (1, STATE_DIM), &Device::Cpu)?;
        Ok(self.critic.forward(&s)?.flatten_all()?.to_vec1::<f32>()?[0])
    }

    // ANCHOR: take_action_continuous
    /// Samples a torque `a ~ Normal(μ(state), σ(state))` with the agent's seeded generator,
    /// as the book's `torch.distributions.Normal(mu, sigma).sample()` (not clipped: the
    /// environment clips it to `[-2, 2]`).
    ///
    /// # Errors
    /// [`PpoError::NonFinite`] when μ or σ is NaN or infinite (a diverged actor).
    pub fn take_action(&mut self, state: &[f32; 3]) -> Result<f32, PpoError> {
        let (mu, std) = self.acting.mu_std(state);
        if !(mu.is_finite() && std.is_finite()) {
            return Err(PpoError::NonFinite(format!(
                "the policy's Normal(μ = {mu}, σ = {std})"
            )));
        }
        let normal = Normal::new(mu, std)
            .map_err(|e| PpoError::NonFinite(format!("Normal(μ = {mu}, σ = {std}): {e}")))?;
        Ok(normal.sample(&mut self.rng))
    }
    // ANCHOR_END: take_action_continuous

    /// The mean torque μ(state), for watching a trained agent without noise.
    #[must_use]
    pub fn deterministic_action(&self, state: &[f32; 3]) -> f32 {
        self.acting.mu_std(state).0
    }

    /// Every parameter by PyTorch name (`actor.fc1.weight`, ..., `critic.fc2.bias`).
    ///
    /// # Errors
    /// Only if candle cannot read a tensor.
    pub fn weights(&self) -> Result<NamedWeights, PpoError> {
        let layers = [
            &self.actor.fc1,
            &self.actor.fc_mu,
            &self.actor.fc_std,
            &self.critic.fc1,
            &self.critic.fc2,
        ];
        let vars = layers.iter().flat_map(|l| l.vars());
        let mut out = NamedWeights::new();
        for (name, var) in parameter_names().into_iter().zip(vars) {
            out.insert(name.to_string(), weight_tensor(var)?);
        }
        Ok(out)
    }

    /// The book's `update(transition_dict)`: `epochs` Adam steps of both networks on one
    /// episode, returning every intermediate. Runs on plain `f32` slices or on candle as the
    /// [module doc](self) says; the trace's `path` says which.
    ///
    /// # Errors
    /// [`PpoError::EmptyBatch`] / [`PpoError::InvalidBatch`] for a malformed batch;
    /// [`PpoError::NonFinite`] when a target, advantage or loss is NaN or infinite.
    pub fn update(
        &mut self,
        batch: &ContinuousTransitions,
    ) -> Result<ContinuousUpdateTrace, PpoError> {
        self.update_as(batch, UpdatePath::forced())
    }

    /// `update` with `forced` in place of `PPO_TUTOR_UPDATE`'s setting, so that the tests
    /// choose a path whatever the environment says.
    fn update_as(
        &mut self,
        batch: &ContinuousTransitions,
        forced: Option<UpdatePath>,
    ) -> Result<ContinuousUpdateTrace, PpoError> {
        batch.check()?;
        // the same operations on plain f32 slices where they are candle's (see `plain`)
        let conditions = plain::conditions(&self.config, batch.len());
        if choose_path(&conditions, forced) == UpdatePath::Plain
            && let Some(simd) = isa()
        {
            return plain::update(simd, self, batch);
        }
        self.update_with_tensors(batch)
    }

    /// The update on candle tensors (the code the lessons show), for a checked batch.
    fn update_with_tensors(
        &mut self,
        batch: &ContinuousTransitions,
    ) -> Result<ContinuousUpdateTrace, PpoError> {
        let cfg = &self.config;
        let n = batch.len();
        let dev = &Device::Cpu;
        let flat = |rows: &[[f32; 3]]| rows.iter().flatten().copied().collect::<Vec<f32>>();
        let column = |v: Vec<f32>| Tensor::from_vec(v, (n, 1), dev);
        let states = Tensor::from_vec(flat(&batch.states), (n, STATE_DIM), dev)?;
        let next_states = Tensor::from_vec(flat(&batch.next_states), (n, STATE_DIM), dev)?;
        let actions = column(batch.actions.clone())?;
        let rewards = column(batch.rewards.clone())?;
        let dones = column(
            batch
                .dones
                .iter()
                .map(|&d| f32::from(u8::from(d)))
                .collect(),
        )?;

        // ANCHOR: scaled_rewards
        let scaled_rewards = ((rewards + REWARD_SHIFT)? / REWARD_SCALE)?;
        // ANCHOR_END: scaled_rewards
        // ANCHOR: td_target_continuous
        let next_values = self.critic.forward(&next_states)?.detach();
        // ANCHOR: td_target_continuous_formula
        let td_target = (&scaled_rewards + ((&next_values * cfg.gamma)? * (1.0 - &dones)?)?)?;
        // ANCHOR_END: td_target_continuous_formula
        let values = self.critic.forward(&states)?.detach();
        // ANCHOR: td_delta_continuous_formula
        let td_delta = (&td_target - &values)?;
        // ANCHOR_END: td_delta_continuous_formula
        // ANCHOR_END: td_target_continuous
        let td_delta_vec = to_vec(&td_delta)?;
        let advantage_vec = compute_advantage(cfg.gamma, cfg.lmbda, &td_delta_vec);
        let advantage = column(advantage_vec.clone())?;
        // ANCHOR: old_log_probs_continuous
        let (mu, std) = self.actor.forward(&states)?;
        let (mu, std) = (mu.detach(), std.detach());
        let old_log_probs = log_prob(&actions, &mu, &std)?.detach();
        // ANCHOR_END: old_log_probs_continuous

        let mut trace = ContinuousUpdateTrace {
            states: batch.states.clone(),
            actions: batch.actions.clone(),
            rewards: batch.rewards.clone(),
            next_states: batch.next_states.clone(),
            dones: batch.dones.clone(),
            scaled_rewards: to_vec(&scaled_rewards)?,
            values: to_vec(&values)?,
            next_values: to_vec(&next_values)?,
            td_target: to_vec(&td_target)?,
            td_delta: td_delta_vec,
            advantage: advantage_vec,
            mu: to_vec(&mu)?,
            std: to_vec(&std)?,
            old_log_probs: to_vec(&old_log_probs)?,
            epochs: Vec::with_capacity(cfg.epochs),
            path: UpdatePath::Candle,
        };
        check_finite("td_target", &trace.td_target)?;
        check_finite("advantage", &trace.advantage)?;
        check_finite("old_log_probs", &trace.old_log_probs)?;

        let inputs = EpochInputs {
            states: &states,
            actions: &actions,
            advantage: &advantage,
            old_log_probs: &old_log_probs,
            td_target: &td_target.detach(),
        };
        for _ in 0..self.config.epochs {
            trace.epochs.push(self.epoch(&inputs)?);
        }
        self.acting = ContinuousActorSnapshot::of(&self.actor)?;
        Ok(trace)
    }

    /// One pass over the batch: both losses, then one Adam step of each network.
    fn epoch(&mut self, b: &EpochInputs<'_>) -> Result<ContinuousEpochTrace, PpoError> {
        let eps = self.config.eps;
        // ANCHOR: epoch_continuous
        let (mu, std) = self.actor.forward(b.states)?;
        let log_probs = log_prob(b.actions, &mu, &std)?;
        // ANCHOR: ratio_continuous
        let ratio = (&log_probs - b.old_log_probs)?.exp()?;
        // ANCHOR_END: ratio_continuous
        // ANCHOR: actor_loss_continuous
        let surr1 = (&ratio * b.advantage)?;
        let surr2 = (ratio.clamp(1.0 - eps, 1.0 + eps)? * b.advantage)?;
        let actor_loss = surr1.minimum(&surr2)?.neg()?.mean_all()?;
        // ANCHOR_END: actor_loss_continuous
        // ANCHOR: critic_loss_continuous
        let critic_loss = (self.critic.forward(b.states)? - b.td_target)?
            .sqr()?
            .mean_all()?;
        // ANCHOR_END: critic_loss_continuous
        // ANCHOR_END: epoch_continuous
        let record = ContinuousEpochTrace {
            log_probs: to_vec(&log_probs)?,
            ratio: to_vec(&ratio)?,
            surr1: to_vec(&surr1)?,
            surr2: to_vec(&surr2)?,
            actor_loss: actor_loss.to_scalar::<f32>()?,
            critic_loss: critic_loss.to_scalar::<f32>()?,
        };
        for (name, value) in [
            ("actor_loss", record.actor_loss),
            ("critic_loss", record.critic_loss),
        ] {
            if !value.is_finite() {
                return Err(PpoError::NonFinite(format!("{name} ({value})")));
            }
        }
        self.actor_optimizer.step(&actor_loss.backward()?, None)?;
        self.critic_optimizer.step(&critic_loss.backward()?, None)?;
        Ok(record)
    }
}

/// The tensors every epoch reads, built once per update.
struct EpochInputs<'a> {
    states: &'a Tensor,
    actions: &'a Tensor,
    advantage: &'a Tensor,
    old_log_probs: &'a Tensor,
    td_target: &'a Tensor,
}

fn to_vec(t: &Tensor) -> candle_core::Result<Vec<f32>> {
    t.flatten_all()?.to_dtype(DType::F32)?.to_vec1::<f32>()
}

fn check_finite(name: &str, values: &[f32]) -> Result<(), PpoError> {
    match values.iter().position(|v| !v.is_finite()) {
        Some(t) => Err(PpoError::NonFinite(format!("{name}[{t}] = {}", values[t]))),
        None => Ok(()),
    }
}

fn weight_tensor(var: &Var) -> candle_core::Result<WeightTensor> {
    Ok(WeightTensor {
        shape: var.dims().to_vec(),
        data: var.as_tensor().flatten_all()?.to_vec1::<f32>()?,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_seed_gives_the_same_torques() -> Result<(), PpoError> {
        let config = PpoContinuousConfig::default();
        let state = [0.0_f32, 1.0, -0.5];
        let draw = |seed| -> Result<Vec<f32>, PpoError> {
            let mut agent = PpoContinuous::new(&config, seed)?;
            (0..5).map(|_| agent.take_action(&state)).collect()
        };
        assert_eq!(draw(4)?, draw(4)?);
        assert_ne!(draw(4)?, draw(5)?);
        Ok(())
    }

    /// Many draws in one state have the policy's mean and standard deviation.
    #[test]
    fn samples_follow_the_policy() -> Result<(), PpoError> {
        let mut agent = PpoContinuous::new(&PpoContinuousConfig::default(), 1)?;
        let state = [0.3_f32, -0.95, 2.0];
        let (mu, std) = agent.mu_std(&state);
        let n = 20_000;
        let xs: Vec<f64> = (0..n)
            .map(|_| agent.take_action(&state).map(f64::from))
            .collect::<Result<_, _>>()?;
        let mean = xs.iter().sum::<f64>() / f64::from(n);
        let var = xs.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / f64::from(n - 1);
        let se = f64::from(std) / f64::from(n).sqrt();
        assert!((mean - f64::from(mu)).abs() < 5.0 * se, "{mean} vs {mu}");
        assert!(
            (var.sqrt() / f64::from(std) - 1.0).abs() < 0.03,
            "{var} vs {std}"
        );
        assert_eq!(agent.deterministic_action(&state), mu);
        Ok(())
    }

    #[test]
    fn a_bad_batch_is_refused() -> Result<(), PpoError> {
        let mut agent = PpoContinuous::new(&PpoContinuousConfig::default(), 0)?;
        let err = agent.update(&ContinuousTransitions::default()).err();
        assert!(matches!(err, Some(PpoError::EmptyBatch)));
        let mut batch = ContinuousTransitions::default();
        batch.push([1.0, 0.0, 0.0], f32::NAN, -1.0, [1.0, 0.0, 0.0], false);
        let err = agent.update(&batch).err().map(|e| e.to_string());
        assert!(err.unwrap_or_default().contains("actions[0]"));
        Ok(())
    }

    /// The update moves the policy: after the epochs, the ratio of the last epoch is no
    /// longer 1, and the weights round-trip through [`PpoContinuous::from_weights`].
    #[test]
    fn update_changes_the_policy_and_weights_round_trip() -> Result<(), PpoError> {
        let config = PpoContinuousConfig::default();
        let mut agent = PpoContinuous::new(&config, 3)?;
        let mut batch = ContinuousTransitions::default();
        let mut state = [1.0_f32, 0.0, 0.0];
        for t in 0..20 {
            let a = agent.take_action(&state)?;
            let next = [(t as f32 * 0.1).cos(), (t as f32 * 0.1).sin(), 0.1 * a];
            batch.push(state, a, -(t as f32) * 0.1, next, t == 19);
            state = next;
        }
        let trace = agent.update(&batch)?;
        assert_eq!(trace.epochs.len(), 10);
        assert!(trace.epochs[0].ratio.iter().all(|&r| r == 1.0));
        assert!(trace.epochs[9].ratio.iter().any(|&r| r != 1.0));
        let copy = PpoContinuous::from_weights(&config, &agent.weights()?, 0, "test")?;
        assert_eq!(copy.weights()?, agent.weights()?);
        assert_eq!(copy.mu_std(&state), agent.mu_std(&state));
        Ok(())
    }
}
