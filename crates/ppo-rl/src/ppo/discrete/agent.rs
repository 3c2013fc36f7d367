//! The PPO agent: the seed's `class PPO` with `take_action` and `update`.
//!
//! One update on an episode of `N` transitions (shapes as PyTorch prints them):
//!
//! ```text
//! td_target     = rewards + γ · V(next_states) · (1 - dones)          (N, 1), detached
//! td_delta      = td_target - V(states)                               (N, 1)
//! advantage     = GAE(td_delta)                                       (N, 1), detached
//! old_log_probs = log π_old(actions | states)                         (N, 1), detached
//! repeat epochs times:
//!     log_probs   = log π(actions | states)                           (N, 1)
//!     ratio       = exp(log_probs - old_log_probs)                    (N, 1)
//!     surr1       = ratio · advantage
//!     surr2       = clamp(ratio, 1 - ε, 1 + ε) · advantage
//!     actor_loss  = mean(-min(surr1, surr2))                          scalar
//!     critic_loss = mean((V(states) - td_target)²)                    scalar
//!     one Adam step of each network on its own loss
//! ```
//!
//! `log π` is `log(gather(softmax))` as in the seed (not `log_softmax`), so the numbers
//! match PyTorch's to float rounding.
//!
//! The code below, on candle tensors with autograd, is the update the lessons show
//! ([`UpdatePath::Candle`]). The same IEEE operations in the same order also run on plain
//! `f32` slices (the private module `plain`, whose tests compare both number for number):
//! [`UpdatePath::Plain`], the same trace and weights bit for bit, about ten times faster.
//! [`update_path`](crate::ppo::update_path) states when it runs (the seed's clipped
//! surrogate, its shapes, a CPU with AVX2 and FMA); [`UpdateTrace::path`] records the path
//! that ran, and `PPO_TUTOR_UPDATE=candle` forces candle for every update.
//!
//! ```
//! use ppo_rl::ppo::{Agent, PpoConfig, Transitions};
//!
//! let mut agent = Agent::new(&PpoConfig::default(), 0)?;
//! let state = [0.01_f32, 0.0, -0.02, 0.0];
//! let action = agent.take_action(&state)?;
//! let mut batch = Transitions::default();
//! batch.push(state, action, 1.0, [0.01, 0.2, -0.02, -0.3], false, false);
//! let trace = agent.update(&batch)?;
//! assert_eq!(trace.epochs.len(), 10);
//! assert_eq!(trace.epochs[0].ratio, vec![1.0]); // π = π_old before the first step
//! # Ok::<(), ppo_rl::ppo::PpoError>(())
//! ```

use candle_core::{DType, Device, Tensor, Var};

use super::line_search::{SearchBatch, line_search};
use super::penalty::{adapt_beta, categorical_kl, penalty_actor_loss};
use super::trace::{EarlyStop, EpochTrace, PenaltyTrace, UpdateTrace};
use super::{ACTION_DIM, PpoConfig, STATE_DIM, UpdateRule};
use crate::env::seeding::NumpyRng;
use crate::ppo::PpoError;
use crate::ppo::adam::Adam;
use crate::ppo::advantage::{compute_advantage, normalize_advantage};
use crate::ppo::kernels::isa;
use crate::ppo::model::{ActorSnapshot, Linear, NamedWeights, PolicyNet, ValueNet, WeightTensor};
use crate::ppo::on_policy::check_columns;
use crate::ppo::update_path::{UpdatePath, choose_path};

mod plain;

// ANCHOR: transition_dict
/// One episode's transitions, the seed's `transition_dict`, column by column.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Transitions {
    /// `s_t`.
    pub states: Vec<[f32; 4]>,
    /// `a_t`.
    pub actions: Vec<usize>,
    /// `r_t` (the seed's `torch.tensor(rewards, dtype=torch.float)`).
    pub rewards: Vec<f32>,
    /// `s_{t+1}`.
    pub next_states: Vec<[f32; 4]>,
    /// `terminated or truncated`, the seed's `done`.
    pub dones: Vec<bool>,
    /// `terminated` alone, for the opt-in bootstrap on truncation.
    pub terminated: Vec<bool>,
}

impl Transitions {
    /// Appends one transition, as the seed's five `transition_dict[...].append(...)`.
    pub fn push(
        &mut self,
        state: [f32; 4],
        action: usize,
        reward: f32,
        next_state: [f32; 4],
        done: bool,
        terminated: bool,
    ) {
        self.states.push(state);
        self.actions.push(action);
        self.rewards.push(reward);
        self.next_states.push(next_state);
        self.dones.push(done);
        self.terminated.push(terminated);
    }
}
// ANCHOR_END: transition_dict

