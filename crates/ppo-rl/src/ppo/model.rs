//! The two networks: the actor `π(a|s)` and the critic `V(s)`, as in the seed.
//!
//! ```text
//! PolicyNet: probs  = softmax(fc2(relu(fc1(states))))   states (N, 4) -> (N, 128) -> probs (N, 2)
//! ValueNet:  values = fc2(relu(fc1(states)))            states (N, 4) -> (N, 128) -> values (N, 1)
//! fc(x) = x · Wᵀ + b, W of shape (out, in) as PyTorch stores it, b of shape (out,)
//! ```
//!
//! Both layers of both networks start as PyTorch's `nn.Linear` does: every weight and bias
//! from `U(-1/√fan_in, 1/√fan_in)` (candle's `linear` would draw Kaiming-normal weights).
//! The draws come from a seeded [`NumpyRng`], so a seed gives the same network everywhere.
//!
//! ```
//! use candle_core::{Device, Tensor};
//! use ppo_rl::env::seeding::NumpyRng;
//! use ppo_rl::ppo::PolicyNet;
//!
//! let actor = PolicyNet::new(4, 128, 2, &mut NumpyRng::from_seed(0))?;
//! let states = Tensor::zeros((3, 4), candle_core::DType::F32, &Device::Cpu)?;
//! let probs = actor.forward(&states)?; // (3, 2), each row sums to 1
//! let row = &probs.to_vec2::<f32>()?[0];
//! assert!((row[0] + row[1] - 1.0).abs() < 1e-6);
//! # Ok::<(), candle_core::Error>(())
//! ```

use std::collections::BTreeMap;

use candle_core::{Device, Tensor, Var};
use serde::{Deserialize, Serialize};

use super::ops::{add_bias, relu};
use crate::env::seeding::NumpyRng;

/// One parameter as plain data: its shape (PyTorch's layout) and values in row-major order.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct WeightTensor {
    /// `[out, in]` for a weight, `[out]` for a bias.
    pub shape: Vec<usize>,
    /// The values, row-major.
    pub data: Vec<f32>,
}

/// Every parameter of an agent by PyTorch name (`actor.fc1.weight`, ..., `critic.fc2.bias`).
pub type NamedWeights = BTreeMap<String, WeightTensor>;

/// A fully connected layer `y = x · Wᵀ + b` whose parameters are trainable candle [`Var`]s.
#[derive(Debug, Clone)]
pub struct Linear {
    /// `W`, shape `(out, in)`.
    pub weight: Var,
    /// `b`, shape `(out,)`.
    pub bias: Var,
}

impl Linear {
    // ANCHOR: linear_init
    /// PyTorch's `nn.Linear(in_dim, out_dim)` initialisation: `kaiming_uniform_(a=√5)` for the
    /// weight, which is `U(-1/√in, 1/√in)`, and the same bound for the bias. The weight is
    /// drawn first, row by row, then the bias.
    ///
    /// # Errors
    /// Only if candle cannot allocate the tensors.
    pub fn pytorch_init(
        in_dim: usize,
        out_dim: usize,
        rng: &mut NumpyRng,
    ) -> candle_core::Result<Self> {
        let bound = 1.0 / (in_dim as f64).sqrt();
        let mut draw =
            |n: usize| -> Vec<f32> { (0..n).map(|_| rng.uniform(-bound, bound) as f32).collect() };
        let weight = draw(out_dim * in_dim);
        let bias = draw(out_dim);
        Self::from_data(in_dim, out_dim, weight, bias)
    }
    // ANCHOR_END: linear_init

    /// A layer holding the given values (`weight` row-major `(out, in)`).
    ///
    /// # Errors
    /// When the lengths do not match `out * in` and `out`.
    pub fn from_data(
        in_dim: usize,
        out_dim: usize,
        weight: Vec<f32>,
        bias: Vec<f32>,
    ) -> candle_core::Result<Self> {
        Ok(Self {
            weight: Var::from_vec(weight, (out_dim, in_dim), &Device::Cpu)?,
            bias: Var::from_vec(bias, out_dim, &Device::Cpu)?,
        })
    }

    /// `x · Wᵀ + b` for `x` of shape `(N, in)`, giving `(N, out)`.
    ///
    /// # Errors
    /// When `x`'s last dimension is not `in`.
    pub fn forward(&self, x: &Tensor) -> candle_core::Result<Tensor> {
        // add_bias is broadcast_add with a faster backward (see `ops`)
        add_bias(
            &x.matmul(&self.weight.as_tensor().t()?)?,
            self.bias.as_tensor(),
        )
    }

