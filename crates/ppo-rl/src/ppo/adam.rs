//! `torch.optim.Adam` (betas 0.9/0.999, eps 1e-8, no weight decay), step for step.
//!
//! For each parameter θ with gradient g, at step t (from 1), in PyTorch's operation order:
//!
//! ```text
//! m ← m + (1 - β₁)(g - m)                 (lerp)
//! v ← β₂ v + (1 - β₂) g²
//! θ ← θ - lr / (1 - β₁ᵗ) · m / (√v / √(1 - β₂ᵗ) + ε)
//! ```
//!
//! The moments live in plain `Vec<f32>`s and the arithmetic is f32 with the scalars rounded
//! to f32 as PyTorch's CPU kernels do, so weights agree with PyTorch to float rounding.
//! (candle-nn's `AdamW` with `weight_decay: 0.0` is the same formula in another order.)
//!
//! ```
//! use candle_core::{Device, Tensor, Var};
//! use ppo_rl::ppo::Adam;
//!
//! let x = Var::new(&[1.0f32, -2.0], &Device::Cpu)?;
//! let mut adam = Adam::new(vec![x.clone()], 0.1);
//! let loss = x.as_tensor().sqr()?.sum_all()?; // gradient 2x
//! adam.step(&loss.backward()?, None)?;
//! // the first step moves every coordinate by lr against its gradient's sign
//! let after = x.as_tensor().to_vec1::<f32>()?;
//! assert!((after[0] - 0.9).abs() < 1e-6 && (after[1] + 1.9).abs() < 1e-6);
//! # Ok::<(), candle_core::Error>(())
//! ```

use candle_core::backprop::GradStore;
use candle_core::{Tensor, Var};

/// Adam over a fixed list of parameters, with its own first and second moments.
#[derive(Debug, Clone)]
pub struct Adam {
    vars: Vec<Var>,
    first_moment: Vec<Vec<f32>>,
    second_moment: Vec<Vec<f32>>,
    step_t: i32,
    lr: f64,
    beta1: f64,
    beta2: f64,
    eps: f64,
}

impl Adam {
    /// `torch.optim.Adam(params, lr=lr)`: fresh state (zero moments, step 0).
    #[must_use]
    pub fn new(vars: Vec<Var>, lr: f64) -> Self {
        let zeros: Vec<Vec<f32>> = vars.iter().map(|v| vec![0.0; v.elem_count()]).collect();
        Self {
            vars,
            first_moment: zeros.clone(),
            second_moment: zeros,
            step_t: 0,
            lr,
            beta1: 0.9,
            beta2: 0.999,
            eps: 1e-8,
        }
    }

    /// The learning rate.
    #[must_use]
    pub fn learning_rate(&self) -> f64 {
        self.lr
    }

    /// Steps taken so far.
    #[must_use]
    pub fn steps(&self) -> i32 {
        self.step_t
    }

    /// One `optimizer.step()` with the gradients of `grads`; parameters without a gradient
    /// are skipped, as PyTorch skips `grad is None`. With `max_grad_norm`, first scales all
    /// gradients as `torch.nn.utils.clip_grad_norm_` does.
    ///
    /// # Errors
    /// Only if candle cannot read a gradient or write a parameter.
    pub fn step(
        &mut self,
        grads: &GradStore,
        max_grad_norm: Option<f64>,
    ) -> candle_core::Result<()> {
        let mut all_grads = Vec::with_capacity(self.vars.len());
        for var in &self.vars {
            let g = match grads.get(var.as_tensor()) {
                Some(g) => Some(g.flatten_all()?.to_vec1::<f32>()?),
                None => None,
            };
            all_grads.push(g);
        }
        let scalars = self.begin_step(&mut all_grads, max_grad_norm);
        for (i, grad) in all_grads.iter().enumerate() {
            let Some(grad) = grad else { continue };
            let var = &self.vars[i];
            let mut theta = var.as_tensor().flatten_all()?.to_vec1::<f32>()?;
            let (m, v) = (&mut self.first_moment[i], &mut self.second_moment[i]);
            scalars.apply(grad, m, v, &mut theta);
            var.set(&Tensor::from_vec(theta, var.shape(), var.device())?)?;
        }
        Ok(())
    }

    /// [`Adam::step`] on plain data: `grads[i]` and `params[i]` belong to the `i`-th variable
    /// given to [`Adam::new`] (flattened, row-major), and `params` are updated in place; the
    /// variables themselves are not touched. The arithmetic is `step`'s, line for line.
    ///
    /// # Errors
    /// When the counts or lengths do not match the variables.
    pub(crate) fn step_params(
        &mut self,
        grads: &mut [Option<Vec<f32>>],
        params: &mut [&mut [f32]],
        max_grad_norm: Option<f64>,
    ) -> candle_core::Result<()> {
        let lengths_match = grads.len() == self.vars.len()
            && params.len() == self.vars.len()
            && self
                .vars
                .iter()
                .zip(grads.iter())
                .zip(params.iter())
                .all(|((var, g), p)| {
                    p.len() == var.elem_count() && g.as_ref().is_none_or(|g| g.len() == p.len())
                });
        if !lengths_match {
            candle_core::bail!("adam: gradients or parameters do not match the variables")
        }
        let scalars = self.begin_step(grads, max_grad_norm);
        for (i, (grad, theta)) in grads.iter().zip(params.iter_mut()).enumerate() {
            let Some(grad) = grad else { continue };
            let (m, v) = (&mut self.first_moment[i], &mut self.second_moment[i]);
            scalars.apply(grad, m, v, theta);
        }
        Ok(())
    }