impl Transitions {
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
                ("terminated", self.terminated.len()),
            ],
        )?;
        if let Some((t, a)) = self
            .actions
            .iter()
            .enumerate()
            .find(|(_, a)| **a >= ACTION_DIM)
        {
            return Err(PpoError::InvalidBatch(crate::tr!(
                "actions[{t}] = {a}: CartPole's actions are 0 and 1",
                "actions[{t}] = {a}：CartPole 的动作只有 0 和 1"
            )));
        }
        Ok(())
    }
}

/// One epoch's two losses from its tensors, as the seed's loop body computes them:
/// `(probs, actions, old_log_probs, advantage, values, td_target, eps) -> (actor_loss,
/// critic_loss)`, with `probs = π(·|states)` `(N, 2)` and `values = V(states)` `(N, 1)` from
/// the current networks (gradients flow through both), `actions` `(N, 1)` u32, the other
/// columns `(N, 1)` f32 and both losses scalars. [`Agent::update_with`] takes one.
pub type Losses<'a> = dyn Fn(
        &Tensor,
        &Tensor,
        &Tensor,
        &Tensor,
        &Tensor,
        &Tensor,
        f64,
    ) -> candle_core::Result<(Tensor, Tensor)>
    + 'a;

/// The seed's `PPO`: actor, critic, their optimizers, and a seeded sampler.
#[derive(Debug, Clone)]
pub struct Agent {
    config: PpoConfig,
    /// The update rule the config names, built once ([`PpoConfig::rule`]).
    rule: UpdateRule,
    actor: PolicyNet,
    critic: ValueNet,
    actor_optimizer: Adam,
    critic_optimizer: Adam,
    rng: NumpyRng,
    acting: ActorSnapshot,
    /// Buffers of the update without tensors ([`plain`]), boxed to keep the agent small.
    plain: Box<plain::Workspace>,
    /// PPO-Penalty's β for the next update (`beta_init` at first; unused with the clip).
    beta: f64,
}

impl Agent {
    /// A fresh agent: networks initialised from `seed` (actor first), then actions sampled
    /// from the same generator.
    ///
    /// # Errors
    /// [`PpoError::InvalidConfig`] for a hyper-parameter out of range.
    pub fn new(config: &PpoConfig, seed: u64) -> Result<Self, PpoError> {
        config.validate()?;
        let mut rng = NumpyRng::from_seed(seed);
        let actor = PolicyNet::new(STATE_DIM, config.hidden_dim, ACTION_DIM, &mut rng)?;
        let critic = ValueNet::new(STATE_DIM, config.hidden_dim, &mut rng)?;
        Self::assemble(config, actor, critic, rng)
    }

    /// An agent holding `weights` (PyTorch names, see [`Agent::weights`]), with fresh Adam
    /// state and a sampler seeded by `seed`. `source` names where the weights came from in
    /// error messages.
    ///
    /// # Errors
    /// [`PpoError::MissingKey`] / [`PpoError::WrongShape`] naming the tensor and the shape
    /// `config.hidden_dim` requires; [`PpoError::InvalidConfig`].
    pub fn from_weights(
        config: &PpoConfig,
        weights: &NamedWeights,
        seed: u64,
        source: &str,
    ) -> Result<Self, PpoError> {
        config.validate()?;
        super::checkpoint::check_weights(weights, config.hidden_dim, source)?;
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
        let actor = PolicyNet {
            fc1: layer("actor.fc1", STATE_DIM, h)?,
            fc2: layer("actor.fc2", h, ACTION_DIM)?,
        };
        let critic = ValueNet {
            fc1: layer("critic.fc1", STATE_DIM, h)?,
            fc2: layer("critic.fc2", h, 1)?,
        };
        Self::assemble(config, actor, critic, NumpyRng::from_seed(seed))
    }

    fn assemble(
        config: &PpoConfig,
        actor: PolicyNet,
        critic: ValueNet,
        rng: NumpyRng,
    ) -> Result<Self, PpoError> {
        // ANCHOR: optimizers
        let actor_params = vec![
            actor.fc1.weight.clone(),
            actor.fc1.bias.clone(),
            actor.fc2.weight.clone(),
            actor.fc2.bias.clone(),
        ];
        let critic_params = vec![
            critic.fc1.weight.clone(),
            critic.fc1.bias.clone(),
            critic.fc2.weight.clone(),
            critic.fc2.bias.clone(),
        ];
        let actor_optimizer = Adam::new(actor_params, config.actor_lr);
        let critic_optimizer = Adam::new(critic_params, config.critic_lr);
        // ANCHOR_END: optimizers
        let acting = ActorSnapshot::of(&actor)?;
        // `validate` refused a clash already; this names it again for a caller that skipped it
        let rule = config.rule().map_err(|clash| PpoError::InvalidConfig {
            field: clash.with.field(),
            value: clash.with.value().into(),
            expected: clash.expected(),
        })?;
        keep_freed_memory();
        Ok(Self {
            config: config.clone(),
            rule,
            actor,
            critic,
            actor_optimizer,
            critic_optimizer,
            rng,
            acting,
            plain: Box::default(),
            beta: config.beta_init,
        })
    }

