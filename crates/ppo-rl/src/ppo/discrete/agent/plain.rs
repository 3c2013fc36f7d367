//! The seed's update on plain `f32` slices: candle's float operations, one for one.
//!
//! [`Agent::update`](super::Agent::update) is written with candle tensors and autograd (the
//! lessons show that code). For the seed's configuration it runs this module instead
//! ([`UpdatePath::Plain`]; [`conditions`] and [`update_path`](crate::ppo::update_path) say
//! exactly when, `PPO_TUTOR_UPDATE=candle` turns it off), which
//! performs the very same IEEE operations in the same order, so that every number (losses,
//! ratios, gradients, weights) is bit for bit the tensor version's, only without building
//! some 150 tensors per epoch. (Measured on the seed's 500 episodes, seeds 0-2, test-profile
//! binary on a 2-core machine: 7.6-7.9 s per run with the tensors, 0.81-0.87 s with this.)
//!
//! What "the same operations" means, per candle 0.11 / gemm 0.19 on x86-64 with AVX2 and
//! FMA (the kernels candle picks there; elsewhere the tensor version runs):
//!
//! ```text
//! matmul, the k-sum of each output:                           (gemm's path for our shapes)
//!   vertical kernel  acc = 0; acc = fma(a_k, b_k, acc) for k = 0, 1, ..  X·W1ᵀ, Hᵀ·G, Xᵀ·G,
//!                                                                        H·W2ᵀ for N > 128
//!   horizontal       8 lane sums of fmas, then ((l0+l4)+(l2+l6))+((l1+l5)+(l3+l7))
//!                                                                        H·W2ᵀ, N·out ≤ 256
//!   gemv (row-major) 8×8 lane sums, a tree, then the lanes in order      critic, N > 256
//!   gemv (col-major) acc = a_0·b_0; acc = fma(a_k, b_k, acc)             critic Hᵀ·g
//!   gevv, k ≤ 2      a_1·b_1 + a_0·b_0 (not fused)                       G·W2 (backward)
//! sum over N (mean_all): 4×8 lane sums of 32-blocks, a tree, then the tail in order
//! sum over 2 (softmax, a broadcast's backward): (0 + x0) + x1
//! autograd: each gradient starts as zeros and is added to, `0 + g` (which turns -0 into
//! +0); where a tensor feeds two ops the two contributions add in the order candle's
//! backward visits them (noted below).
//! ```
//!
//! The shapes decide gemm's path, so the module takes batches of 3 to 512 transitions and
//! hidden layers of 2 to 512 units (up to 512, every k-sum is one block of gemm's; and more
//! than 256 hidden-layer entries) and leaves the rest to the tensors. Its tests compare
//! both, number for number, on batch sizes on either side of every switch of path; on a CPU
//! without AVX2 and FMA they print `SKIPPED` instead of comparing candle with candle.
//!
//! The matrix products, sums and the clipped surrogate are in
//! [`kernels`](crate::ppo::kernels), generic in the number of inputs, which the continuous
//! agent's update on plain slices shares; this module has what is the discrete actor's own
//! (softmax, `log(gather)`, the entropy, the 2-logit output layer).

use super::{Agent, EpochTrace, Transitions, check_batch, mean};
use crate::ppo::PpoError;
use crate::ppo::advantage::{compute_advantage, normalize_advantage};
use crate::ppo::discrete::trace::{EarlyStop, UpdateTrace};
use crate::ppo::discrete::{PpoConfig, STATE_DIM, UpdateRule};
use crate::ppo::kernels::{
    CriticKernels, Grads, Isa, Params, Scratch, Surrogate, critic_loss, exp_exact,
    fc1_backward_row, hidden_columns, hidden_layer, horizontal_columns, input_columns, isa, kernel,
    store_columns, take, vec_sum,
};
use crate::ppo::model::ActorSnapshot;
use crate::ppo::update_path::{PathConditions, UpdatePath};

/// Buffers reused from update to update.
#[derive(Clone, Default)]
pub(super) struct Workspace {
    /// The actor's hidden layer `relu(fc1(states))`, `(N, hidden)`.
    actor_hidden: Vec<f32>,
    /// The critic's hidden layer, `(N, hidden)`.
    critic_hidden: Vec<f32>,
    /// The forward passes' buffers.
    scratch: Scratch,
}

