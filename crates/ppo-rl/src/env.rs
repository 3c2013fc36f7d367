//! The native environments: Gymnasium 1.4.0's `CartPole-v1` (and `-v0`) and `Pendulum-v1`,
//! bit for bit.
//!
//! - [`Environment`] and [`VectorEnv`] ([`interface`]): Gymnasium's `Env` and `VectorEnv`
//!   interfaces, one environment or several with automatic reset in either [`Autoreset`]
//!   mode; [`SyncVectorEnv`] runs any environment as a vector.
//! - [`CartPole`]: one environment with Gymnasium's `reset(seed)` / `step(action)`.
//! - [`CartPoleVec`]: many environments stepped together as a struct of arrays, for
//!   throughput (same-step autoreset).
//! - [`Pendulum`], [`PendulumVec`]: the same for `Pendulum-v1` (one continuous torque).
//! - [`seeding`]: numpy's `SeedSequence` → `PCG64` → `uniform`, so seeds give Gymnasium's states.
//! - [`sincos`]: libm's `sin` and `cos` bit for bit, computed inline (glibc's algorithm) where valid.

pub mod cartpole;
pub mod interface;
pub mod pendulum;
pub mod quotient;
pub mod seeding;
pub mod sincos;
pub mod trace;
pub mod vector;

pub use cartpole::{CartPole, CartPoleConfig, EnvId, Integrator, Step};
pub use interface::{Autoreset, EnvStep, Environment, SyncVectorEnv, VectorEnv};
pub use pendulum::{Pendulum, PendulumConfig, PendulumStep, PendulumTrajectory};
pub use trace::{Policy, Trajectory};
pub use vector::{CartPoleVec, PendulumVec, VecStep};

/// What can go wrong when using a CartPole or a Pendulum.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum EnvError {
    /// `step` was called before the first `reset`.
    #[error("step() called before reset(): call reset(seed) first")]
    NotReset,
    /// CartPole has two actions.
    #[error("invalid action {0}: CartPole's actions are 0 (push left) and 1 (push right)")]
    InvalidAction(usize),
    /// An environment id this crate does not provide.
    #[error("unknown environment id '{0}': use CartPole-v1 or CartPole-v0")]
    UnknownEnv(String),
    /// Reset bounds that are not finite or have `low > high`.
    #[error("invalid reset bounds low={low}, high={high}: need finite low <= high")]
    InvalidBounds {
        /// The lower bound given.
        low: f64,
        /// The upper bound given.
        high: f64,
    },
    /// A vector environment of no environments.
    #[error("a vector environment needs at least one environment: ask for 1 or more")]
    NoEnvironments,
    /// An autoreset mode this crate does not provide.
    #[error("unknown autoreset mode '{0}': use same-step or next-step")]
    UnknownAutoreset(String),
    /// A vector step got the wrong number of actions.
    #[error("expected {expected} actions (one per environment), got {got}")]
    ActionCount {
        /// The number of environments.
        expected: usize,
        /// The number of actions passed.
        got: usize,
    },
}