    /// PPO-Penalty's β for the next update: `beta_init` before the first, then as
    /// [`adapt_beta`] left it ([`PenaltyTrace`] records each change). Not saved in
    /// checkpoints (they hold the weights only, and Adam starts fresh too).
    #[must_use]
    pub fn beta(&self) -> f64 {
        self.beta
    }

    /// Sets PPO-Penalty's β for the next update (a replay starts from the recorded β).
    ///
    /// # Errors
    /// [`PpoError::InvalidConfig`] for a β that is not a finite number > 0.
    pub fn set_beta(&mut self, beta: f64) -> Result<(), PpoError> {
        crate::ppo::ranges::positive("beta", beta)?;
        self.beta = beta;
        Ok(())
    }

    /// The hyper-parameters.
    #[must_use]
    pub fn config(&self) -> &PpoConfig {
        &self.config
    }

    /// The actor network (candle).
    #[must_use]
    pub fn actor(&self) -> &PolicyNet {
        &self.actor
    }

    /// The critic network (candle).
    #[must_use]
    pub fn critic(&self) -> &ValueNet {
        &self.critic
    }

    /// `π(·|state)`: the action probabilities for one observation.
    #[must_use]
    pub fn probs(&self, state: &[f32; 4]) -> Vec<f32> {
        self.acting.probs(state)
    }

    /// `V(state)` for one observation.
    ///
    /// # Errors
    /// Only if a candle operation fails.
    pub fn value(&self, state: &[f32; 4]) -> Result<f32, PpoError> {
        let s = Tensor::from_slice(state, (1, STATE_DIM), &Device::Cpu)?;
        Ok(self.critic.forward(&s)?.flatten_all()?.to_vec1::<f32>()?[0])
    }

    // ANCHOR: take_action
    /// Samples `a ~ Categorical(π(·|state))` with the agent's seeded generator, as the seed's
    /// `torch.distributions.Categorical(probs).sample()`.
    ///
    /// # Errors
    /// [`PpoError::NonFinite`] when the probabilities are NaN (a diverged actor).
    pub fn take_action(&mut self, state: &[f32; 4]) -> Result<usize, PpoError> {
        let probs = self.acting.probs(state);
        if probs.iter().any(|p| !p.is_finite()) {
            return Err(PpoError::NonFinite(format!(
                "action probabilities {probs:?}"
            )));
        }
        // ANCHOR: categorical_sample
        let u = self.rng.next_f64() * probs.iter().map(|&p| f64::from(p)).sum::<f64>();
        let mut cumulative = 0.0;
        for (action, &p) in probs.iter().enumerate() {
            cumulative += f64::from(p);
            if u < cumulative {
                return Ok(action);
            }
        }
        Ok(probs.len() - 1)
        // ANCHOR_END: categorical_sample
    }
    // ANCHOR_END: take_action

    /// The most probable action (ties go to the lower index), for watching a trained agent.
    #[must_use]
    pub fn greedy_action(&self, state: &[f32; 4]) -> usize {
        let probs = self.acting.probs(state);
        let best = probs
            .iter()
            .enumerate()
            .fold((0, f32::NEG_INFINITY), |best, (a, &p)| {
                if p > best.1 { (a, p) } else { best }
            });
        best.0
    }

    /// Every parameter by PyTorch name, as plain data.
    ///
    /// # Errors
    /// Only if candle cannot read a tensor.
    pub fn weights(&self) -> Result<NamedWeights, PpoError> {
        let mut out = NamedWeights::new();
        let layers = [
            ("actor.fc1", &self.actor.fc1),
            ("actor.fc2", &self.actor.fc2),
            ("critic.fc1", &self.critic.fc1),
            ("critic.fc2", &self.critic.fc2),
        ];
        for (prefix, layer) in layers {
            for (name, var) in [("weight", &layer.weight), ("bias", &layer.bias)] {
                out.insert(format!("{prefix}.{name}"), weight_tensor(var)?);
            }
        }
        Ok(out)
    }

