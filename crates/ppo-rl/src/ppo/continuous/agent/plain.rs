//! The book's `PPOContinuous` update on plain `f32` slices: candle's float operations, one
//! for one.
//!
//! [`PpoContinuous::update`] is written with candle tensors and autograd (the lessons show
//! that code). For batches of 3 to 512 transitions and hidden layers of 2 to 512 units
//! (more than 256 hidden-layer entries), on x86-64 with AVX2 and FMA, and unless
//! `PPO_TUTOR_UPDATE=candle`, it runs this module instead ([`UpdatePath::Plain`]; see
//! [`conditions`] and [`update_path`](crate::ppo::update_path)), which performs the very same IEEE
//! operations in the same order, so that every number (targets, log-probabilities, ratios,
//! losses, gradients, weights) is bit for bit the tensor version's, only without building
//! some 200 tensors per epoch. The matrix products and sums are the discrete agent's
//! kernels ([`kernels`](crate::ppo::kernels), whose summation orders the discrete
//! `plain` module documents) with 3 inputs instead of 4; what is new here is the Gaussian
//! head and its backward pass, in the order candle's backward visits the graph:
//!
//! ```text
//! forward, per row                       backward, per row (g = ∂loss/∂log_prob)
//! t      = tanh(z_μ)                      g_t = 0 + (g · 1 + 0)                   affine
//! μ      = t · 2 + 0          affine      g_σ = 0 + (-g_t) / σ                    log, first
//! σ      = softplus(z_σ)                  g_var2 = 0 - (g_t · nse) / (var2 · var2)  div
//! var2   = σ² · 2 + 0         affine      g_σ += (σ · (0 + (g_var2 · 2 + 0))) · 2 + 0  sqr
//! nse    = -((a - μ)²)                    g_z_σ = 0 + g_σ · eᶻ / (eᶻ + 1)         softplus
//! lp     = (nse / var2 - log σ) · 1 + (-log √2π)
//!                                         g_μ = 0 - (0 + ((a - μ) · -(0 + g_t / var2)) · 2 + 0)
//!                                         g_z_μ = 0 - (0 + (g_μ · 2 + 0)) · (t · t · 1 + -1)
//! hidden's gradient: (0 + g_z_σ · w_σ) + g_z_μ · w_μ   (the σ head's product is visited first)
//! ```
//!
//! Its tests compare both versions, number for number, on batch sizes on either side of
//! every switch of gemm's paths, with other widths and epochs; on a CPU without AVX2 and FMA
//! they print `SKIPPED` instead of comparing candle with candle.

use super::{ContinuousTransitions, PpoContinuous, check_finite};
use crate::ppo::PpoError;
use crate::ppo::advantage::compute_advantage;
use crate::ppo::continuous::model::{
    ContinuousActorSnapshot, PolicyNetContinuous, SOFTPLUS_THRESHOLD, softplus_f32,
};
use crate::ppo::continuous::normal::LOG_SQRT_2PI;
use crate::ppo::continuous::trace::{ContinuousEpochTrace, ContinuousUpdateTrace};
use crate::ppo::continuous::{PpoContinuousConfig, REWARD_SCALE, REWARD_SHIFT, STATE_DIM};
use crate::ppo::kernels::{
    CriticKernels, Grads, Isa, Params, Scratch, Surrogate, critic_loss, fc1_backward_row,
    hidden_columns, hidden_layer, input_columns, isa, kernel, output_column, store_columns, take,
    vec_sum,
};
use crate::ppo::update_path::{PathConditions, UpdatePath};

use candle_core::{Device, Tensor};

/// What decides whether this module computes the update of an agent configured by
/// `config` on a batch of `rows` transitions: the shapes and the CPU (the losses are always
/// the book's clipped surrogate and critic loss); see
/// [`choose_path`](crate::ppo::update_path::choose_path).
pub(super) fn conditions(config: &PpoContinuousConfig, rows: usize) -> PathConditions {
    PathConditions {
        learner_losses: false,
        clipped_surrogate: true,
        entropy_bonus: false,
        rows,
        hidden: config.hidden_dim,
        avx2_fma: isa().is_some(),
    }
}

