//! The seed's PPO on CartPole (*Hands-on RL*, `task_PPO.py`), and REINFORCE on the same
//! networks: a softmax policy over CartPole's two actions.
//!
//! - [`config`]: [`PpoConfig`], whose `Default` is the seed's hyper-parameters, and the
//!   [`Algorithm`] (PPO or REINFORCE).
//! - [`agent`]: [`Agent`] with `take_action` and `update`, which returns an [`UpdateTrace`].
//! - [`trace`]: the recorded intermediates every face displays.
//! - [`gradient`]: the policy gradient and PPO's surrogate have one gradient at θ_old.
//! - [`replay`]: re-running a recorded PyTorch update (`ppo_update_pytorch.json`).

pub mod agent;
pub mod config;
pub mod gradient;
pub mod replay;
pub mod trace;

pub use agent::{Agent, Losses, Transitions};
pub use config::{Algorithm, PpoConfig};
pub use trace::{EarlyStop, EpochTrace, UpdateTrace};

/// Observations per state: CartPole's `(x, x_dot, theta, theta_dot)`.
pub const STATE_DIM: usize = 4;
/// Actions: 0 pushes left, 1 pushes right.
pub const ACTION_DIM: usize = 2;