impl std::fmt::Debug for Workspace {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Workspace")
            .field("actor_hidden", &self.actor_hidden.len())
            .field("critic_hidden", &self.critic_hidden.len())
            .finish()
    }
}

/// What decides whether this module computes the update of an agent configured by
/// `config` on a batch of `rows` transitions, `learner_losses` when the losses are a
/// learner's ([`Agent::update_with`](super::Agent::update_with)); see
/// [`choose_path`](crate::ppo::update_path::choose_path).
pub(super) fn conditions(config: &PpoConfig, rows: usize, learner_losses: bool) -> PathConditions {
    PathConditions {
        learner_losses,
        // PPO-Penalty's KL term has no plain kernel: it runs on candle
        clipped_surrogate: config.rule() == Ok(UpdateRule::Clip),
        entropy_bonus: config.entropy_coef != 0.0,
        rows,
        hidden: config.hidden_dim,
        avx2_fma: isa().is_some(),
    }
}

/// Runs the update; the kernels run under `simd` (see [`Kernels`]).
pub(super) fn update(
    simd: Isa,
    agent: &mut Agent,
    batch: &Transitions,
) -> Result<UpdateTrace, PpoError> {
    run(Kernels(simd), agent, batch)
}

/// The four loops over the batch, each compiled for the [`Isa`] as its own function, so
/// that `mul_add` is one FMA instruction and the compiler vectorises them. (`mul_add` is
/// exact everywhere; without FMA it is a slow library call.)
#[derive(Clone, Copy)]
struct Kernels(Isa);

kernel!(ActorForward {
    params: &'a Params,
    states: &'a [[f32; 4]],
    xt: &'a [Vec<f32>; STATE_DIM],
    hidden: &'a mut [f32],
    scratch: &'a mut Scratch,
} -> ActorPass = actor_pass);
kernel!(ActorBackward {
    params: &'a Params,
    states: &'a [[f32; 4]],
    hidden: &'a [f32],
    grad_logits: &'a [[f32; 2]],
} -> Grads = actor_backward);

impl Kernels {
    /// The critic's kernels, under the same instruction set.
    fn critic(self) -> CriticKernels {
        CriticKernels(self.0)
    }

    fn actor_forward(
        self,
        params: &Params,
        states: &[[f32; 4]],
        xt: &[Vec<f32>; STATE_DIM],
        hidden: &mut [f32],
        scratch: &mut Scratch,
    ) -> ActorPass {
        let _life = std::marker::PhantomData;
        pulp::Simd::vectorize(
            self.0,
            ActorForward {
                params,
                states,
                xt,
                hidden,
                scratch,
                _life,
            },
        )
    }

    fn actor_backward(
        self,
        params: &Params,
        states: &[[f32; 4]],
        hidden: &[f32],
        grad_logits: &[[f32; 2]],
    ) -> Grads {
        let _life = std::marker::PhantomData;
        pulp::Simd::vectorize(
            self.0,
            ActorBackward {
                params,
                states,
                hidden,
                grad_logits,
                _life,
            },
        )
    }
}

/// What the actor computes on the batch: the forward values one epoch needs.
struct ActorPass {
    /// `(z0, z1)`, the logits `fc2(relu(fc1(s)))`.
    logits: Vec<[f32; 2]>,
}

/// Reads the weights, runs the epochs on them, and stores them back (also after an error,
/// as the tensor version has stepped its variables by then).
fn run(kernels: Kernels, agent: &mut Agent, batch: &Transitions) -> Result<UpdateTrace, PpoError> {
    let mut actor = Params::read(&agent.actor.fc1, &agent.actor.fc2)?;
    let mut critic = Params::read(&agent.critic.fc1, &agent.critic.fc2)?;
    let mut ws = std::mem::take(&mut agent.plain);
    let result = epochs(kernels, agent, batch, &mut actor, &mut critic, &mut ws);
    agent.plain = ws;
    actor.write(&agent.actor.fc1, &agent.actor.fc2)?;
    critic.write(&agent.critic.fc1, &agent.critic.fc2)?;
    if result.is_ok() {
        agent.acting = ActorSnapshot::from_parts(actor.w1, actor.b1, actor.w2, actor.b2, STATE_DIM);
    }
    result
}