/// Runs the update on a checked batch; the kernels run under `simd`.
pub(super) fn update(
    simd: Isa,
    agent: &mut PpoContinuous,
    batch: &ContinuousTransitions,
) -> Result<ContinuousUpdateTrace, PpoError> {
    let mut actor = read_actor(&agent.actor)?;
    let mut critic = Params::read(&agent.critic.fc1, &agent.critic.fc2)?;
    let result = epochs(Kernels(simd), agent, batch, &mut actor, &mut critic);
    // stored also after an error, as the tensor version has stepped its variables by then
    write_actor(&actor, &agent.actor)?;
    critic.write(&agent.critic.fc1, &agent.critic.fc2)?;
    if result.is_ok() {
        agent.acting = ContinuousActorSnapshot::of(&agent.actor)?;
    }
    result
}

/// The actor as one [`Params`]: `fc1`, then the two heads stacked as the rows of `w2`
/// (`fc_mu.weight` then `fc_std.weight`) and `b2` (`[fc_mu.bias, fc_std.bias]`).
fn read_actor(actor: &PolicyNetContinuous) -> candle_core::Result<Params> {
    let flat = |t: &Tensor| t.flatten_all()?.to_vec1::<f32>();
    let mut w2 = flat(actor.fc_mu.weight.as_tensor())?;
    w2.extend(flat(actor.fc_std.weight.as_tensor())?);
    let mut b2 = flat(actor.fc_mu.bias.as_tensor())?;
    b2.extend(flat(actor.fc_std.bias.as_tensor())?);
    Ok(Params {
        w1: flat(actor.fc1.weight.as_tensor())?,
        b1: flat(actor.fc1.bias.as_tensor())?,
        w2,
        b2,
    })
}

/// Stores [`read_actor`]'s layout back into the actor's variables.
fn write_actor(params: &Params, actor: &PolicyNetContinuous) -> candle_core::Result<()> {
    let h = params.b1.len();
    let (w_mu, w_std) = params.w2.split_at(h);
    let (b_mu, b_std) = params.b2.split_at(1);
    let dev = &Device::Cpu;
    for (var, data) in [
        (&actor.fc1.weight, &params.w1[..]),
        (&actor.fc1.bias, &params.b1[..]),
        (&actor.fc_mu.weight, w_mu),
        (&actor.fc_mu.bias, b_mu),
        (&actor.fc_std.weight, w_std),
        (&actor.fc_std.bias, b_std),
    ] {
        var.set(&Tensor::from_slice(data, var.shape(), dev)?)?;
    }
    Ok(())
}

/// Adam's step on the actor's six tensors, in `PolicyNetContinuous::vars`' order.
fn step_actor(
    params: &mut Params,
    adam: &mut crate::ppo::adam::Adam,
    grads: Grads,
) -> candle_core::Result<()> {
    let h = params.b1.len();
    let (mut gw_mu, mut gb_mu) = (grads.w2, grads.b2);
    let (gw_std, gb_std) = (gw_mu.split_off(h), gb_mu.split_off(1));
    let mut grads = [
        Some(grads.w1),
        Some(grads.b1),
        Some(gw_mu),
        Some(gb_mu),
        Some(gw_std),
        Some(gb_std),
    ];
    let (w_mu, w_std) = params.w2.split_at_mut(h);
    let (b_mu, b_std) = params.b2.split_at_mut(1);
    let mut tensors = [
        &mut params.w1[..],
        &mut params.b1[..],
        w_mu,
        b_mu,
        w_std,
        b_std,
    ];
    adam.step_params(&mut grads, &mut tensors, None)
}

/// The loops over the batch, each compiled for the [`Isa`] (see the discrete `plain`).
#[derive(Clone, Copy)]
struct Kernels(Isa);

kernel!(ActorForward {
    params: &'a Params,
    states: &'a [[f32; 3]],
    xt: &'a [Vec<f32>; STATE_DIM],
    hidden: &'a mut [f32],
    scratch: &'a mut Scratch,
} -> [Vec<f32>; 2] = heads);
kernel!(ActorBackward {
    params: &'a Params,
    states: &'a [[f32; 3]],
    hidden: &'a [f32],
    grad_heads: &'a [[f32; 2]],
} -> Grads = actor_backward);

impl Kernels {
    /// The critic's kernels, under the same instruction set.
    fn critic(self) -> CriticKernels {
        CriticKernels(self.0)
    }

