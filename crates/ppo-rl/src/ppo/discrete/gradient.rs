//! The bridge from the policy gradient to PPO, computed rather than asserted.
//!
//! REINFORCE with a baseline climbs `mean_t log π_θ(a_t|s_t) · Â_t`. PPO's surrogate is
//! `mean_t r_t(θ) · Â_t` with `r_t = π_θ(a_t|s_t) / π_θ_old(a_t|s_t)`. At `θ = θ_old` every
//! ratio is 1 and `∇r_t = r_t ∇log π_θ = ∇log π_θ`, so the two objectives have the same
//! gradient there: PPO's first epoch *is* a policy-gradient step. [`surrogate_gradients`]
//! computes both with candle's autograd on one batch so the lesson can show them side by
//! side.

use candle_core::{Device, Tensor};

use super::STATE_DIM;
use crate::ppo::PpoError;
use crate::ppo::model::PolicyNet;

/// The gradients of the two objectives with respect to every actor parameter, flattened in
/// PyTorch's order (`fc1.weight`, `fc1.bias`, `fc2.weight`, `fc2.bias`, each row-major).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct SurrogateGradients {
    /// `∇θ mean(r_t · Â_t)` at `θ = θ_old`.
    pub surrogate: Vec<f32>,
    /// `∇θ mean(log π_θ(a_t|s_t) · Â_t)` at the same `θ`.
    pub log_prob: Vec<f32>,
    /// The actor's parameters in that order, by name and shape (`fc1.weight`, `[128, 4]`).
    pub shapes: Vec<(&'static str, Vec<usize>)>,
}

impl SurrogateGradients {
    /// The largest `|surrogate − log_prob|` over all parameters.
    #[must_use]
    pub fn max_abs_diff(&self) -> f32 {
        self.surrogate
            .iter()
            .zip(&self.log_prob)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f32::max)
    }

    /// The parameter entry `i` belongs to, e.g. `fc2.weight[1,127]` (`None` past the end).
    #[must_use]
    pub fn label(&self, i: usize) -> Option<String> {
        let mut start = 0;
        for (name, shape) in &self.shapes {
            let len: usize = shape.iter().product();
            if i < start + len {
                let k = i - start;
                return Some(match shape[..] {
                    [_, cols] => format!("{name}[{},{}]", k / cols, k % cols),
                    _ => format!("{name}[{k}]"),
                });
            }
            start += len;
        }
        None
    }

    /// The largest `|log_prob|` entry, the scale the difference is measured against.
    #[must_use]
    pub fn max_abs(&self) -> f32 {
        self.log_prob.iter().map(|g| g.abs()).fold(0.0, f32::max)
    }
}