    /// Clips the gradients if asked, counts the step and rounds its scalars to f32.
    fn begin_step(
        &mut self,
        all_grads: &mut [Option<Vec<f32>>],
        max_grad_norm: Option<f64>,
    ) -> StepScalars {
        if let Some(max_norm) = max_grad_norm {
            clip_grad_norm(all_grads, max_norm);
        }
        self.step_t += 1;
        let bias_correction1 = 1.0 - self.beta1.powi(self.step_t);
        let bias_correction2 = 1.0 - self.beta2.powi(self.step_t);
        StepScalars {
            step_size: (self.lr / bias_correction1) as f32,
            bias_correction2_sqrt: bias_correction2.sqrt() as f32,
            w1: (1.0 - self.beta1) as f32,
            b2: self.beta2 as f32,
            w2: (1.0 - self.beta2) as f32,
            eps: self.eps as f32,
        }
    }
}

/// One step's scalars, rounded to f32 as PyTorch's kernels use them.
struct StepScalars {
    step_size: f32,
    bias_correction2_sqrt: f32,
    w1: f32,
    b2: f32,
    w2: f32,
    eps: f32,
}

impl StepScalars {
    /// The moment updates and the parameter step for one parameter tensor.
    #[inline(always)]
    fn apply(&self, grad: &[f32], m: &mut [f32], v: &mut [f32], theta: &mut [f32]) {
        let Self {
            step_size,
            bias_correction2_sqrt,
            w1,
            b2,
            w2,
            eps,
        } = *self;
        for (k, &g) in grad.iter().enumerate() {
            m[k] += w1 * (g - m[k]);
            v[k] = v[k] * b2 + w2 * g * g;
            let denom = v[k].sqrt() / bias_correction2_sqrt + eps;
            theta[k] += -step_size * m[k] / denom;
        }
    }
}

/// `torch.nn.utils.clip_grad_norm_`: if the global L2 norm of all gradients exceeds
/// `max_norm`, scale them all by `max_norm / (norm + 1e-6)`.
fn clip_grad_norm(grads: &mut [Option<Vec<f32>>], max_norm: f64) {
    let sum_sq: f32 = grads.iter().flatten().flatten().map(|g| g * g).sum();
    let total_norm = sum_sq.sqrt();
    let clip_coef = (max_norm as f32 / (total_norm + 1e-6)).min(1.0);
    for g in grads.iter_mut().flatten().flatten() {
        *g *= clip_coef;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use candle_core::Device;

    /// Provenance: torch 2.x, `p = torch.tensor([0.5, -1.5], requires_grad=True)`,
    /// `opt = torch.optim.Adam([p], lr=0.01)`, three steps of `(p**3).sum().backward()`.
    /// Recomputed here from the formula in f64 (the same recurrence), to 1e-6.
    #[test]
    fn three_steps_follow_the_formula() -> candle_core::Result<()> {
        let p = Var::new(&[0.5f32, -1.5], &Device::Cpu)?;
        let mut adam = Adam::new(vec![p.clone()], 0.01);
        let mut want = [0.5f64, -1.5];
        let (mut m, mut v) = ([0.0f64; 2], [0.0f64; 2]);
        for t in 1..=3 {
            let loss = p.as_tensor().powf(3.0)?.sum_all()?;
            adam.step(&loss.backward()?, None)?;
            for k in 0..2 {
                let g = 3.0 * want[k] * want[k];
                m[k] = 0.9 * m[k] + 0.1 * g;
                v[k] = 0.999 * v[k] + 0.001 * g * g;
                let mh = m[k] / (1.0 - 0.9f64.powi(t));
                let vh = v[k] / (1.0 - 0.999f64.powi(t));
                want[k] -= 0.01 * mh / (vh.sqrt() + 1e-8);
            }
        }
        let got = p.as_tensor().to_vec1::<f32>()?;
        for k in 0..2 {
            assert!(
                (f64::from(got[k]) - want[k]).abs() < 1e-6,
                "{got:?} {want:?}"
            );
        }
        Ok(())
    }

    #[test]
    fn clipping_scales_to_the_max_norm() {
        let mut g = vec![Some(vec![3.0f32, 0.0]), None, Some(vec![4.0])];
        clip_grad_norm(&mut g, 1.0);
        let flat: Vec<f32> = g.into_iter().flatten().flatten().collect();
        assert!((flat[0] - 0.6).abs() < 1e-6 && (flat[2] - 0.8).abs() < 1e-6);
    }
}