    fn actor_forward(
        self,
        params: &Params,
        states: &[[f32; 3]],
        xt: &[Vec<f32>; STATE_DIM],
        hidden: &mut [f32],
        scratch: &mut Scratch,
    ) -> [Vec<f32>; 2] {
        let _life = std::marker::PhantomData;
        let args = ActorForward {
            params,
            states,
            xt,
            hidden,
            scratch,
            _life,
        };
        pulp::Simd::vectorize(self.0, args)
    }

    fn actor_backward(
        self,
        params: &Params,
        states: &[[f32; 3]],
        hidden: &[f32],
        grad_heads: &[[f32; 2]],
    ) -> Grads {
        let _life = std::marker::PhantomData;
        let args = ActorBackward {
            params,
            states,
            hidden,
            grad_heads,
            _life,
        };
        pulp::Simd::vectorize(self.0, args)
    }
}

/// The update's prologue and epochs on plain data.
fn epochs(
    kernels: Kernels,
    agent: &mut PpoContinuous,
    batch: &ContinuousTransitions,
    actor: &mut Params,
    critic: &mut Params,
) -> Result<ContinuousUpdateTrace, PpoError> {
    let cfg = agent.config.clone();
    let n = batch.len();
    let hidden = cfg.hidden_dim;
    let (mut actor_hidden, mut critic_hidden) = (vec![0.0; n * hidden], vec![0.0; n * hidden]);
    let mut scratch = Scratch::default();
    let xt = input_columns(&batch.states);

    // scaled_rewards = (rewards + 8) / 8: two affine ops, `x * mul + add` in f32
    let (shift, scale) = (REWARD_SHIFT as f32, (1.0 / REWARD_SCALE) as f32);
    let scaled_rewards: Vec<f32> = batch
        .rewards
        .iter()
        .map(|&r| (r * 1.0 + shift) * scale + 0.0)
        .collect();
    let next_values = kernels.critic().forward(
        critic,
        &batch.next_states,
        &input_columns(&batch.next_states),
        None,
        &mut scratch,
    );
    // td_target = scaled + (next_values * γ) * (1 - dones), `* γ` and `1.0 -` affine ops
    let gamma = cfg.gamma as f32;
    let td_target: Vec<f32> = scaled_rewards
        .iter()
        .zip(&next_values)
        .zip(&batch.dones)
        .map(|((&r, &v), &d)| {
            let not_done = -f32::from(u8::from(d)) + 1.0; // x * -1 is -x
            r + (v * gamma + 0.0) * not_done
        })
        .collect();
    let values = kernels.critic().forward(
        critic,
        &batch.states,
        &xt,
        Some(&mut critic_hidden),
        &mut scratch,
    );
    let td_delta: Vec<f32> = td_target.iter().zip(&values).map(|(t, v)| t - v).collect();
    let advantage = compute_advantage(cfg.gamma, cfg.lmbda, &td_delta);
    let mut heads =
        kernels.actor_forward(actor, &batch.states, &xt, &mut actor_hidden, &mut scratch);
    let old: Vec<GaussianRow> = rows(&heads, &batch.actions).collect();

    let mut trace = ContinuousUpdateTrace {
        states: batch.states.clone(),
        actions: batch.actions.clone(),
        rewards: batch.rewards.clone(),
        next_states: batch.next_states.clone(),
        dones: batch.dones.clone(),
        scaled_rewards,
        values: values.clone(),
        next_values,
        td_target,
        td_delta,
        advantage,
        mu: old.iter().map(|r| r.mu).collect(),
        std: old.iter().map(|r| r.std).collect(),
        old_log_probs: old.iter().map(|r| r.log_prob).collect(),
        epochs: Vec::with_capacity(cfg.epochs),
        path: UpdatePath::Plain,
    };
    check_finite("td_target", &trace.td_target)?;
    check_finite("advantage", &trace.advantage)?;
    check_finite("old_log_probs", &trace.old_log_probs)?;

    // mean_all's `sum / N` is candle's affine with mul = 1/N rounded to f32
    let inv_n = (1.0 / n as f64) as f32;
    let (lo, hi) = ((1.0 - cfg.eps) as f32, (1.0 + cfg.eps) as f32);
    let mut critic_out = values; // V(s) with the current critic
    for k in 0..cfg.epochs {
        if k > 0 {
            heads =
                kernels.actor_forward(actor, &batch.states, &xt, &mut actor_hidden, &mut scratch);
            critic_out = kernels.critic().forward(
                critic,
                &batch.states,
                &xt,
                Some(&mut critic_hidden),
                &mut scratch,
            );
        }
        let mut record = ContinuousEpochTrace {
            log_probs: Vec::with_capacity(n),
            ratio: Vec::with_capacity(n),
            surr1: Vec::with_capacity(n),
            surr2: Vec::with_capacity(n),
            actor_loss: 0.0,
            critic_loss: 0.0,
        };
        let mut neg_objective = Vec::with_capacity(n);
        let mut grad_heads = Vec::with_capacity(n);
        for ((row, &old), &adv) in rows(&heads, &batch.actions)
            .zip(&trace.old_log_probs)
            .zip(&trace.advantage)
        {
            let surrogate = Surrogate::forward(row.log_prob, old, adv, lo, hi);
            record.log_probs.push(row.log_prob);
            record.ratio.push(surrogate.ratio);
            record.surr1.push(surrogate.surr1);
            record.surr2.push(surrogate.surr2);
            neg_objective.push(-surrogate.objective);
            grad_heads.push(row.backward(surrogate.backward(inv_n, adv, lo, hi)));
        }
        record.actor_loss = vec_sum(&neg_objective) * inv_n + 0.0;
        let (critic_loss, grad_values) = critic_loss(&critic_out, &trace.td_target, inv_n);
        record.critic_loss = critic_loss;
        for (name, value) in [
            ("actor_loss", record.actor_loss),
            ("critic_loss", record.critic_loss),
        ] {
            if !value.is_finite() {
                return Err(PpoError::NonFinite(format!("{name} ({value})")));
            }
        }
        trace.epochs.push(record);

        let grads = kernels.actor_backward(actor, &batch.states, &actor_hidden, &grad_heads);
        step_actor(actor, &mut agent.actor_optimizer, grads)?;
        let grads = kernels
            .critic()
            .backward(critic, &batch.states, &critic_hidden, &grad_values);
        critic.step(&mut agent.critic_optimizer, grads, None)?;
    }
    Ok(trace)
}