    /// The seed's `update(transition_dict)`: `epochs` Adam steps of both networks on one
    /// episode, returning every intermediate. Runs on plain `f32` slices or on candle as the
    /// [module doc](self) says; the trace's `path` says which.
    ///
    /// # Errors
    /// [`PpoError::EmptyBatch`] / [`PpoError::InvalidBatch`] for a malformed batch;
    /// [`PpoError::NonFinite`] when a target, advantage or loss is NaN or infinite.
    pub fn update(&mut self, batch: &Transitions) -> Result<UpdateTrace, PpoError> {
        self.run_update(batch, None)
    }

    /// [`Agent::update`] with the two losses of every epoch computed by `losses` instead of
    /// the built-in lines (the `ppo_losses` exercise plugs a learner's function in here).
    /// Everything else is the same: the targets, the advantage, the opt-in entropy bonus
    /// (added to the returned actor loss) and the Adam steps; the trace records the
    /// returned losses. Always on candle, whose autograd differentiates `losses`.
    ///
    /// # Errors
    /// As [`Agent::update`], plus [`PpoError::Candle`] carrying an error `losses` returned.
    pub fn update_with(
        &mut self,
        batch: &Transitions,
        losses: &Losses<'_>,
    ) -> Result<UpdateTrace, PpoError> {
        self.run_update(batch, Some(losses))
    }

    fn run_update(
        &mut self,
        batch: &Transitions,
        losses: Option<&Losses<'_>>,
    ) -> Result<UpdateTrace, PpoError> {
        self.run_update_as(batch, losses, UpdatePath::forced())
    }

    /// `run_update` with `forced` in place of `PPO_TUTOR_UPDATE`'s setting, so that
    /// the tests choose a path whatever the environment says.
    fn run_update_as(
        &mut self,
        batch: &Transitions,
        losses: Option<&Losses<'_>>,
        forced: Option<UpdatePath>,
    ) -> Result<UpdateTrace, PpoError> {
        batch.check()?;
        // The seed's configuration runs without tensors, with the same float operations
        // (bit for bit the numbers of `update_with_tensors`; see `plain`).
        let conditions = plain::conditions(&self.config, batch.len(), losses.is_some());
        let before = self.acting.clone(); // π_old, for the KL every objective reports
        let mut trace = if choose_path(&conditions, forced) == UpdatePath::Plain
            && let Some(simd) = isa()
        {
            plain::update(simd, self, batch)?
        } else {
            self.update_with_tensors(batch, losses)?
        };
        trace.kl_after = Some(mean_kl(&before, &self.acting, &batch.states));
        Ok(trace)
    }