/// `run_update`'s prologue and epochs on plain data.
fn epochs(
    kernels: Kernels,
    agent: &mut Agent,
    batch: &Transitions,
    actor: &mut Params,
    critic: &mut Params,
    ws: &mut Workspace,
) -> Result<UpdateTrace, PpoError> {
    let cfg = agent.config.clone();
    let n = batch.len();
    let hidden = cfg.hidden_dim;
    ws.actor_hidden.resize(n * hidden, 0.0);
    ws.critic_hidden.resize(n * hidden, 0.0);
    let xt = input_columns(&batch.states);

    let done_flags = if cfg.bootstrap_on_truncation {
        &batch.terminated
    } else {
        &batch.dones
    };
    // next_values = V(s'), its hidden layer not kept
    let next_values = kernels.critic().forward(
        critic,
        &batch.next_states,
        &input_columns(&batch.next_states),
        None,
        &mut ws.scratch,
    );
    // td_target = rewards + (next_values * γ) * (1 - dones): `* γ` and `1.0 -` are
    // candle's affine ops, `x * mul + add` in f32
    let gamma = cfg.gamma as f32;
    let td_target: Vec<f32> = batch
        .rewards
        .iter()
        .zip(&next_values)
        .zip(done_flags)
        .map(|((&r, &v), &d)| {
            let not_done = -f32::from(u8::from(d)) + 1.0; // x * -1 is -x
            r + (v * gamma + 0.0) * not_done
        })
        .collect();
    let values = kernels.critic().forward(
        critic,
        &batch.states,
        &xt,
        Some(&mut ws.critic_hidden),
        &mut ws.scratch,
    );
    let td_delta: Vec<f32> = td_target.iter().zip(&values).map(|(t, v)| t - v).collect();
    let mut advantage = compute_advantage(cfg.gamma, cfg.lmbda, &td_delta);
    let lambda_return: Vec<f32> = advantage.iter().zip(&values).map(|(a, v)| a + v).collect();
    if cfg.normalize_advantage {
        advantage = normalize_advantage(&advantage);
    }
    let mut pass = kernels.actor_forward(
        actor,
        &batch.states,
        &xt,
        &mut ws.actor_hidden,
        &mut ws.scratch,
    );
    let old_log_probs: Vec<f32> = pass
        .logits
        .iter()
        .zip(&batch.actions)
        .map(|(z, &a)| Softmax::of(*z).probs[a].ln())
        .collect();

    let mut trace = UpdateTrace {
        states: batch.states.clone(),
        actions: batch.actions.clone(),
        rewards: batch.rewards.clone(),
        next_states: batch.next_states.clone(),
        dones: done_flags.clone(),
        values: values.clone(),
        next_values,
        td_target,
        td_delta,
        advantage,
        lambda_return,
        old_log_probs,
        epochs: Vec::with_capacity(cfg.epochs),
        early_stop: None,
        explained_variance: None,
        path: UpdatePath::Plain,
        penalty: None,
        line_search: None,
        kl_after: None,
    };
    check_batch(&mut trace)?;

    // mean_all's `sum / N` is candle's affine with mul = 1/N rounded to f32
    let inv_n = (1.0 / n as f64) as f32;
    let eps = cfg.eps;
    let (lo, hi) = ((1.0 - eps) as f32, (1.0 + eps) as f32);
    let mut critic_out = values; // V(s) with the current critic
    // with `critic_epochs` set, one network stops stepping before the other (the order of
    // the two networks' steps does not matter: they share nothing)
    let (actor_epochs, critic_epochs) = cfg.epochs_of_each();
    for k in 0..actor_epochs.max(critic_epochs) {
        if k > 0 {
            pass = kernels.actor_forward(
                actor,
                &batch.states,
                &xt,
                &mut ws.actor_hidden,
                &mut ws.scratch,
            );
            critic_out = kernels.critic().forward(
                critic,
                &batch.states,
                &xt,
                Some(&mut ws.critic_hidden),
                &mut ws.scratch,
            );
        }
        // the actor's loss, row by row, and its gradient with respect to the logits
        let mut log_probs = Vec::with_capacity(n);
        let mut ratio = Vec::with_capacity(n);
        let mut surr1 = Vec::with_capacity(n);
        let mut surr2 = Vec::with_capacity(n);
        let mut neg_objective = Vec::with_capacity(n);
        let mut neg_entropy_rows = Vec::with_capacity(n);
        let mut grad_logits = Vec::with_capacity(n);
        for (((z, &a), &old), &adv) in pass
            .logits
            .iter()
            .zip(&batch.actions)
            .zip(&trace.old_log_probs)
            .zip(&trace.advantage)
        {
            let row = ActorRow::forward(*z, a, old, adv, lo, hi);
            log_probs.push(row.log_prob);
            ratio.push(row.surrogate.ratio);
            surr1.push(row.surrogate.surr1);
            surr2.push(row.surrogate.surr2);
            neg_objective.push(-row.surrogate.objective);
            neg_entropy_rows.push(row.neg_entropy);
            grad_logits.push(row.backward(inv_n, adv, lo, hi));
        }
        let approx_kl = mean(
            ratio
                .iter()
                .zip(&log_probs)
                .zip(&trace.old_log_probs)
                .map(|((r, lp), old)| (r - 1.0) - (lp - old)),
        );
        if let Some(target) = cfg.target_kl
            && f64::from(approx_kl) > 1.5 * target
        {
            trace.early_stop = Some(EarlyStop {
                epoch: k + 1,
                approx_kl,
            });
            break;
        }
        let actor_loss = vec_sum(&neg_objective) * inv_n + 0.0;
        let entropy = vec_sum(&neg_entropy_rows) * inv_n + 0.0;
        // the critic's loss: mean((V(s) + b - target)²) and its gradient
        let (critic_loss, grad_values) = critic_loss(&critic_out, &trace.td_target, inv_n);

        let clipped: Vec<bool> = ratio.iter().map(|r| (r - 1.0).abs() > eps as f32).collect();
        let record = EpochTrace {
            clip_fraction: mean(clipped.iter().map(|&c| f32::from(u8::from(c)))),
            clipped,
            approx_kl,
            actor_loss,
            critic_loss,
            entropy,
            surr1,
            surr2,
            log_probs,
            ratio,
            kl: Vec::new(),
            kl_mean: None,
        };
        for (name, value) in [("actor_loss", actor_loss), ("critic_loss", critic_loss)] {
            if !value.is_finite() {
                return Err(PpoError::NonFinite(format!("{name} ({value})")));
            }
        }
        trace.epochs.push(record);

        if k < actor_epochs {
            let grads =
                kernels.actor_backward(actor, &batch.states, &ws.actor_hidden, &grad_logits);
            actor.step(&mut agent.actor_optimizer, grads, cfg.max_grad_norm)?;
        }
        if k < critic_epochs {
            let grads =
                kernels
                    .critic()
                    .backward(critic, &batch.states, &ws.critic_hidden, &grad_values);
            critic.step(&mut agent.critic_optimizer, grads, cfg.max_grad_norm)?;
        }
    }
    Ok(trace)
}

