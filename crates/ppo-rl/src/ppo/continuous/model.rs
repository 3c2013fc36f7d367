//! The book's `PolicyNetContinuous`: one hidden layer, two heads, `μ` and `σ` of a Gaussian.
//!
//! ```text
//! h = relu(fc1(states))            states (N, 3) -> (N, H)
//! μ = 2 · tanh(fc_mu(h))           (N, 1), the mean torque, in (-2, 2)
//! σ = softplus(fc_std(h))          (N, 1), the standard deviation, > 0
//! softplus(x) = x                  if x > 20      (PyTorch's beta 1, threshold 20)
//!             = log1p(exp(x))      otherwise
//! ∂softplus/∂x = 1 if x > 20, else eˣ / (eˣ + 1)
//! ```
//!
//! The layers are [`Linear`]s initialised as PyTorch's `nn.Linear` (fc1, fc_mu, fc_std, in
//! the order PyTorch builds them). `softplus` is a candle custom op computing PyTorch's
//! formula (`log1p`, not `log(1 + ·)`, which loses digits when `eˣ` is small).
//!
//! ```
//! use candle_core::{Device, Tensor};
//! use ppo_rl::env::seeding::NumpyRng;
//! use ppo_rl::ppo::PolicyNetContinuous;
//!
//! let actor = PolicyNetContinuous::new(3, 128, 1, &mut NumpyRng::from_seed(0))?;
//! let states = Tensor::zeros((5, 3), candle_core::DType::F32, &Device::Cpu)?;
//! let (mu, std) = actor.forward(&states)?; // (5, 1) each
//! assert_eq!(mu.dims(), &[5, 1]);
//! assert!(std.flatten_all()?.to_vec1::<f32>()?.iter().all(|s| *s > 0.0));
//! # Ok::<(), candle_core::Error>(())
//! ```

use candle_core::{CpuStorage, CustomOp1, CustomOp2, Layout, Shape, Tensor, Var};

use crate::env::seeding::NumpyRng;
use crate::ppo::model::Linear;
use crate::ppo::ops::relu;

/// PyTorch's `F.softplus` threshold: above it, `softplus(x) = x`.
pub(crate) const SOFTPLUS_THRESHOLD: f32 = 20.0;

// ANCHOR: policy_net_continuous
/// The actor: `μ = 2 · tanh(fc_mu(h))`, `σ = softplus(fc_std(h))`, `h = relu(fc1(s))`.
#[derive(Debug, Clone)]
pub struct PolicyNetContinuous {
    /// `Linear(state_dim, hidden_dim)`.
    pub fc1: Linear,
    /// `Linear(hidden_dim, action_dim)`, the mean's head.
    pub fc_mu: Linear,
    /// `Linear(hidden_dim, action_dim)`, the standard deviation's head.
    pub fc_std: Linear,
}

impl PolicyNetContinuous {
    /// A freshly initialised actor (fc1, fc_mu, fc_std, as PyTorch builds them).
    ///
    /// # Errors
    /// Only if candle cannot allocate the tensors.
    pub fn new(
        state_dim: usize,
        hidden_dim: usize,
        action_dim: usize,
        rng: &mut NumpyRng,
    ) -> candle_core::Result<Self> {
        let fc1 = Linear::pytorch_init(state_dim, hidden_dim, rng)?;
        let fc_mu = Linear::pytorch_init(hidden_dim, action_dim, rng)?;
        let fc_std = Linear::pytorch_init(hidden_dim, action_dim, rng)?;
        Ok(Self { fc1, fc_mu, fc_std })
    }

    /// `states (N, state_dim)` → `(μ, σ)`, each `(N, action_dim)`.
    ///
    /// # Errors
    /// When `states` has the wrong width.
    pub fn forward(&self, states: &Tensor) -> candle_core::Result<(Tensor, Tensor)> {
        let hidden = relu(&self.fc1.forward(states)?)?;
        let mu = (self.fc_mu.forward(&hidden)?.tanh()? * 2.0)?;
        let std = softplus(&self.fc_std.forward(&hidden)?)?;
        Ok((mu, std))
    }
}
// ANCHOR_END: policy_net_continuous