    /// The update on candle tensors (the code the lessons show), for a checked batch.
    fn update_with_tensors(
        &mut self,
        batch: &Transitions,
        losses: Option<&Losses<'_>>,
    ) -> Result<UpdateTrace, PpoError> {
        let cfg = &self.config;
        let n = batch.len();
        let dev = &Device::Cpu;
        let flat = |rows: &[[f32; 4]]| rows.iter().flatten().copied().collect::<Vec<f32>>();
        let column = |v: Vec<f32>| Tensor::from_vec(v, (n, 1), dev);
        let states = Tensor::from_vec(flat(&batch.states), (n, STATE_DIM), dev)?;
        let next_states = Tensor::from_vec(flat(&batch.next_states), (n, STATE_DIM), dev)?;
        let actions = Tensor::from_vec(
            batch
                .actions
                .iter()
                .map(|&a| a as u32)
                .collect::<Vec<u32>>(),
            (n, 1),
            dev,
        )?;
        let rewards = column(batch.rewards.clone())?;
        // ANCHOR: truncation_switch
        let done_flags = if cfg.bootstrap_on_truncation {
            &batch.terminated // a time-limit cut is not an end: bootstrap from V(s')
        } else {
            &batch.dones // the seed: terminated or truncated
        };
        // ANCHOR_END: truncation_switch
        let dones = column(done_flags.iter().map(|&d| f32::from(u8::from(d))).collect())?;

        // ANCHOR: td_target
        let next_values = self.critic.forward(&next_states)?.detach();
        // ANCHOR: td_target_formula
        let td_target = (&rewards + ((&next_values * cfg.gamma)? * (1.0 - &dones)?)?)?;
        // ANCHOR_END: td_target_formula
        // ANCHOR_END: td_target
        // ANCHOR: td_delta
        let values = self.critic.forward(&states)?.detach();
        // ANCHOR: td_delta_formula
        let td_delta = (&td_target - &values)?;
        // ANCHOR_END: td_delta_formula
        // ANCHOR_END: td_delta
        let td_delta_vec = to_vec(&td_delta)?;
        let values_vec = to_vec(&values)?;
        // ANCHOR: reinforce_targets
        let reinforce = self.rule == UpdateRule::Reinforce;
        // REINFORCE: λ = 1 sums the whole rest of the episode, Â_t = G_t − V(s_t)
        let lmbda = if reinforce { 1.0 } else { cfg.lmbda };
        let mut advantage_vec = compute_advantage(cfg.gamma, lmbda, &td_delta_vec);
        // the λ-return Â_t + V(s_t): G_t itself when λ = 1
        let lambda_return: Vec<f32> = advantage_vec
            .iter()
            .zip(&values_vec)
            .map(|(a, v)| a + v)
            .collect();
        let critic_target = if reinforce {
            column(lambda_return.clone())? // fit V(s_t) to the Monte-Carlo return
        } else {
            td_target.detach() // the seed: the one-step TD target
        };
        // ANCHOR_END: reinforce_targets
        if cfg.normalize_advantage {
            advantage_vec = normalize_advantage(&advantage_vec);
        }
        let advantage = column(advantage_vec.clone())?;
        // ANCHOR: old_log_probs
        let old_log_probs = self
            .actor
            .forward(&states)?
            .gather(&actions, 1)?
            .log()?
            .detach();
        // ANCHOR_END: old_log_probs
        // PPO-Penalty's π_old(·|s), held fixed like old_log_probs (the KL's first argument)
        let old_probs = match self.rule {
            UpdateRule::Penalty => Some(self.actor.forward(&states)?.detach()),
            _ => None,
        };
        // The KL line search's π_old(·|s): the KL it bounds, not a loss term
        let search_old_probs = if self.rule == UpdateRule::LineSearch {
            Some(self.actor.forward(&states)?.detach())
        } else {
            None
        };

        let mut trace = UpdateTrace {
            states: batch.states.clone(),
            actions: batch.actions.clone(),
            rewards: batch.rewards.clone(),
            next_states: batch.next_states.clone(),
            dones: done_flags.clone(),
            values: values_vec,
            next_values: to_vec(&next_values)?,
            td_target: to_vec(&td_target)?,
            td_delta: td_delta_vec,
            advantage: advantage_vec,
            lambda_return,
            old_log_probs: to_vec(&old_log_probs)?,
            epochs: Vec::with_capacity(cfg.epochs),
            early_stop: None,
            explained_variance: None,
            path: UpdatePath::Candle,
            penalty: None,
            line_search: None,
            kl_after: None,
        };
        check_batch(&mut trace)?;
        // The KL line search: one actor step, no Adam for the actor (its epochs below step
        // only the critic)
        if let Some(old_probs) = &search_old_probs {
            let search = SearchBatch {
                states: &states,
                actions: &actions,
                old_log_probs: &old_log_probs,
                old_probs,
                advantage: &advantage,
            };
            trace.line_search = Some(line_search(&self.actor, &search, &self.config)?);
        }

        let batch = EpochInputs {
            states: &states,
            actions: &actions,
            advantage: &advantage,
            old_log_probs: &old_log_probs,
            old_log_probs_vec: &trace.old_log_probs,
            old_probs: old_probs.as_ref(),
            critic_target: &critic_target,
            losses,
        };
        // Both networks step `epochs` times (the seed); with `critic_epochs` set, the network
        // with more steps takes its extra ones after these, alone.
        let (actor_epochs, critic_epochs) = self.config.epochs_of_each();
        // after the line search's step the actor has no epochs left: the critic steps alone
        let actor_epochs = if self.rule == UpdateRule::LineSearch {
            0
        } else {
            actor_epochs
        };
        let epochs = actor_epochs.min(critic_epochs);
        // ANCHOR: epochs
        for k in 0..epochs {
            match self.epoch(&batch)? {
                Epoch::Stepped(epoch) => trace.epochs.push(epoch),
                Epoch::Stopped { approx_kl } => {
                    trace.early_stop = Some(EarlyStop {
                        epoch: k + 1,
                        approx_kl,
                    });
                    break;
                }
            }
        }
        // ANCHOR_END: epochs
        let alone = if actor_epochs > critic_epochs {
            Network::Actor
        } else {
            Network::Critic
        };
        let extra = if trace.early_stop.is_none() {
            epochs..actor_epochs.max(critic_epochs)
        } else {
            0..0
        };
        for k in extra {
            match self.epoch_of(&batch, alone)? {
                Epoch::Stepped(epoch) => trace.epochs.push(epoch),
                Epoch::Stopped { approx_kl } => {
                    trace.early_stop = Some(EarlyStop {
                        epoch: k + 1,
                        approx_kl,
                    });
                    break;
                }
            }
        }
        if let Some(old_probs) = &old_probs {
            trace.penalty = Some(self.adapt_beta(old_probs, &states)?);
        }
        self.acting = ActorSnapshot::of(&self.actor)?;
        Ok(trace)
    }

