//! What the grader and the learner's compiled program say to each other, and the
//! evaluation of a losses function both sides share.
//!
//! This file is compiled twice: into ppo-tutor, where it evaluates the reference and the
//! known mistakes, and, copied as text next to the learner's file, into the program that
//! runs the learner's `ppo_losses` (a crate depending on candle alone). It therefore uses
//! nothing but `std`, `candle_core` and the shared serving loop (`crate::harness`, copied
//! beside it), and reads the same in editions 2021 and 2024.
//!
//! One request per line (the serving loop marks the replies apart from the learner's
//! prints: see `crate::harness`): `n eps`, then `probs` (2n numbers, row-major), `actions`,
//! `old_log_probs`, `advantage`, `values` and `td_target` (n each). One reply per line:
//!
//! - `ok a c`, then `∂a/∂probs` (2n), `∂c/∂values` (n) and `∂c/∂td_target` (n), where `a`
//!   and `c` are the actor and critic losses: the losses and the gradients a backward pass
//!   sends into the networks (the grader carries them on to the weights);
//! - `error <message>`: the function returned an error, or a loss that is not a scalar;
//! - `panic <message>`: the function panicked (message and place).

use candle_core::backprop::GradStore;
use candle_core::{DType, Device, Tensor, Var};

/// The exercise's signature: `(probs, actions, old_log_probs, advantage, values,
/// td_target, eps) -> (actor_loss, critic_loss)`.
pub type LossesFn = fn(
    &Tensor,
    &Tensor,
    &Tensor,
    &Tensor,
    &Tensor,
    &Tensor,
    f64,
) -> candle_core::Result<(Tensor, Tensor)>;

/// One epoch's inputs as numbers, for a batch of `n` steps.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Inputs {
    /// `π(·|s_t)`, `(n, 2)` row-major.
    pub probs: Vec<f32>,
    /// `a_t`.
    pub actions: Vec<u32>,
    /// `log π_old(a_t|s_t)`.
    pub old_log_probs: Vec<f32>,
    /// `Â_t`.
    pub advantage: Vec<f32>,
    /// `V(s_t)`.
    pub values: Vec<f32>,
    /// `r_t + γ·V(s_{t+1})·(1 − done_t)`.
    pub td_target: Vec<f32>,
    /// The clip range ε.
    pub eps: f64,
}

/// What a losses function gave on one [`Inputs`].
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Reply {
    /// The actor loss.
    pub actor_loss: f32,
    /// The critic loss.
    pub critic_loss: f32,
    /// `∂ actor_loss / ∂ probs`, `(n, 2)` row-major (zeros where no gradient flows).
    pub d_probs: Vec<f32>,
    /// `∂ critic_loss / ∂ values`.
    pub d_values: Vec<f32>,
    /// `∂ critic_loss / ∂ td_target` (zero when the target is detached).
    pub d_td_target: Vec<f32>,
}

fn push_all<T: std::fmt::Debug>(out: &mut String, xs: &[T]) {
    for x in xs {
        out.push(' ');
        out.push_str(&format!("{x:?}"));
    }
}

fn take<T: std::str::FromStr>(
    words: &mut std::str::SplitWhitespace<'_>,
    count: usize,
) -> Option<Vec<T>> {
    (0..count).map(|_| words.next()?.parse().ok()).collect()
}

impl Inputs {
    /// The number of steps.
    #[must_use]
    pub fn len(&self) -> usize {
        self.actions.len()
    }

    /// Whether there are none.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.actions.is_empty()
    }

    /// The request line (without its newline).
    #[must_use]
    pub fn encode(&self) -> String {
        let mut out = format!("{} {:?}", self.len(), self.eps);
        push_all(&mut out, &self.probs);
        push_all(&mut out, &self.actions);
        push_all(&mut out, &self.old_log_probs);
        push_all(&mut out, &self.advantage);
        push_all(&mut out, &self.values);
        push_all(&mut out, &self.td_target);
        out
    }

    /// Reads a request line; `None` if it is malformed.
    #[must_use]
    pub fn decode(line: &str) -> Option<Self> {
        let mut words = line.split_whitespace();
        let n: usize = words.next()?.parse().ok()?;
        let eps: f64 = words.next()?.parse().ok()?;
        let inputs = Self {
            probs: take(&mut words, 2 * n)?,
            actions: take(&mut words, n)?,
            old_log_probs: take(&mut words, n)?,
            advantage: take(&mut words, n)?,
            values: take(&mut words, n)?,
            td_target: take(&mut words, n)?,
            eps,
        };
        words.next().is_none().then_some(inputs)
    }
}