/// `softmax(z)` over two logits as candle-nn's `softmax` computes it.
struct Softmax {
    /// `max(z)` (`max_keepdim`: the first, unless the second is larger).
    max: f32,
    /// `exp(z - max)`.
    exp: [f32; 2],
    /// `Σ exp` (`sum_keepdim`: `(0 + e0) + e1`).
    sum: f32,
    /// `exp / sum`.
    probs: [f32; 2],
}

impl Softmax {
    #[inline(always)]
    fn of(z: [f32; 2]) -> Self {
        let max = if z[0] < z[1] { z[1] } else { z[0] };
        let exp = [exp_exact(z[0] - max), exp_exact(z[1] - max)];
        let sum = (0.0 + exp[0]) + exp[1];
        Self {
            max,
            exp,
            sum,
            probs: [exp[0] / sum, exp[1] / sum],
        }
    }
}

/// One row of the actor's epoch: `log π(a|s)`, the ratio, the clipped surrogate, and the
/// row's part of the entropy.
struct ActorRow {
    z: [f32; 2],
    action: usize,
    softmax: Softmax,
    /// `π(a|s)`, the gathered probability.
    prob: f32,
    log_prob: f32,
    /// The ratio and the clipped surrogate.
    surrogate: Surrogate,
    /// `-Σ_a π log π` for this row, before the mean (`neg` of the row sum).
    neg_entropy: f32,
}