    /// PPO-Penalty after the update's last epoch: `d`, the mean exact KL under the updated
    /// actor, moves β for the next update ([`adapt_beta`]).
    ///
    /// # Errors
    /// [`PpoError::NonFinite`] when `d` is NaN or infinite (β is then left as it was).
    fn adapt_beta(
        &mut self,
        old_probs: &Tensor,
        states: &Tensor,
    ) -> Result<PenaltyTrace, PpoError> {
        let probs = self.actor.forward(states)?.detach();
        let kl_after = categorical_kl(old_probs, &probs)?
            .mean_all()?
            .to_scalar::<f32>()?;
        if !kl_after.is_finite() {
            return Err(PpoError::NonFinite(crate::tr!(
                "the KL after the update ({kl_after})",
                "更新后的 KL（{kl_after}）"
            )));
        }
        let beta_before = self.beta;
        self.beta = adapt_beta(beta_before, f64::from(kl_after), self.config.kl_delta);
        Ok(PenaltyTrace {
            beta_before,
            kl_after,
            beta_after: self.beta,
        })
    }

    /// One pass over the batch that steps only `network`: the other one has taken all its
    /// epochs (`critic_epochs` differs from the actor's). The actor and the critic share no
    /// weights and each epoch's inputs are fixed before the first, so taking the extra steps
    /// after the shared ones gives the same networks as interleaving them.
    fn epoch_of(&mut self, b: &EpochInputs<'_>, network: Network) -> Result<Epoch, PpoError> {
        let (record, actor_loss, critic_loss) = match self.epoch_losses(b)? {
            EpochLosses::Stopped { approx_kl } => return Ok(Epoch::Stopped { approx_kl }),
            EpochLosses::Computed(c) => (c.record, c.actor_loss, c.critic_loss),
        };
        let max_norm = self.config.max_grad_norm;
        match network {
            Network::Actor => self
                .actor_optimizer
                .step(&actor_loss.backward()?, max_norm)?,
            Network::Critic => self
                .critic_optimizer
                .step(&critic_loss.backward()?, max_norm)?,
        }
        Ok(Epoch::Stepped(record))
    }

    /// One pass over the batch: both losses, then one Adam step of each network; or, with
    /// `target_kl`, no step when the policy has already moved too far.
    fn epoch(&mut self, b: &EpochInputs<'_>) -> Result<Epoch, PpoError> {
        let (record, actor_loss, critic_loss) = match self.epoch_losses(b)? {
            EpochLosses::Stopped { approx_kl } => return Ok(Epoch::Stopped { approx_kl }),
            EpochLosses::Computed(c) => (c.record, c.actor_loss, c.critic_loss),
        };
        // ANCHOR: backprop
        let max_norm = self.config.max_grad_norm;
        self.actor_optimizer
            .step(&actor_loss.backward()?, max_norm)?;
        self.critic_optimizer
            .step(&critic_loss.backward()?, max_norm)?;
        // ANCHOR_END: backprop
        Ok(Epoch::Stepped(record))
    }