    /// The two parameters, weight first.
    #[must_use]
    pub fn vars(&self) -> [&Var; 2] {
        [&self.weight, &self.bias]
    }

    /// An independent layer holding the same values now (a clone shares the variables, so
    /// an optimizer step on the original would change it too).
    ///
    /// # Errors
    /// Only if candle cannot allocate the tensors.
    pub fn frozen_copy(&self) -> candle_core::Result<Self> {
        Ok(Self {
            weight: Var::from_tensor(&self.weight.as_tensor().copy()?)?,
            bias: Var::from_tensor(&self.bias.as_tensor().copy()?)?,
        })
    }
}

// ANCHOR: policy_net
/// The actor: `probs = softmax(fc2(relu(fc1(states))))`, one probability per action.
#[derive(Debug, Clone)]
pub struct PolicyNet {
    /// `Linear(state_dim, hidden_dim)`.
    pub fc1: Linear,
    /// `Linear(hidden_dim, action_dim)`.
    pub fc2: Linear,
}

impl PolicyNet {
    /// A freshly initialised actor (fc1 then fc2, as PyTorch builds them).
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
        let fc2 = Linear::pytorch_init(hidden_dim, action_dim, rng)?;
        Ok(Self { fc1, fc2 })
    }

    /// An independent copy of the actor as it is now (see [`Linear::frozen_copy`]).
    ///
    /// # Errors
    /// Only if candle cannot allocate the tensors.
    pub fn frozen_copy(&self) -> candle_core::Result<Self> {
        Ok(Self {
            fc1: self.fc1.frozen_copy()?,
            fc2: self.fc2.frozen_copy()?,
        })
    }

    /// `states (N, state_dim)` → `probs (N, action_dim)`.
    ///
    /// # Errors
    /// When `states` has the wrong width.
    pub fn forward(&self, states: &Tensor) -> candle_core::Result<Tensor> {
        let hidden = relu(&self.fc1.forward(states)?)?;
        candle_nn::ops::softmax(&self.fc2.forward(&hidden)?, 1)
    }
}
// ANCHOR_END: policy_net

// ANCHOR: value_net
/// The critic: `values = fc2(relu(fc1(states)))`, one state value `V(s)` per row.
#[derive(Debug, Clone)]
pub struct ValueNet {
    /// `Linear(state_dim, hidden_dim)`.
    pub fc1: Linear,
    /// `Linear(hidden_dim, 1)`.
    pub fc2: Linear,
}

impl ValueNet {
    /// A freshly initialised critic.
    ///
    /// # Errors
    /// Only if candle cannot allocate the tensors.
    pub fn new(
        state_dim: usize,
        hidden_dim: usize,
        rng: &mut NumpyRng,
    ) -> candle_core::Result<Self> {
        let fc1 = Linear::pytorch_init(state_dim, hidden_dim, rng)?;
        let fc2 = Linear::pytorch_init(hidden_dim, 1, rng)?;
        Ok(Self { fc1, fc2 })
    }

    /// `states (N, state_dim)` → `values (N, 1)`.
    ///
    /// # Errors
    /// When `states` has the wrong width.
    pub fn forward(&self, states: &Tensor) -> candle_core::Result<Tensor> {
        let hidden = relu(&self.fc1.forward(states)?)?;
        self.fc2.forward(&hidden)
    }
}
// ANCHOR_END: value_net

/// The actor's weights copied out of candle, for acting on one observation at a time.
///
/// Computes exactly the formula of [`PolicyNet::forward`] with plain loops: a 4-128-2
/// network is ~1k multiply-adds, far below the cost of building tensors for it. (Its sums
/// run in order, so its probabilities can differ from the tensor version's in the last
/// bit; they are what the agent samples from, and they stay the same from version to
/// version.)
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ActorSnapshot {
    w1: Vec<f32>,
    b1: Vec<f32>,
    w2: Vec<f32>,
    b2: Vec<f32>,
    state_dim: usize,
    /// `w1` transposed, `(state_dim, hidden)`, for [`ActorSnapshot::probs2`].
    w1t: Vec<f32>,
}

/// The widest hidden layer [`ActorSnapshot::probs2`] keeps on the stack.
const MAX_STACK_HIDDEN: usize = 512;