impl ActorRow {
    #[inline(always)]
    fn forward(
        z: [f32; 2],
        action: usize,
        old_log_prob: f32,
        advantage: f32,
        lo: f32,
        hi: f32,
    ) -> Self {
        let softmax = Softmax::of(z);
        let prob = softmax.probs[action];
        let log_prob = prob.ln();
        let surrogate = Surrogate::forward(log_prob, old_log_prob, advantage, lo, hi);
        // entropy: probs · log(clamp(probs, MIN_POSITIVE, 1)), summed over the row, negated
        let term = |c: usize| {
            let p = softmax.probs[c];
            let p_lo = if p < f32::MIN_POSITIVE {
                f32::MIN_POSITIVE
            } else {
                p
            };
            let p_clamped = if p_lo > 1.0 { 1.0 } else { p_lo };
            // log(p) of the action taken is log_prob already
            let log = if c == action && p_clamped == p {
                log_prob
            } else {
                p_clamped.ln()
            };
            p * log
        };
        let row_sum = (0.0 + term(0)) + term(1);
        Self {
            z,
            action,
            prob,
            log_prob,
            surrogate,
            neg_entropy: -row_sum,
            softmax,
        }
    }

    /// `∂ actor_loss / ∂ logits` for this row, `actor_loss = mean(-min(surr1, surr2))`, in
    /// the order candle's backward pass visits the graph.
    #[inline(always)]
    fn backward(&self, inv_n: f32, advantage: f32, lo: f32, hi: f32) -> [f32; 2] {
        let eq = |a: f32, b: f32| f32::from(u8::from(a == b));
        // log_prob = log(prob)
        let grad_log_prob = self.surrogate.backward(inv_n, advantage, lo, hi);
        let grad_prob = 0.0 + grad_log_prob / self.prob;
        // gather's backward: scatter_add into zeros
        let mut grad_probs = [0.0_f32; 2];
        grad_probs[self.action] = 0.0 + grad_prob;
        // probs = exp / sum (broadcast): the numerator first, then the sum's broadcast
        let Softmax { max, exp, sum, .. } = self.softmax;
        let grad_exp_div = grad_probs.map(|g| 0.0 + g / sum);
        let grad_sum_b = [0, 1].map(|c| 0.0 - (grad_probs[c] * exp[c]) / (sum * sum));
        let grad_sum = 0.0 + ((0.0 + grad_sum_b[0]) + grad_sum_b[1]);
        let grad_exp = grad_exp_div.map(|g| g + grad_sum);
        // exp(diff); diff = z - max (broadcast): z first, then the max's broadcast
        let grad_diff = [0, 1].map(|c| 0.0 + grad_exp[c] * exp[c]);
        let grad_z = grad_diff.map(|g| 0.0 + g);
        let grad_max_b = grad_diff.map(|g| 0.0 - g);
        let grad_max = 0.0 + ((0.0 + grad_max_b[0]) + grad_max_b[1]);
        [0, 1].map(|c| grad_z[c] + eq(max, self.z[c]) * grad_max)
    }
}

/// gemm's vertical kernel for two outputs over all rows: FMA chains from +0 in order of `j`.
#[inline(always)]
fn vertical2_columns(cols: &[f32], w0: &[f32], w1: &[f32], out0: &mut [f32], out1: &mut [f32]) {
    let n = out0.len();
    out0.fill(0.0);
    out1.fill(0.0);
    for ((col, &y0), &y1) in cols.chunks_exact(n).zip(w0).zip(w1) {
        for ((o0, o1), &h) in out0.iter_mut().zip(out1.iter_mut()).zip(col) {
            *o0 = h.mul_add(y0, *o0);
            *o1 = h.mul_add(y1, *o1);
        }
    }
}

/// The actor's forward pass: the hidden layer into `hidden` (row-major, for the backward
/// pass), the logits returned.
#[inline(always)]
fn actor_pass(
    params: &Params,
    states: &[[f32; 4]],
    xt: &[Vec<f32>; STATE_DIM],
    hidden: &mut [f32],
    scratch: &mut Scratch,
) -> ActorPass {
    hidden_layer(params, states, hidden);
    let n = states.len();
    let h = params.b1.len();
    scratch.fit(n, h);
    hidden_columns(params, xt, &mut scratch.cols);
    let (w0, w1) = params.w2.split_at(h);
    let Scratch {
        cols,
        lanes,
        out0,
        out1,
        ..
    } = scratch;
    if 2 * n <= 256 {
        horizontal_columns(cols, w0, lanes, out0);
        horizontal_columns(cols, w1, lanes, out1);
    } else {
        vertical2_columns(cols, w0, w1, out0, out1);
    }
    // add_bias
    let (b0, b1) = (params.b2[0], params.b2[1]);
    let logits = out0
        .iter()
        .zip(out1.iter())
        .map(|(&z0, &z1)| [z0 + b0, z1 + b1])
        .collect();
    ActorPass { logits }
}