    /// One epoch's losses and record, before any step; `Stopped` when `target_kl` ends the
    /// update here.
    fn epoch_losses(&self, b: &EpochInputs<'_>) -> Result<EpochLosses, PpoError> {
        let eps = self.config.eps;
        let probs = self.actor.forward(b.states)?;
        let log_probs = probs.gather(b.actions, 1)?.log()?;
        // ANCHOR: ratio
        let ratio = (&log_probs - b.old_log_probs)?.exp()?;
        // ANCHOR_END: ratio
        let ratio_vec = to_vec(&ratio)?;
        let log_probs_vec = to_vec(&log_probs)?;
        let approx_kl = mean(
            ratio_vec
                .iter()
                .zip(&log_probs_vec)
                .zip(b.old_log_probs_vec)
                .map(|((r, lp), old)| (r - 1.0) - (lp - old)),
        );
        if let Some(target) = self.config.target_kl
            && f64::from(approx_kl) > 1.5 * target
        {
            return Ok(EpochLosses::Stopped { approx_kl });
        }
        // ANCHOR: surrogate
        let surr1 = (&ratio * b.advantage)?;
        let surr2 = (ratio.clamp(1.0 - eps, 1.0 + eps)? * b.advantage)?;
        // ANCHOR_END: surrogate
        // -Σ π log π, with π floored so that an underflowed probability counts 0, not NaN
        let log_probs_all = probs.clamp(f32::MIN_POSITIVE, 1.0)?.log()?;
        let entropy = (&probs * log_probs_all)?.sum(1)?.neg()?.mean_all()?;
        // ANCHOR: actor_loss
        // PPO-Penalty's KL(π_old ‖ π_θ), the term that stands in for the clip
        let kl = match b.old_probs {
            Some(old_probs) => Some(categorical_kl(old_probs, &probs)?),
            None => None,
        };
        let objective = match self.rule {
            // ANCHOR: clipped_objective
            UpdateRule::Clip => surr1.minimum(&surr2)?, // the seed
            // ANCHOR_END: clipped_objective
            UpdateRule::NoClip => surr1.clone(), // no clip: ratio · Â
            UpdateRule::Reinforce => (&log_probs * b.advantage)?, // log π · Â
            // PPO-Penalty: −mean(ratio · Â) + β · mean(KL), a KL term in place of the clip
            UpdateRule::Penalty => match &kl {
                Some(kl) => penalty_actor_loss(&surr1, kl, self.beta)?,
                None => return Err(PpoError::InvalidBatch("PPO-Penalty needs π_old".into())),
            },
            // the KL line search takes no Adam step: its record is the surrogate it
            // climbed, −mean(ratio · Â), at the accepted θ
            UpdateRule::LineSearch => surr1.mean_all()?.neg()?,
        };
        // ANCHOR: actor_loss_mean
        let mut actor_loss = match self.rule {
            UpdateRule::Penalty | UpdateRule::LineSearch => objective, // already a loss
            _ => objective.neg()?.mean_all()?,
        };
        // ANCHOR_END: actor_loss_mean
        if self.config.entropy_coef > 0.0 {
            actor_loss = (actor_loss - (&entropy * self.config.entropy_coef)?)?;
        }
        // ANCHOR_END: actor_loss
        // ANCHOR: critic_loss
        let critic_loss = (self.critic.forward(b.states)? - b.critic_target)?
            .sqr()?
            .mean_all()?;
        // ANCHOR_END: critic_loss
        let (actor_loss, critic_loss) = match b.losses {
            None => (actor_loss, critic_loss),
            Some(losses) => {
                let values = self.critic.forward(b.states)?;
                let (actor_loss, critic_loss) = losses(
                    &probs,
                    b.actions,
                    b.old_log_probs,
                    b.advantage,
                    &values,
                    b.critic_target,
                    eps,
                )?;
                let actor_loss = if self.config.entropy_coef > 0.0 {
                    (actor_loss - (&entropy * self.config.entropy_coef)?)?
                } else {
                    actor_loss
                };
                (actor_loss, critic_loss)
            }
        };

        let record = EpochTrace {
            clipped: ratio_vec
                .iter()
                .map(|r| (r - 1.0).abs() > eps as f32)
                .collect(),
            approx_kl,
            clip_fraction: 0.0,
            actor_loss: actor_loss.to_scalar::<f32>()?,
            critic_loss: critic_loss.to_scalar::<f32>()?,
            entropy: entropy.to_scalar::<f32>()?,
            surr1: to_vec(&surr1)?,
            surr2: to_vec(&surr2)?,
            log_probs: log_probs_vec,
            ratio: ratio_vec,
            kl: kl.as_ref().map(to_vec).transpose()?.unwrap_or_default(),
            kl_mean: match &kl {
                Some(kl) => Some(kl.mean_all()?.to_scalar::<f32>()?),
                None => None,
            },
        };
        let record = EpochTrace {
            clip_fraction: mean(record.clipped.iter().map(|&c| f32::from(u8::from(c)))),
            ..record
        };
        for (name, value) in [
            ("actor_loss", record.actor_loss),
            ("critic_loss", record.critic_loss),
        ] {
            if !value.is_finite() {
                return Err(PpoError::NonFinite(format!("{name} ({value})")));
            }
        }
        Ok(EpochLosses::Computed(Computed {
            record,
            actor_loss,
            critic_loss,
        }))
    }
}

/// Which network an epoch steps alone ([`Agent::epoch_of`]).
#[derive(Debug, Clone, Copy)]
enum Network {
    Actor,
    Critic,
}

/// An epoch's losses, computed before any step.
enum EpochLosses {
    /// The two losses to differentiate, and the epoch's record.
    Computed(Computed),
    /// `target_kl`: the policy had moved too far, so no step (the update ends).
    Stopped {
        /// The `approx_kl` that was too large.
        approx_kl: f32,
    },
}

/// [`EpochLosses::Computed`]'s contents.
struct Computed {
    record: EpochTrace,
    actor_loss: Tensor,
    critic_loss: Tensor,
}