impl ActorSnapshot {
    /// Copies the current weights of `actor`.
    ///
    /// # Errors
    /// Only if candle cannot read the tensors.
    pub fn of(actor: &PolicyNet) -> candle_core::Result<Self> {
        let flat = |v: &Var| v.as_tensor().flatten_all()?.to_vec1::<f32>();
        let state_dim = actor
            .fc1
            .weight
            .as_tensor()
            .dims()
            .get(1)
            .copied()
            .unwrap_or(0);
        Ok(Self::from_parts(
            flat(&actor.fc1.weight)?,
            flat(&actor.fc1.bias)?,
            flat(&actor.fc2.weight)?,
            flat(&actor.fc2.bias)?,
            state_dim,
        ))
    }

    /// A snapshot of the given weights (PyTorch layouts, row-major), `state_dim` inputs.
    pub(crate) fn from_parts(
        w1: Vec<f32>,
        b1: Vec<f32>,
        w2: Vec<f32>,
        b2: Vec<f32>,
        state_dim: usize,
    ) -> Self {
        let hidden = b1.len();
        let mut w1t = vec![0.0; w1.len()];
        if w1.len() == hidden * state_dim {
            for (j, row) in w1.chunks_exact(state_dim.max(1)).enumerate() {
                for (p, &w) in row.iter().enumerate() {
                    w1t[p * hidden + j] = w;
                }
            }
        }
        Self {
            w1,
            b1,
            w2,
            b2,
            state_dim,
            w1t,
        }
    }

    /// The hidden layer's width (`fc1`'s outputs).
    #[must_use]
    pub fn hidden_dim(&self) -> usize {
        self.b1.len()
    }

    /// Every parameter, flattened in PyTorch's order (`fc1.weight`, `fc1.bias`,
    /// `fc2.weight`, `fc2.bias`, each row-major): the layout of
    /// [`SurrogateGradients`](crate::ppo::SurrogateGradients), so that `θ + α · g` is an
    /// entry-by-entry sum.
    #[must_use]
    pub fn parameters(&self) -> Vec<f32> {
        [&self.w1, &self.b1, &self.w2, &self.b2]
            .into_iter()
            .flatten()
            .copied()
            .collect()
    }

    /// `softmax(fc2(relu(fc1(state))))` for one state, in f32.
    #[must_use]
    pub fn probs(&self, state: &[f32]) -> Vec<f32> {
        if let Some(probs) = self.probs2(state) {
            return probs.to_vec();
        }
        let hidden: Vec<f32> = self
            .w1
            .chunks_exact(self.state_dim.max(1))
            .zip(&self.b1)
            .map(|(row, b)| (dot(row, state) + b).max(0.0))
            .collect();
        let logits: Vec<f32> = self
            .w2
            .chunks_exact(hidden.len().max(1))
            .zip(&self.b2)
            .map(|(row, b)| dot(row, &hidden) + b)
            .collect();
        softmax(&logits)
    }

    /// [`ActorSnapshot::probs`] for CartPole's shapes (4 inputs, 2 actions, a hidden layer
    /// of at most 512) without allocating: the same operations in the same order (each
    /// unit's sum runs over its inputs in order, from `-0.0` as `Iterator::sum`), only the
    /// independent units side by side. `None` for other shapes.
    #[must_use]
    pub(crate) fn probs2(&self, state: &[f32]) -> Option<[f32; 2]> {
        let h = self.b1.len();
        let shapes_fit = self.state_dim == 4
            && state.len() == 4
            && h <= MAX_STACK_HIDDEN
            && self.w1t.len() == 4 * h
            && self.w2.len() == 2 * h
            && self.b2.len() == 2;
        if !shapes_fit {
            return None;
        }
        let mut buffer = [0.0_f32; MAX_STACK_HIDDEN];
        let hidden = &mut buffer[..h];
        let (c0, rest) = self.w1t.split_at(h);
        let (c1, rest) = rest.split_at(h);
        let (c2, c3) = rest.split_at(h);
        let (s0, s1, s2, s3) = (state[0], state[1], state[2], state[3]);
        for (((((y, &a), &b), &c), &d), &bias) in hidden
            .iter_mut()
            .zip(c0)
            .zip(c1)
            .zip(c2)
            .zip(c3)
            .zip(&self.b1)
        {
            let dot = (((-0.0 + a * s0) + b * s1) + c * s2) + d * s3;
            *y = (dot + bias).max(0.0);
        }
        let (w0, w1) = self.w2.split_at(h);
        let (mut z0, mut z1) = (-0.0_f32, -0.0_f32);
        for ((&a, &b), &x) in w0.iter().zip(w1).zip(hidden.iter()) {
            z0 += a * x;
            z1 += b * x;
        }
        let logits = [z0 + self.b2[0], z1 + self.b2[1]];
        let max = f32::max(f32::max(f32::NEG_INFINITY, logits[0]), logits[1]);
        let exps = [
            exp_of_difference(logits[0], max),
            exp_of_difference(logits[1], max),
        ];
        let sum = (-0.0 + exps[0]) + exps[1];
        Some([exps[0] / sum, exps[1] / sum])
    }
}