impl PolicyNetContinuous {
    /// The six parameters in PyTorch's `parameters()` order (what the actor's Adam steps).
    #[must_use]
    pub fn vars(&self) -> Vec<Var> {
        [&self.fc1, &self.fc_mu, &self.fc_std]
            .iter()
            .flat_map(|l| l.vars().map(Var::clone))
            .collect()
    }
}

/// PyTorch's `F.softplus(x)` (beta 1, threshold 20), elementwise and differentiable.
///
/// ```
/// use candle_core::{Device, Tensor};
/// use ppo_rl::ppo::continuous::softplus;
///
/// let x = Tensor::new(&[0.0f32, 25.0, -30.0], &Device::Cpu)?;
/// let y = softplus(&x)?.to_vec1::<f32>()?;
/// assert!((y[0] - 2f32.ln()).abs() < 1e-7); // log(1 + e⁰)
/// assert_eq!(y[1], 25.0); // above the threshold: x itself
/// assert!(y[2] > 0.0 && y[2] < 1e-12); // log1p keeps the tiny value
/// # Ok::<(), candle_core::Error>(())
/// ```
///
/// # Errors
/// For a tensor that is not f32.
pub fn softplus(x: &Tensor) -> candle_core::Result<Tensor> {
    x.contiguous()?.apply_op1(Softplus)
}

/// `softplus` of one number, the formula of [`softplus`].
#[must_use]
pub fn softplus_f32(x: f32) -> f32 {
    if x > SOFTPLUS_THRESHOLD {
        x
    } else {
        x.exp().ln_1p()
    }
}

/// The contiguous f32 values of a storage.
fn values<'a>(s: &'a CpuStorage, l: &Layout, op: &'static str) -> candle_core::Result<&'a [f32]> {
    let CpuStorage::F32(v) = s else {
        candle_core::bail!("{op}: only f32 tensors are supported")
    };
    match l.contiguous_offsets() {
        Some((start, end)) => Ok(&v[start..end]),
        None => candle_core::bail!("{op}: the tensor must be contiguous"),
    }
}

struct Softplus;

impl CustomOp1 for Softplus {
    fn name(&self) -> &'static str {
        "softplus"
    }

    fn cpu_fwd(&self, s: &CpuStorage, l: &Layout) -> candle_core::Result<(CpuStorage, Shape)> {
        let x = values(s, l, "softplus")?;
        let y = x.iter().map(|&v| softplus_f32(v)).collect();
        Ok((CpuStorage::F32(y), l.shape().clone()))
    }

    fn bwd(
        &self,
        arg: &Tensor,
        _res: &Tensor,
        grad: &Tensor,
    ) -> candle_core::Result<Option<Tensor>> {
        Ok(Some(
            grad.contiguous()?
                .apply_op2_no_bwd(&arg.contiguous()?, &SoftplusGrad)?,
        ))
    }
}

/// `grad · eˣ / (eˣ + 1)` (or `grad` above the threshold), as PyTorch's `softplus_backward`.
struct SoftplusGrad;

impl CustomOp2 for SoftplusGrad {
    fn name(&self) -> &'static str {
        "softplus-grad"
    }

    fn cpu_fwd(
        &self,
        s1: &CpuStorage,
        l1: &Layout,
        s2: &CpuStorage,
        l2: &Layout,
    ) -> candle_core::Result<(CpuStorage, Shape)> {
        let grad = values(s1, l1, "softplus-grad")?;
        let x = values(s2, l2, "softplus-grad")?;
        if grad.len() != x.len() {
            candle_core::bail!("softplus-grad: {:?} vs {:?}", l1.dims(), l2.dims())
        }
        let out = grad
            .iter()
            .zip(x)
            .map(|(&g, &v)| {
                if v > SOFTPLUS_THRESHOLD {
                    g
                } else {
                    let z = v.exp();
                    g * z / (z + 1.0)
                }
            })
            .collect();
        Ok((CpuStorage::F32(out), l1.shape().clone()))
    }
}