/// What one epoch did.
enum Epoch {
    /// Computed both losses and stepped both networks.
    Stepped(EpochTrace),
    /// `target_kl`: the policy had moved too far, so no step (the update ends).
    Stopped {
        /// The `approx_kl` that was too large.
        approx_kl: f32,
    },
}

/// `1 − Var[y − v] / Var[y]` (population variances, as `np.var`), `None` when `y` does not
/// vary.
fn explained_variance(y: &[f32], v: &[f32]) -> Option<f32> {
    let var = |xs: &[f64]| {
        let m = xs.iter().sum::<f64>() / xs.len() as f64;
        xs.iter().map(|x| (x - m).powi(2)).sum::<f64>() / xs.len() as f64
    };
    let ys: Vec<f64> = y.iter().map(|&x| f64::from(x)).collect();
    let residual: Vec<f64> = y
        .iter()
        .zip(v)
        .map(|(&a, &b)| f64::from(a) - f64::from(b))
        .collect();
    let var_y = var(&ys);
    (!ys.is_empty() && var_y > 0.0).then(|| (1.0 - var(&residual) / var_y) as f32)
}

/// Asks glibc's allocator to keep freed memory instead of returning it to the OS at once.
///
/// Each update allocates and frees dozens of `(N, 128)` tensors (~250 KB). By default glibc
/// gives the top of the heap back to the OS when more than 128 KB is free there, so every
/// epoch faults the same pages in again: this tripled training time (measured 17 s vs 5 s).
/// Freeing one 16 MB block raises glibc's dynamic mmap and trim thresholds (to 16 and 32 MB)
/// for the rest of the process; other allocators ignore it. Safe Rust, done once.
fn keep_freed_memory() {
    static ONCE: std::sync::Once = std::sync::Once::new();
    ONCE.call_once(|| drop(std::hint::black_box(vec![0_u8; 16 << 20])));
}

/// The tensors every epoch reads, built once per update.
struct EpochInputs<'a> {
    states: &'a Tensor,
    actions: &'a Tensor,
    advantage: &'a Tensor,
    old_log_probs: &'a Tensor,
    old_log_probs_vec: &'a [f32],
    /// What the critic is fitted to: the TD target (PPO) or the return (REINFORCE).
    critic_target: &'a Tensor,
    /// PPO-Penalty's `π_old(·|s)` `(N, 2)`, `None` for the clip and REINFORCE.
    old_probs: Option<&'a Tensor>,
    /// A learner's losses in place of the built-in ones ([`Agent::update_with`]).
    losses: Option<&'a Losses<'a>>,
}

/// The mean over `states` of the exact `KL(π_before(·|s) ‖ π_after(·|s))`, computed in
/// `f64` from the two acting snapshots' probabilities (a probability of 0 under `before`
/// contributes 0; one of 0 under `after` alone makes the KL infinite).
fn mean_kl(before: &ActorSnapshot, after: &ActorSnapshot, states: &[[f32; 4]]) -> f32 {
    if states.is_empty() {
        return 0.0;
    }
    let probs = |snap: &ActorSnapshot, s: &[f32; 4]| match snap.probs2(s) {
        Some(p) => p.to_vec(),
        None => snap.probs(s),
    };
    let total: f64 = states
        .iter()
        .map(|s| {
            let (p, q) = (probs(before, s), probs(after, s));
            p.iter()
                .zip(&q)
                .filter(|(p, _)| **p > 0.0)
                .map(|(&p, &q)| {
                    let (p, q) = (f64::from(p), f64::from(q));
                    p * (p.ln() - q.ln())
                })
                .sum::<f64>()
        })
        .sum();
    (total / states.len() as f64) as f32
}

fn to_vec(t: &Tensor) -> candle_core::Result<Vec<f32>> {
    t.flatten_all()?.to_dtype(DType::F32)?.to_vec1::<f32>()
}

fn mean(xs: impl Iterator<Item = f32>) -> f32 {
    let (sum, n) = xs.fold((0.0_f32, 0_usize), |(s, n), x| (s + x, n + 1));
    if n == 0 { 0.0 } else { sum / n as f32 }
}

/// The batch half of an update's trace, before any epoch: the critic's explained variance,
/// and the check that targets, advantages and old log-probs are finite (both update paths).
///
/// # Errors
/// [`PpoError::NonFinite`] naming the first non-finite column.
fn check_batch(trace: &mut UpdateTrace) -> Result<(), PpoError> {
    trace.explained_variance = explained_variance(&trace.td_target, &trace.values);
    check_finite("td_target", &trace.td_target)?;
    check_finite("advantage", &trace.advantage)?;
    check_finite("old_log_probs", &trace.old_log_probs)
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