/// The actor's parameter gradients from `∂loss/∂logits` (`grad_logits`, one pair per row).
///
/// Every weight gradient is a chain over the rows, so the columns are taken eight at a
/// time (the last ones one by one) with their sums held in registers down the rows.
#[inline(always)]
fn actor_backward(
    params: &Params,
    states: &[[f32; 4]],
    hidden: &[f32],
    grad_logits: &[[f32; 2]],
) -> Grads {
    let h = params.b1.len();
    let mut grads = Grads {
        w1: vec![0.0; STATE_DIM * h],
        b1: vec![0.0; h],
        w2: vec![0.0; 2 * h],
        b2: vec![0.0; 2],
    };
    // add_bias's backward: the bias sums the logits' gradient (SumRows), added to zeros
    let mut grad_b2 = [0.0_f32; 2];
    for g in grad_logits {
        grad_b2[0] += g[0];
        grad_b2[1] += g[1];
    }
    grads.b2 = grad_b2.iter().map(|g| 0.0 + g).collect();
    let blocks = h / 8 * 8;
    for j in (0..blocks).step_by(8) {
        actor_columns::<8>(params, states, hidden, grad_logits, j, &mut grads);
    }
    for j in blocks..h {
        actor_columns::<1>(params, states, hidden, grad_logits, j, &mut grads);
    }
    grads
}

