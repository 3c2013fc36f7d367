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
// Display below, in the current language (thiserror writes only the `Error` impl).
pub enum EnvError {
    /// `step` was called before the first `reset`.
    NotReset,
    /// CartPole has two actions.
    InvalidAction(usize),
    /// An environment id this crate does not provide.
    UnknownEnv(String),
    /// Reset bounds that are not finite or have `low > high`.
    InvalidBounds {
        /// The lower bound given.
        low: f64,
        /// The upper bound given.
        high: f64,
    },
    /// A vector environment of no environments.
    NoEnvironments,
    /// An autoreset mode this crate does not provide.
    UnknownAutoreset(String),
    /// A vector step got the wrong number of actions.
    ActionCount {
        /// The number of environments.
        expected: usize,
        /// The number of actions passed.
        got: usize,
    },
}

impl std::fmt::Display for EnvError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        use crate::tr;
        let text = match self {
            Self::NotReset => tr!(
                "step() called before reset(): call reset(seed) first",
                "在 reset() 之前调用了 step()：请先调用 reset(seed)"
            ),
            Self::InvalidAction(action) => tr!(
                "invalid action {action}: CartPole's actions are 0 (push left) and 1 (push right)",
                "无效的动作 {action}：车杆的动作只有 0（向左推）和 1（向右推）"
            ),
            Self::UnknownEnv(id) => tr!(
                "unknown environment id '{id}': use CartPole-v1 or CartPole-v0",
                "未知的环境名“{id}”：请用 CartPole-v1 或 CartPole-v0"
            ),
            Self::InvalidBounds { low, high } => tr!(
                "invalid reset bounds low={low}, high={high}: need finite low <= high",
                "重置范围 low={low}、high={high} 无效：两者须为有限数，且 low <= high"
            ),
            Self::NoEnvironments => tr!(
                "a vector environment needs at least one environment: ask for 1 or more",
                "向量环境至少需要一个环境：请指定 1 个或更多"
            ),
            Self::UnknownAutoreset(mode) => tr!(
                "unknown autoreset mode '{mode}': use same-step or next-step",
                "未知的自动重置方式“{mode}”：请用 same-step 或 next-step"
            ),
            Self::ActionCount { expected, got } => tr!(
                "expected {expected} actions (one per environment), got {got}",
                "应有 {expected} 个动作（每个环境一个），实际是 {got} 个"
            ),
        };
        f.write_str(&text)
    }
}

#[cfg(test)]
mod tests {
    use super::EnvError;
    use crate::i18n::Lang;

    /// One of each variant; the match fails to compile when a variant is added and not
    /// listed here.
    fn every_error() -> Vec<EnvError> {
        let all = vec![
            EnvError::NotReset,
            EnvError::InvalidAction(2),
            EnvError::UnknownEnv("Acrobot-v1".into()),
            EnvError::InvalidBounds {
                low: 1.0,
                high: -1.0,
            },
            EnvError::NoEnvironments,
            EnvError::UnknownAutoreset("sometimes".into()),
            EnvError::ActionCount {
                expected: 4,
                got: 3,
            },
        ];
        for e in &all {
            match e {
                EnvError::NotReset
                | EnvError::InvalidAction(_)
                | EnvError::UnknownEnv(_)
                | EnvError::InvalidBounds { .. }
                | EnvError::NoEnvironments
                | EnvError::UnknownAutoreset(_)
                | EnvError::ActionCount { .. } => {}
            }
        }
        all
    }

    fn has_chinese(text: &str) -> bool {
        text.chars().any(|c| ('\u{4e00}'..='\u{9fff}').contains(&c))
    }

    #[test]
    fn every_environment_error_is_worded_in_the_current_language() {
        for e in every_error() {
            let en = {
                let _en = Lang::En.scoped();
                e.to_string()
            };
            let zh = {
                let _zh = Lang::Zh.scoped();
                e.to_string()
            };
            assert!(!has_chinese(&en), "{e:?}: {en}");
            assert!(has_chinese(&zh), "{e:?} in Chinese: {zh}");
            // The value the caller gave is in both.
            if let EnvError::UnknownEnv(v) | EnvError::UnknownAutoreset(v) = &e {
                assert!(
                    en.contains(v.as_str()) && zh.contains(v.as_str()),
                    "{en} / {zh}"
                );
            }
        }
    }
}