impl Reply {
    /// The reply line `ok ...` (without its newline).
    #[must_use]
    pub fn encode(&self) -> String {
        let mut out = format!("ok {:?} {:?}", self.actor_loss, self.critic_loss);
        push_all(&mut out, &self.d_probs);
        push_all(&mut out, &self.d_values);
        push_all(&mut out, &self.d_td_target);
        out
    }

    /// Reads the part after `ok` of a reply to a request of `n` steps.
    #[must_use]
    pub fn decode(payload: &str, n: usize) -> Option<Self> {
        let mut words = payload.split_whitespace();
        let reply = Self {
            actor_loss: words.next()?.parse().ok()?,
            critic_loss: words.next()?.parse().ok()?,
            d_probs: take(&mut words, 2 * n)?,
            d_values: take(&mut words, n)?,
            d_td_target: take(&mut words, n)?,
        };
        words.next().is_none().then_some(reply)
    }
}

/// The first line of an error's message (candle appends a backtrace when asked to).
fn message(e: &candle_core::Error) -> String {
    e.to_string()
        .lines()
        .next()
        .unwrap_or("")
        .trim()
        .to_string()
}

fn scalar(name: &str, loss: &Tensor) -> Result<f32, String> {
    if loss.rank() != 0 {
        return Err(format!(
            "{name} has shape {:?}, not a scalar: a loss is one number (shape []), so reduce \
             the rows with mean_all()",
            loss.dims()
        ));
    }
    loss.to_dtype(DType::F32)
        .and_then(|l| l.to_scalar::<f32>())
        .map_err(|e| message(&e))
}

fn gradient(grads: &GradStore, var: &Var) -> Result<Vec<f32>, String> {
    match grads.get(var.as_tensor()) {
        Some(g) => g
            .to_dtype(DType::F32)
            .and_then(|g| g.flatten_all())
            .and_then(|g| g.to_vec1::<f32>())
            .map_err(|e| message(&e)),
        None => Ok(vec![0.0; var.elem_count()]),
    }
}

/// Runs `losses` on `inputs` (as tensors: `probs`, `values` and `td_target` tracked by
/// autograd, the other columns constants as in the seed) and differentiates both losses.
///
/// # Errors
/// The function's own error, a loss that is not a scalar, or a malformed `inputs`, as one
/// line of text.
pub fn evaluate(losses: LossesFn, inputs: &Inputs) -> Result<Reply, String> {
    let n = inputs.len();
    let dev = &Device::Cpu;
    let column = |v: &[f32]| Tensor::from_vec(v.to_vec(), (n, 1), dev);
    let tensors = (|| {
        Ok::<_, candle_core::Error>((
            Var::from_vec(inputs.probs.clone(), (n, 2), dev)?,
            Tensor::from_vec(inputs.actions.clone(), (n, 1), dev)?,
            column(&inputs.old_log_probs)?,
            column(&inputs.advantage)?,
            Var::from_vec(inputs.values.clone(), (n, 1), dev)?,
            Var::from_vec(inputs.td_target.clone(), (n, 1), dev)?,
        ))
    })();
    let (probs, actions, old_log_probs, advantage, values, td_target) =
        tensors.map_err(|e| format!("malformed inputs: {}", message(&e)))?;
    let (actor_loss, critic_loss) = losses(
        probs.as_tensor(),
        &actions,
        &old_log_probs,
        &advantage,
        values.as_tensor(),
        td_target.as_tensor(),
        inputs.eps,
    )
    .map_err(|e| message(&e))?;
    let a = scalar("actor_loss", &actor_loss)?;
    let c = scalar("critic_loss", &critic_loss)?;
    let backward = |loss: &Tensor| {
        loss.backward()
            .map_err(|e| format!("backward() failed: {}", message(&e)))
    };
    let actor_grads = backward(&actor_loss)?;
    let critic_grads = backward(&critic_loss)?;
    Ok(Reply {
        actor_loss: a,
        critic_loss: c,
        d_probs: gradient(&actor_grads, &probs)?,
        d_values: gradient(&critic_grads, &values)?,
        d_td_target: gradient(&critic_grads, &td_target)?,
    })
}

/// The learner's program: answers requests from stdin until it closes, through the
/// serving loop every learner program shares (`crate::harness`, copied beside this file),
/// which catches panics per request and marks its answers apart from the learner's prints.
pub fn serve(losses: LossesFn) {
    crate::harness::serve(|line| match Inputs::decode(line) {
        None => "error malformed request".to_string(),
        Some(inputs) => match evaluate(losses, &inputs) {
            Ok(reply) => reply.encode(),
            Err(e) => format!("error {e}"),
        },
    });
}