/// The Gaussian rows of an actor's forward pass: `heads` are `(z_μ, z_σ)` column by column.
fn rows<'a>(
    heads: &'a [Vec<f32>; 2],
    actions: &'a [f32],
) -> impl Iterator<Item = GaussianRow> + 'a {
    heads[0]
        .iter()
        .zip(&heads[1])
        .zip(actions)
        .map(|((&z_mu, &z_std), &a)| GaussianRow::forward(z_mu, z_std, a))
}

/// One row of the actor: `μ`, `σ` and `log N(a; μ, σ)` with what the backward pass needs.
struct GaussianRow {
    /// `tanh(z_μ)`.
    tanh: f32,
    mu: f32,
    /// `z_σ`, softplus's input.
    z_std: f32,
    std: f32,
    /// `a - μ`.
    diff: f32,
    /// `-(a - μ)²`.
    neg_squared_error: f32,
    /// `σ² · 2`.
    var2: f32,
    log_prob: f32,
}

impl GaussianRow {
    #[inline(always)]
    fn forward(z_mu: f32, z_std: f32, action: f32) -> Self {
        let tanh = z_mu.tanh();
        let mu = tanh * 2.0 + 0.0; // affine(2, 0)
        let std = softplus_f32(z_std);
        // normal::log_prob: var = σ², -((a - μ)²) / (var * 2), - log σ, - log √(2π)
        let var = std * std;
        let diff = action - mu;
        let neg_squared_error = -(diff * diff);
        let var2 = var * 2.0 + 0.0;
        let log_prob = (neg_squared_error / var2 - std.ln()) * 1.0 + -(LOG_SQRT_2PI as f32);
        Self {
            tanh,
            mu,
            z_std,
            std,
            diff,
            neg_squared_error,
            var2,
            log_prob,
        }
    }