/// The actor's weights copied out of candle, for acting on one observation at a time.
///
/// Computes the formula of [`PolicyNetContinuous::forward`] with plain loops (a 3-128-1-1
/// network), far cheaper than building tensors for one row.
#[derive(Debug, Clone, Default)]
pub struct ContinuousActorSnapshot {
    w1: Vec<f32>,
    b1: Vec<f32>,
    w_mu: Vec<f32>,
    b_mu: f32,
    w_std: Vec<f32>,
    b_std: f32,
    state_dim: usize,
    /// `w1` transposed, `(state_dim, hidden)`, for one state's units side by side.
    w1t: Vec<f32>,
}

impl ContinuousActorSnapshot {
    /// Copies the current weights of `actor` (its first action dimension).
    ///
    /// # Errors
    /// Only if candle cannot read the tensors.
    pub fn of(actor: &PolicyNetContinuous) -> candle_core::Result<Self> {
        let flat = |v: &Var| v.as_tensor().flatten_all()?.to_vec1::<f32>();
        let hidden = actor.fc1.bias.elem_count();
        let first_row = |v: &Var| -> candle_core::Result<Vec<f32>> {
            Ok(flat(v)?.into_iter().take(hidden).collect())
        };
        let first =
            |v: &Var| -> candle_core::Result<f32> { Ok(flat(v)?.first().copied().unwrap_or(0.0)) };
        let state_dim = actor
            .fc1
            .weight
            .as_tensor()
            .dims()
            .get(1)
            .copied()
            .unwrap_or(0);
        let w1 = flat(&actor.fc1.weight)?;
        let mut w1t = vec![0.0; w1.len()];
        for (j, row) in w1.chunks_exact(state_dim.max(1)).enumerate() {
            for (p, &w) in row.iter().enumerate() {
                w1t[p * hidden + j] = w;
            }
        }
        Ok(Self {
            w1,
            b1: flat(&actor.fc1.bias)?,
            w_mu: first_row(&actor.fc_mu.weight)?,
            b_mu: first(&actor.fc_mu.bias)?,
            w_std: first_row(&actor.fc_std.weight)?,
            b_std: first(&actor.fc_std.bias)?,
            state_dim,
            w1t,
        })
    }

    /// `(μ, σ)` for one state, in f32.
    #[must_use]
    pub fn mu_std(&self, state: &[f32]) -> (f32, f32) {
        let h = self.b1.len();
        if h > MAX_STACK_HIDDEN {
            let mut hidden = vec![0.0; h];
            return self.mu_std_in(state, &mut hidden);
        }
        // called once per environment step: the hidden layer stays on the stack
        let mut buffer = [0.0_f32; MAX_STACK_HIDDEN];
        self.mu_std_in(state, &mut buffer[..h])
    }

    /// [`ContinuousActorSnapshot::mu_std`] with the hidden layer in `hidden`. Every sum runs
    /// over its inputs in order from `-0.0` (as `Iterator::sum`); the two heads' sums run
    /// side by side.
    fn mu_std_in(&self, state: &[f32], hidden: &mut [f32]) -> (f32, f32) {
        let h = hidden.len();
        if let ([s0, s1, s2], true) = (state, self.w1t.len() == 3 * h && self.b1.len() == h) {
            // Pendulum's 3 inputs: the same sums, the units side by side (W1 transposed)
            let (c0, rest) = self.w1t.split_at(h);
            let (c1, c2) = rest.split_at(h);
            for j in 0..h {
                let dot = ((-0.0 + c0[j] * s0) + c1[j] * s1) + c2[j] * s2;
                hidden[j] = (dot + self.b1[j]).max(0.0);
            }
        } else {
            for ((y, row), b) in hidden
                .iter_mut()
                .zip(self.w1.chunks_exact(self.state_dim.max(1)))
                .zip(&self.b1)
            {
                *y = (dot(row, state) + b).max(0.0);
            }
        }
        let (mut z_mu, mut z_std) = (-0.0_f32, -0.0_f32);
        for ((&a, &b), &x) in self.w_mu.iter().zip(&self.w_std).zip(hidden.iter()) {
            z_mu += a * x;
            z_std += b * x;
        }
        let mu = 2.0 * (z_mu + self.b_mu).tanh();
        let std = softplus_f32(z_std + self.b_std);
        (mu, std)
    }
}

/// The widest hidden layer [`ContinuousActorSnapshot::mu_std`] keeps on the stack.
const MAX_STACK_HIDDEN: usize = 512;