/// [`actor_backward`] for the `L` columns from `j0` of the hidden layer.
#[inline(always)]
fn actor_columns<const L: usize>(
    params: &Params,
    states: &[[f32; 4]],
    hidden: &[f32],
    grad_logits: &[[f32; 2]],
    j0: usize,
    grads: &mut Grads,
) {
    let h = params.b1.len();
    let w0: [f32; L] = take(&params.w2[j0..]);
    let w1: [f32; L] = take(&params.w2[h + j0..]);
    let mut gw0 = [0.0_f32; L]; // Hᵀ · G, chains from +0 (vertical kernel)
    let mut gw1 = [0.0_f32; L];
    let mut gb1 = [0.0_f32; L]; // SumRows, from 0
    let mut gw1t = [[0.0_f32; L]; STATE_DIM]; // Xᵀ · G1 (vertical kernel)
    for ((row, x), g) in hidden.chunks_exact(h).zip(states).zip(grad_logits) {
        let hv: [f32; L] = take(&row[j0..]);
        let (g0, g1) = (0.0 + g[0], 0.0 + g[1]); // fc2's input gradient: 0 + g
        let mut grad_h = [0.0_f32; L];
        for l in 0..L {
            gw0[l] = hv[l].mul_add(g0, gw0[l]);
            gw1[l] = hv[l].mul_add(g1, gw1[l]);
            // G · W2 (gevv, k = 2)
            grad_h[l] = 0.0 + (g1 * w1[l] + g0 * w0[l]);
        }
        fc1_backward_row(&hv, x, &grad_h, &mut gb1, &mut gw1t);
    }
    store_columns(grads, j0, gw1t, gb1, &[gw0, gw1]);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::env::seeding::NumpyRng;
    use crate::ppo::update_path::{choose_path, plain_runs_here};

    /// `n` consecutive transitions of a random walk over CartPole-sized states; the episode
    /// ends at the last one (terminated or truncated, alternating with `n`).
    fn walk(n: usize, rng: &mut NumpyRng) -> Transitions {
        let scale = [2.4, 2.0, 0.21, 3.0];
        let mut state = scale.map(|s| (rng.uniform(-0.5, 0.5) * s) as f32);
        let mut batch = Transitions::default();
        for t in 0..n {
            let mut next = state;
            for (v, s) in next.iter_mut().zip(scale) {
                *v = (f64::from(*v) + rng.uniform(-0.1, 0.1) * s).clamp(-s, s) as f32;
            }
            let action = usize::from(rng.next_f64() < 0.5);
            let done = t + 1 == n;
            batch.push(state, action, 1.0, next, done, done && n.is_multiple_of(2));
            state = next;
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
    /// the same traces, weights and acting snapshots, bit for bit. Callers first check that
    /// this CPU runs the plain path ([`plain_runs_here`]).
    fn compare(config: &PpoConfig, n: usize, seed: u64) -> Result<(), PpoError> {
        let mut plain_agent = Agent::new(config, seed)?;
        let mut tensor_agent = Agent::new(config, seed)?;
        let mut rng = NumpyRng::from_seed(seed + 1000 * n as u64);
        for update in 0..3 {
            let batch = walk(n, &mut rng);
            let what = format!("n = {n}, update {update}, {config:?}");
            // automatic, whatever PPO_TUTOR_UPDATE says in the environment of the tests
            let plain = plain_agent.run_update_as(&batch, None, None)?;
            let tensors = tensor_agent.run_update_as(&batch, None, Some(UpdatePath::Candle))?;
            assert_eq!(
                plain.path,
                UpdatePath::Plain,
                "the plain path should take this batch: {what}"
            );
            assert_eq!(tensors.path, UpdatePath::Candle, "forced candle: {what}");
            // every number, the path aside
            let plain = UpdateTrace {
                path: tensors.path,
                ..plain
            };
            assert_eq!(text(&plain), text(&tensors), "trace differs: {what}");
            assert_eq!(
                text(&plain_agent.weights()?),
                text(&tensor_agent.weights()?),
                "weights differ: {what}"
            );
            let state = [0.01_f32, -0.3, 0.05, 0.4];
            assert_eq!(
                plain_agent.acting.probs(&state),
                tensor_agent.acting.probs(&state),
                "acting snapshot differs: {what}"
            );
        }
        Ok(())
    }

    /// `critic_epochs`: after its own epochs a network stops moving while the other one
    /// goes on, on both paths. (The actor's ratios stay put once it has stopped; the critic's
    /// loss stays put once it has.)
    #[test]
    fn each_network_takes_its_own_number_of_epochs() -> Result<(), PpoError> {
        let mut rng = NumpyRng::from_seed(5);
        let batch = walk(40, &mut rng);
        for forced in [None, Some(UpdatePath::Candle)] {
            let config = PpoConfig {
                epochs: 1,
                critic_epochs: Some(10),
                ..PpoConfig::default()
            };
            let trace = Agent::new(&config, 3)?.run_update_as(&batch, None, forced)?;
            assert_eq!(trace.epochs.len(), 10, "{forced:?}");
            assert!(
                trace.epochs[2..]
                    .iter()
                    .all(|e| e.ratio == trace.epochs[1].ratio)
            );
            assert_ne!(
                trace.epochs[1].ratio, trace.epochs[0].ratio,
                "one actor step"
            );
            assert!(trace.epochs[9].critic_loss < trace.epochs[1].critic_loss);

            let config = PpoConfig {
                critic_epochs: Some(1),
                ..PpoConfig::default()
            };
            let trace = Agent::new(&config, 3)?.run_update_as(&batch, None, forced)?;
            assert_eq!(trace.epochs.len(), 10, "{forced:?}");
            let critic: Vec<f32> = trace.epochs.iter().map(|e| e.critic_loss).collect();
            assert!(critic[2..].iter().all(|&l| l == critic[1]), "{critic:?}");
            assert_ne!(critic[1], critic[0], "one critic step");
            assert_ne!(trace.epochs[9].ratio, trace.epochs[1].ratio);
        }
        Ok(())
    }

    /// Batch sizes on both sides of every switch of gemm's paths and candle's sums
    /// (32-blocks, 64-blocks, N·out ≤ 256 for the horizontal kernel) and the ends.
    #[test]
    fn bit_for_bit_the_tensor_update_at_every_path_boundary() -> Result<(), PpoError> {
        if !plain_runs_here("bit_for_bit_the_tensor_update_at_every_path_boundary") {
            return Ok(());
        }
        let config = PpoConfig::default();
        let sizes = (3..=34)
            .chain(62..=66)
            .chain(126..=130)
            .chain(254..=258)
            .chain([319, 320, 321, 447, 448, 449, 500, 511, 512]);
        for n in sizes {
            compare(&config, n, 7)?;
        }
        Ok(())
    }

    /// The opt-in switches the plain path supports, other widths, and early stopping.
    #[test]
    fn bit_for_bit_the_tensor_update_with_switches() -> Result<(), PpoError> {
        if !plain_runs_here("bit_for_bit_the_tensor_update_with_switches") {
            return Ok(());
        }
        let base = PpoConfig::default();
        let configs = [
            PpoConfig {
                normalize_advantage: true,
                bootstrap_on_truncation: true,
                max_grad_norm: Some(0.5),
                ..base.clone()
            },
            PpoConfig {
                target_kl: Some(0.002),
                actor_lr: 0.05,
                ..base.clone()
            },
            PpoConfig {
                hidden_dim: 64,
                epochs: 3,
                ..base.clone()
            },
            PpoConfig {
                hidden_dim: 13,
                ..base.clone()
            },
            PpoConfig {
                epochs: 1,
                critic_epochs: Some(10),
                ..base.clone()
            },
            PpoConfig {
                epochs: 10,
                critic_epochs: Some(1),
                target_kl: Some(0.002),
                actor_lr: 0.05,
                ..base.clone()
            },
            PpoConfig {
                hidden_dim: 200,
                ..base
            },
        ];
        for config in &configs {
            for n in [21, 40, 129, 300] {
                compare(config, n, 3)?;
            }
        }
        Ok(())
    }

    /// `PPO_TUTOR_UPDATE=candle`'s setting on the seed's training: every update of a
    /// 20-episode CartPole run says candle and equals, bit for bit, the same run on the plain
    /// path, whose traces say plain (the setting itself is read once per process, so it is
    /// given here as the agents receive it; `tests/cli/ppo.rs` sets the variable).
    #[test]
    fn forcing_candle_gives_the_plain_numbers() -> Result<(), PpoError> {
        if !plain_runs_here("forcing_candle_gives_the_plain_numbers") {
            return Ok(());
        }
        let config = PpoConfig::default();
        let mut plain = Agent::new(&config, 11)?;
        let mut candle = Agent::new(&config, 11)?;
        let mut rng = NumpyRng::from_seed(11);
        for episode in 0..20 {
            let batch = walk(9 + 23 * episode, &mut rng);
            let a = plain.run_update_as(&batch, None, None)?;
            let b = candle.run_update_as(&batch, None, Some(UpdatePath::Candle))?;
            assert_eq!((a.path, b.path), (UpdatePath::Plain, UpdatePath::Candle));
            let a = UpdateTrace { path: b.path, ..a };
            assert_eq!(text(&a), text(&b), "episode {episode}");
        }
        assert_eq!(text(&plain.weights()?), text(&candle.weights()?));
        Ok(())
    }

    /// Configurations and batches the plain path leaves to the tensors, on any CPU: the
    /// conditions say candle, and so does the trace of an update.
    #[test]
    fn other_configurations_use_the_tensors() -> Result<(), PpoError> {
        let mut rng = NumpyRng::from_seed(0);
        let batch = walk(50, &mut rng);
        let base = PpoConfig::default();
        let candle = |config: &PpoConfig, batch: &Transitions| -> Result<(), PpoError> {
            let chosen = choose_path(&conditions(config, batch.len(), false), None);
            assert_eq!(
                chosen,
                UpdatePath::Candle,
                "{config:?}, n = {}",
                batch.len()
            );
            let trace = Agent::new(config, 0)?.run_update_as(batch, None, None)?;
            assert_eq!(trace.path, UpdatePath::Candle, "{config:?}");
            Ok(())
        };
        for config in [
            PpoConfig {
                entropy_coef: 0.01,
                ..base.clone()
            },
            PpoConfig {
                no_clip: true,
                ..base.clone()
            },
            PpoConfig {
                algorithm: crate::ppo::Algorithm::Reinforce,
                ..base.clone()
            },
        ] {
            candle(&config, &batch)?;
        }
        candle(&base, &walk(2, &mut rng))?;
        candle(&base, &walk(513, &mut rng))?;
        // a learner's losses (the ppo_losses exercise)
        assert!(conditions(&base, 50, true).learner_losses);
        assert_eq!(
            choose_path(&conditions(&base, 50, true), None),
            UpdatePath::Candle
        );
        // and the seed's configuration runs plain exactly where the CPU allows it
        assert_eq!(
            choose_path(&conditions(&base, 50, false), None) == UpdatePath::Plain,
            isa().is_some()
        );
        Ok(())
    }
}