    /// `(∂loss/∂z_μ, ∂loss/∂z_σ)` from `∂loss/∂log_prob`, in the order candle's backward
    /// pass visits the graph (see the module doc).
    #[inline(always)]
    fn backward(&self, grad_log_prob: f32) -> [f32; 2] {
        let grad_t = 0.0 + (grad_log_prob * 1.0 + 0.0); // affine(1, -log √(2π))
        // t = scaled - log σ
        let grad_scaled = 0.0 + grad_t;
        let grad_log_std = 0.0 - grad_t;
        // log σ is visited before σ², so σ's gradient starts with its part
        let grad_std = 0.0 + grad_log_std / self.std;
        // scaled = nse / var2
        let grad_nse = 0.0 + grad_scaled / self.var2;
        let grad_var2 = 0.0 - (grad_scaled * self.neg_squared_error) / (self.var2 * self.var2);
        let grad_var = 0.0 + (grad_var2 * 2.0 + 0.0); // affine(2, 0)
        let grad_std = grad_std + ((self.std * grad_var) * 2.0 + 0.0); // sqr
        // softplus's backward (model::SoftplusGrad)
        let grad_z_std = 0.0
            + if self.z_std > SOFTPLUS_THRESHOLD {
                grad_std
            } else {
                let e = self.z_std.exp();
                grad_std * e / (e + 1.0)
            };
        // nse = -(diff²), diff = a - μ, μ = tanh · 2
        let grad_squared_error = 0.0 - grad_nse;
        let grad_diff = 0.0 + ((self.diff * grad_squared_error) * 2.0 + 0.0);
        let grad_mu = 0.0 - grad_diff;
        let grad_tanh = 0.0 + (grad_mu * 2.0 + 0.0);
        let minus_dtanh = self.tanh * self.tanh * 1.0 + -1.0; // node.sqr() - 1
        let grad_z_mu = 0.0 - grad_tanh * minus_dtanh;
        [grad_z_mu, grad_z_std]
    }
}

/// The actor's heads over all rows: the hidden layer into `hidden` (row-major, for the
/// backward pass), `[z_μ, z_σ]` returned (`fc_mu` and `fc_std` with their biases).
#[inline(always)]
fn heads<const D: usize>(
    params: &Params,
    states: &[[f32; D]],
    xt: &[Vec<f32>; D],
    hidden: &mut [f32],
    scratch: &mut Scratch,
) -> [Vec<f32>; 2] {
    hidden_layer(params, states, hidden);
    let n = states.len();
    let h = params.b1.len();
    scratch.fit(n, h);
    hidden_columns(params, xt, &mut scratch.cols);
    let (w_mu, w_std) = params.w2.split_at(h);
    let z_mu = output_column(w_mu, params.b2[0], n, scratch);
    let z_std = output_column(w_std, params.b2[1], n, scratch);
    [z_mu, z_std]
}

/// The actor's parameter gradients from `(∂loss/∂z_μ, ∂loss/∂z_σ)`, one pair per row.
#[inline(always)]
fn actor_backward<const D: usize>(
    params: &Params,
    states: &[[f32; D]],
    hidden: &[f32],
    grad_heads: &[[f32; 2]],
) -> Grads {
    let h = params.b1.len();
    let mut grads = Grads {
        w1: vec![0.0; D * h],
        b1: vec![0.0; h],
        w2: vec![0.0; 2 * h],
        b2: vec![0.0; 2],
    };
    // each head's add_bias: SumRows, added to zeros
    let mut grad_b2 = [0.0_f32; 2];
    for g in grad_heads {
        grad_b2[0] += g[0];
        grad_b2[1] += g[1];
    }
    grads.b2 = grad_b2.iter().map(|g| 0.0 + g).collect();
    let blocks = h / 8 * 8;
    for j in (0..blocks).step_by(8) {
        actor_columns::<D, 8>(params, states, hidden, grad_heads, j, &mut grads);
    }
    for j in blocks..h {
        actor_columns::<D, 1>(params, states, hidden, grad_heads, j, &mut grads);
    }
    grads
}