/// Both gradients for the batch `(states, actions, advantage)` at the actor's current
/// weights, which play θ_old: the old log-probabilities are this actor's own, detached.
///
/// # Errors
/// [`PpoError::InvalidBatch`] when the three lengths differ or the batch is empty;
/// [`PpoError::Candle`] if autograd fails (a bug).
pub fn surrogate_gradients(
    actor: &PolicyNet,
    states: &[[f32; 4]],
    actions: &[usize],
    advantage: &[f32],
) -> Result<SurrogateGradients, PpoError> {
    let n = states.len();
    if n == 0 || actions.len() != n || advantage.len() != n {
        let (a, adv) = (actions.len(), advantage.len());
        return Err(PpoError::InvalidBatch(crate::tr!(
            "surrogate_gradients: {n} states, {a} actions, {adv} advantages; they must be equal and > 0",
            "surrogate_gradients：{n} 个状态、{a} 个动作、{adv} 个优势值；三者必须相等且大于 0"
        )));
    }
    let dev = &Device::Cpu;
    let flat: Vec<f32> = states.iter().flatten().copied().collect();
    let states = Tensor::from_vec(flat, (n, STATE_DIM), dev)?;
    let actions: Vec<u32> = actions.iter().map(|&a| a as u32).collect();
    let actions = Tensor::from_vec(actions, (n, 1), dev)?;
    let advantage = Tensor::from_vec(advantage.to_vec(), (n, 1), dev)?;

    // ANCHOR: surrogate_gradient
    // ANCHOR: gradient_log_probs
    let log_probs = actor.forward(&states)?.gather(&actions, 1)?.log()?;
    // ANCHOR_END: gradient_log_probs
    let old_log_probs = log_probs.detach(); // θ_old = θ: every ratio is exactly 1
    // ANCHOR: gradient_ratio
    let ratio = (&log_probs - &old_log_probs)?.exp()?;
    // ANCHOR_END: gradient_ratio
    let surrogate = (&ratio * &advantage)?.mean_all()?; // PPO, first epoch, unclipped
    let policy_gradient = (&log_probs * &advantage)?.mean_all()?; // REINFORCE with baseline
    // surrogate.backward() and policy_gradient.backward(): one GradStore each, compared
    // parameter by parameter below.
    // ANCHOR_END: surrogate_gradient

    let grads_of = |objective: &Tensor| -> Result<Vec<f32>, PpoError> {
        let grads = objective.backward()?;
        let mut out = Vec::new();
        for var in [&actor.fc1, &actor.fc2].into_iter().flat_map(|l| l.vars()) {
            let g = grads.get(var.as_tensor()).ok_or_else(|| {
                PpoError::InvalidBatch(
                    crate::i18n::t("a parameter has no gradient", "某个参数没有梯度").into(),
                )
            })?;
            out.extend(g.flatten_all()?.to_vec1::<f32>()?);
        }
        Ok(out)
    };
    Ok(SurrogateGradients {
        surrogate: grads_of(&surrogate)?,
        log_prob: grads_of(&policy_gradient)?,
        shapes: vec![
            ("fc1.weight", actor.fc1.weight.dims().to_vec()),
            ("fc1.bias", actor.fc1.bias.dims().to_vec()),
            ("fc2.weight", actor.fc2.weight.dims().to_vec()),
            ("fc2.bias", actor.fc2.bias.dims().to_vec()),
        ],
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::env::seeding::NumpyRng;

    type TestResult = Result<(), Box<dyn std::error::Error>>;

    fn batch() -> (Vec<[f32; 4]>, Vec<usize>, Vec<f32>) {
        let mut rng = NumpyRng::from_seed(7);
        let states = (0..12)
            .map(|_| std::array::from_fn(|_| rng.uniform(-0.5, 0.5) as f32))
            .collect();
        let actions = (0..12).map(|t| (t * 7 % 3) % 2).collect();
        let advantage = (0..12).map(|t| (t as f32 - 5.5) / 3.0).collect();
        (states, actions, advantage)
    }

    #[test]
    fn at_theta_old_the_two_gradients_agree() -> TestResult {
        let actor = PolicyNet::new(4, 16, 2, &mut NumpyRng::from_seed(0))?;
        let (s, a, adv) = batch();
        let g = surrogate_gradients(&actor, &s, &a, &adv)?;
        assert_eq!(g.surrogate.len(), 16 * 4 + 16 + 2 * 16 + 2);
        let last = g.surrogate.len() - 1;
        assert_eq!(g.label(last).as_deref(), Some("fc2.bias[1]"));
        assert_eq!(g.label(16 * 4).as_deref(), Some("fc1.bias[0]"));
        assert_eq!(g.label(16 * 5 + 17).as_deref(), Some("fc2.weight[1,1]"));
        assert_eq!(g.label(last + 1), None);
        assert!(g.max_abs() > 1e-3, "the batch must move the policy");
        assert!(
            g.max_abs_diff() <= 1e-6 * g.max_abs(),
            "{}",
            g.max_abs_diff()
        );
        Ok(())
    }

    #[test]
    fn the_gradient_is_not_the_same_for_another_advantage() -> TestResult {
        // Guards the check itself: flipping one row's advantage changes the gradient.
        let actor = PolicyNet::new(4, 16, 2, &mut NumpyRng::from_seed(0))?;
        let (s, a, adv) = batch();
        let g = surrogate_gradients(&actor, &s, &a, &adv)?;
        let mut flipped = adv.clone();
        flipped[0] = -flipped[0];
        let h = surrogate_gradients(&actor, &s, &a, &flipped)?;
        let diff = g
            .surrogate
            .iter()
            .zip(&h.log_prob)
            .map(|(x, y)| (x - y).abs())
            .fold(0.0, f32::max);
        assert!(diff > 1e-4, "{diff}");
        Ok(())
    }

    #[test]
    fn a_ragged_batch_is_refused() -> TestResult {
        let actor = PolicyNet::new(4, 8, 2, &mut NumpyRng::from_seed(0))?;
        let err = surrogate_gradients(&actor, &[[0.0; 4]], &[0, 1], &[1.0]);
        assert!(matches!(err, Err(PpoError::InvalidBatch(m)) if m.contains("must be equal")));
        Ok(())
    }
}