/// `(z - max).exp()`, without calling `exp` where the difference is zero (`exp(±0) = 1`
/// exactly).
#[inline]
fn exp_of_difference(z: f32, max: f32) -> f32 {
    let d = z - max;
    if d == 0.0 { 1.0 } else { d.exp() }
}

fn dot(a: &[f32], b: &[f32]) -> f32 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// `exp(z - max z) / Σ exp(z - max z)`, as candle's `softmax` computes it.
fn softmax(logits: &[f32]) -> Vec<f32> {
    let max = logits.iter().copied().fold(f32::NEG_INFINITY, f32::max);
    let exps: Vec<f32> = logits.iter().map(|z| (z - max).exp()).collect();
    let sum: f32 = exps.iter().sum();
    exps.iter().map(|e| e / sum).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn init_is_in_pytorch_bounds_and_seeded() -> candle_core::Result<()> {
        let net = PolicyNet::new(4, 128, 2, &mut NumpyRng::from_seed(3))?;
        let w1 = net.fc1.weight.as_tensor().flatten_all()?.to_vec1::<f32>()?;
        assert!(w1.iter().all(|w| w.abs() <= 0.5));
        let w2 = net.fc2.weight.as_tensor().flatten_all()?.to_vec1::<f32>()?;
        let bound = 1.0 / 128f32.sqrt();
        assert!(w2.iter().all(|w| w.abs() <= bound));
        assert!(
            w2.iter().any(|w| w.abs() > bound * 0.9),
            "uses the full range"
        );
        let again = PolicyNet::new(4, 128, 2, &mut NumpyRng::from_seed(3))?;
        let w1b = again
            .fc1
            .weight
            .as_tensor()
            .flatten_all()?
            .to_vec1::<f32>()?;
        assert_eq!(w1, w1b);
        Ok(())
    }

    /// The allocation-free path gives the generic loops' numbers, bit for bit.
    #[test]
    fn probs2_is_the_generic_formula() -> candle_core::Result<()> {
        assert_eq!(0.0_f32.exp().to_bits(), 1.0_f32.to_bits());
        assert_eq!((-0.0_f32).exp().to_bits(), 1.0_f32.to_bits());
        let mut rng = NumpyRng::from_seed(5);
        for hidden in [1, 7, 128, 200] {
            let net = PolicyNet::new(4, hidden, 2, &mut rng)?;
            let snap = ActorSnapshot::of(&net)?;
            let generic = ActorSnapshot {
                w1t: Vec::new(), // no fast path
                ..snap.clone()
            };
            for _ in 0..500 {
                let state = [2.4, 3.0, 0.21, 3.5].map(|s: f64| (rng.uniform(-s, s)) as f32);
                let fast = snap.probs2(&state).map(|p| p.map(f32::to_bits));
                let slow = generic.probs(&state);
                assert!(generic.probs2(&state).is_none());
                assert_eq!(fast, Some([slow[0].to_bits(), slow[1].to_bits()]));
            }
        }
        Ok(())
    }

    #[test]
    fn snapshot_matches_candle_forward() -> candle_core::Result<()> {
        let net = PolicyNet::new(4, 128, 2, &mut NumpyRng::from_seed(1))?;
        let snap = ActorSnapshot::of(&net)?;
        let state = [0.03_f32, -0.4, 0.1, 0.7];
        let t = Tensor::from_slice(&state, (1, 4), &Device::Cpu)?;
        let want = net.forward(&t)?.to_vec2::<f32>()?;
        let got = snap.probs(&state);
        for (a, b) in got.iter().zip(&want[0]) {
            assert!((a - b).abs() < 1e-6, "{got:?} vs {want:?}");
        }
        Ok(())
    }
}