fn dot(a: &[f32], b: &[f32]) -> f32 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

#[cfg(test)]
mod tests {
    use super::*;
    use candle_core::Device;

    #[test]
    fn snapshot_matches_candle_forward() -> candle_core::Result<()> {
        let net = PolicyNetContinuous::new(3, 128, 1, &mut NumpyRng::from_seed(2))?;
        let snap = ContinuousActorSnapshot::of(&net)?;
        let state = [0.6_f32, -0.8, 1.5];
        let t = Tensor::from_slice(&state, (1, 3), &Device::Cpu)?;
        let (mu, std) = net.forward(&t)?;
        let (m, s) = snap.mu_std(&state);
        let want_mu = mu.flatten_all()?.to_vec1::<f32>()?[0];
        let want_std = std.flatten_all()?.to_vec1::<f32>()?[0];
        assert!((m - want_mu).abs() < 1e-6, "{m} vs {want_mu}");
        assert!((s - want_std).abs() < 1e-6, "{s} vs {want_std}");
        Ok(())
    }

    /// `mu_std` is the formula with `Iterator::sum`'s dot products, bit for bit, on the
    /// stack and off it.
    #[test]
    fn mu_std_is_the_formula_with_iterator_sums() -> candle_core::Result<()> {
        for hidden in [1, 7, 128, 600] {
            let net = PolicyNetContinuous::new(3, hidden, 1, &mut NumpyRng::from_seed(4))?;
            let snap = ContinuousActorSnapshot::of(&net)?;
            let mut rng = NumpyRng::from_seed(5);
            for _ in 0..200 {
                let state = [0.0_f32; 3].map(|_| rng.uniform(-8.0, 8.0) as f32);
                let h: Vec<f32> = snap
                    .w1
                    .chunks_exact(3)
                    .zip(&snap.b1)
                    .map(|(row, b)| (dot(row, &state) + b).max(0.0))
                    .collect();
                let mu = 2.0 * (dot(&snap.w_mu, &h) + snap.b_mu).tanh();
                let std = softplus_f32(dot(&snap.w_std, &h) + snap.b_std);
                let (m, s) = snap.mu_std(&state);
                assert_eq!((m.to_bits(), s.to_bits()), (mu.to_bits(), std.to_bits()));
            }
        }
        Ok(())
    }

    /// The backward pass is `sigmoid(x)` below the threshold and 1 above it.
    #[test]
    fn softplus_gradient_is_the_sigmoid() -> candle_core::Result<()> {
        let x = Var::new(&[-3.0f32, 0.0, 2.0, 21.0], &Device::Cpu)?;
        let grads = softplus(x.as_tensor())?.sum_all()?.backward()?;
        let g = grads
            .get(x.as_tensor())
            .map(|t| t.to_vec1::<f32>())
            .transpose()?
            .unwrap_or_default();
        let sigmoid = |v: f32| 1.0 / (1.0 + (-v).exp());
        for (gi, v) in g.iter().zip([-3.0f32, 0.0, 2.0]) {
            assert!((gi - sigmoid(v)).abs() < 1e-6, "{gi} vs {}", sigmoid(v));
        }
        assert_eq!(g[3], 1.0);
        Ok(())
    }

    #[test]
    fn init_draws_fc1_then_fc_mu_then_fc_std() -> candle_core::Result<()> {
        let net = PolicyNetContinuous::new(3, 4, 1, &mut NumpyRng::from_seed(9))?;
        let mut rng = NumpyRng::from_seed(9);
        let fc1 = Linear::pytorch_init(3, 4, &mut rng)?;
        let fc_mu = Linear::pytorch_init(4, 1, &mut rng)?;
        let fc_std = Linear::pytorch_init(4, 1, &mut rng)?;
        for (a, b) in [
            (&net.fc1, &fc1),
            (&net.fc_mu, &fc_mu),
            (&net.fc_std, &fc_std),
        ] {
            let va = a.weight.as_tensor().flatten_all()?.to_vec1::<f32>()?;
            let vb = b.weight.as_tensor().flatten_all()?.to_vec1::<f32>()?;
            assert_eq!(va, vb);
        }
        Ok(())
    }
}