/// [`actor_backward`] for the `L` columns from `j0` of the hidden layer.
#[inline(always)]
fn actor_columns<const D: usize, const L: usize>(
    params: &Params,
    states: &[[f32; D]],
    hidden: &[f32],
    grad_heads: &[[f32; 2]],
    j0: usize,
    grads: &mut Grads,
) {
    let h = params.b1.len();
    let w_mu: [f32; L] = take(&params.w2[j0..]);
    let w_std: [f32; L] = take(&params.w2[h + j0..]);
    let mut gw_mu = [0.0_f32; L]; // Hᵀ · g, gemm's column-major gemv
    let mut gw_std = [0.0_f32; L];
    let mut gb1 = [0.0_f32; L];
    let mut gw1t = [[0.0_f32; L]; D];
    for ((row, x), g) in hidden.chunks_exact(h).zip(states).zip(grad_heads) {
        let hv: [f32; L] = take(&row[j0..]);
        let (g_mu, g_std) = (0.0 + g[0], 0.0 + g[1]); // each head's input gradient: 0 + g
        let mut grad_h = [0.0_f32; L];
        for l in 0..L {
            gw_mu[l] = hv[l].mul_add(g_mu, gw_mu[l]);
            gw_std[l] = hv[l].mul_add(g_std, gw_std[l]);
            // g · w (gevv, k = 1) of each head; the σ head's is visited first
            grad_h[l] = (0.0 + g_std * w_std[l]) + g_mu * w_mu[l];
        }
        fc1_backward_row(&hv, x, &grad_h, &mut gb1, &mut gw1t);
    }
    store_columns(grads, j0, gw1t, gb1, &[gw_mu, gw_std]);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::env::seeding::NumpyRng;
    use crate::ppo::update_path::{choose_path, plain_runs_here};

    /// `n` consecutive transitions of a random walk over Pendulum-like states and torques
    /// beyond the clip range; the episode ends at the last one.
    fn walk(n: usize, rng: &mut NumpyRng) -> ContinuousTransitions {
        let mut theta = rng.uniform(-3.1, 3.1);
        let mut speed = rng.uniform(-1.0, 1.0);
        let mut batch = ContinuousTransitions::default();
        let obs = |theta: f64, speed: f64| [theta.cos() as f32, theta.sin() as f32, speed as f32];
        for t in 0..n {
            let state = obs(theta, speed);
            let action = rng.uniform(-3.0, 3.0) as f32;
            speed = (speed + rng.uniform(-0.8, 0.8)).clamp(-8.0, 8.0);
            theta += 0.05 * speed;
            let reward = -(theta * theta + 0.1 * speed * speed) as f32;
            batch.push(state, action, reward, obs(theta, speed), t + 1 == n);
        }
        batch
    }

    /// Every number as text (serde_json keeps each f32's shortest round-trip form, -0.0
    /// included), so equal text is equal bits.
    fn text(value: &impl serde::Serialize) -> String {
        serde_json::to_string(value).unwrap_or_else(|e| format!("unserialisable: {e}"))
    }

    /// Three updates of two agents built alike, one on the path chosen for it (plain, which
    /// the trace must say) and one forced onto candle as `PPO_TUTOR_UPDATE=candle` forces it:
    /// the same traces (or the same error), weights and acting snapshots, bit for bit.
    /// Callers first check that this CPU runs the plain path ([`plain_runs_here`]).
    fn compare(config: &PpoContinuousConfig, n: usize, seed: u64) -> Result<(), PpoError> {
        let mut plain_agent = PpoContinuous::new(config, seed)?;
        let mut tensor_agent = PpoContinuous::new(config, seed)?;
        let mut rng = NumpyRng::from_seed(seed + 1000 * n as u64);
        for update in 0..3 {
            let batch = walk(n, &mut rng);
            let what = format!("n = {n}, update {update}, {config:?}");
            assert_eq!(
                choose_path(&conditions(config, n), None),
                UpdatePath::Plain,
                "the plain path should take this batch: {what}"
            );
            // a diverged update is an error in both, after the same steps; automatic, whatever
            // PPO_TUTOR_UPDATE says in the environment of the tests
            let plain = plain_agent.update_as(&batch, None);
            let tensors = tensor_agent.update_as(&batch, Some(UpdatePath::Candle));
            if let (Ok(plain), Ok(tensors)) = (&plain, &tensors) {
                assert_eq!(plain.path, UpdatePath::Plain, "{what}");
                assert_eq!(tensors.path, UpdatePath::Candle, "forced candle: {what}");
            }
            // every number, the path aside
            let numbers = |t: ContinuousUpdateTrace| {
                text(&ContinuousUpdateTrace {
                    path: UpdatePath::Candle,
                    ..t
                })
            };
            let (plain, tensors) = (plain.map(numbers), tensors.map(numbers));
            assert_eq!(
                format!("{plain:?}"),
                format!("{tensors:?}"),
                "trace differs: {what}"
            );
            assert_eq!(
                text(&plain_agent.weights()?),
                text(&tensor_agent.weights()?),
                "weights differ: {what}"
            );
            let state = [0.6_f32, -0.8, 1.5];
            assert_eq!(
                plain_agent.mu_std(&state),
                tensor_agent.mu_std(&state),
                "acting snapshot differs: {what}"
            );
            if plain.is_err() {
                break;
            }
        }
        Ok(())
    }

    /// Batch sizes on both sides of every switch of gemm's paths and candle's sums
    /// (32-blocks, 64-blocks, N ≤ 256 for the horizontal kernel), Pendulum's 200, the ends.
    #[test]
    fn bit_for_bit_the_tensor_update_at_every_path_boundary() -> Result<(), PpoError> {
        if !plain_runs_here("bit_for_bit_the_tensor_update_at_every_path_boundary") {
            return Ok(());
        }
        let config = PpoContinuousConfig::default();
        let sizes = (3..=10)
            .chain(30..=34)
            .chain(62..=66)
            .chain(126..=130)
            .chain([199, 200, 201])
            .chain(254..=258)
            .chain([319, 320, 321, 447, 448, 449, 511, 512]);
        for n in sizes {
            compare(&config, n, 7)?;
        }
        Ok(())
    }

    /// Other widths, epochs, clip ranges and learning rates.
    #[test]
    fn bit_for_bit_the_tensor_update_with_other_settings() -> Result<(), PpoError> {
        if !plain_runs_here("bit_for_bit_the_tensor_update_with_other_settings") {
            return Ok(());
        }
        let base = PpoContinuousConfig::default();
        let configs = [
            PpoContinuousConfig {
                hidden_dim: 64,
                epochs: 3,
                eps: 0.1,
                ..base.clone()
            },
            PpoContinuousConfig {
                hidden_dim: 13,
                gamma: 0.99,
                ..base.clone()
            },
            // diverges (σ → 0): both versions fail in the same epoch with the same weights
            PpoContinuousConfig {
                hidden_dim: 13,
                actor_lr: 0.05,
                ..base.clone()
            },
            PpoContinuousConfig {
                hidden_dim: 200,
                lmbda: 0.0,
                ..base
            },
        ];
        for config in &configs {
            for n in [21, 40, 129, 200, 300] {
                compare(config, n, 3)?;
            }
        }
        Ok(())
    }

    /// `PPO_TUTOR_UPDATE=candle`'s setting on Pendulum's 200-step episodes: every update
    /// says candle and equals, bit for bit, the same updates on the plain path, whose traces
    /// say plain (the setting is given here as the agent receives it; `tests/cli/ppo.rs`
    /// sets the variable).
    #[test]
    fn forcing_candle_gives_the_plain_numbers() -> Result<(), PpoError> {
        if !plain_runs_here("forcing_candle_gives_the_plain_numbers") {
            return Ok(());
        }
        let config = PpoContinuousConfig::default();
        let mut plain = PpoContinuous::new(&config, 11)?;
        let mut candle = PpoContinuous::new(&config, 11)?;
        let mut rng = NumpyRng::from_seed(11);
        for episode in 0..5 {
            let batch = walk(200, &mut rng);
            let a = plain.update_as(&batch, None)?;
            let b = candle.update_as(&batch, Some(UpdatePath::Candle))?;
            assert_eq!((a.path, b.path), (UpdatePath::Plain, UpdatePath::Candle));
            let a = ContinuousUpdateTrace { path: b.path, ..a };
            assert_eq!(text(&a), text(&b), "episode {episode}");
        }
        assert_eq!(text(&plain.weights()?), text(&candle.weights()?));
        Ok(())
    }

    /// Batches the plain path leaves to the tensors, on any CPU: the conditions say candle,
    /// and so does the trace of an update.
    #[test]
    fn other_shapes_use_the_tensors() -> Result<(), PpoError> {
        let mut rng = NumpyRng::from_seed(0);
        let base = PpoContinuousConfig::default();
        let narrow = PpoContinuousConfig {
            hidden_dim: 1,
            ..base.clone()
        };
        for (config, n) in [(&base, 2), (&base, 513), (&narrow, 50)] {
            assert_eq!(
                choose_path(&conditions(config, n), None),
                UpdatePath::Candle,
                "n = {n}, {config:?}"
            );
            let trace = PpoContinuous::new(config, 0)?.update_as(&walk(n, &mut rng), None)?;
            assert_eq!(trace.path, UpdatePath::Candle, "n = {n}, {config:?}");
        }
        assert_eq!(
            choose_path(&conditions(&base, 200), None) == UpdatePath::Plain,
            isa().is_some(),
            "the book's batches run plain exactly where the CPU allows it"
        );
        Ok(())
    }
}
