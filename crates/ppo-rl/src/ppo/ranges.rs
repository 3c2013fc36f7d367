//! The ranges of the hyper-parameters every PPO of the course shares (learning rates,
//! width, γ, λ, epochs, ε, episodes), checked once for all agents: each config's
//! `validate` calls `check_shared!` and then checks its own fields.

use super::PpoError;
use crate::i18n::t;

/// `field = value` out of range, with the range it needs.
pub(crate) fn invalid(
    field: &'static str,
    value: impl ToString,
    expected: &'static str,
) -> PpoError {
    PpoError::InvalidConfig {
        field,
        value: value.to_string(),
        expected,
    }
}

/// A finite number > 0 (a learning rate, a norm, a KL target).
///
/// # Errors
/// [`PpoError::InvalidConfig`] naming `field`.
pub(crate) fn positive(field: &'static str, value: f64) -> Result<(), PpoError> {
    if value.is_finite() && value > 0.0 {
        Ok(())
    } else {
        Err(invalid(
            field,
            value,
            t("a finite number > 0", "大于 0 的有限数"),
        ))
    }
}

/// The shared settings, borrowed from a config by `check_shared!`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Shared {
    pub actor_lr: f64,
    pub critic_lr: f64,
    pub hidden_dim: usize,
    pub gamma: f64,
    pub lmbda: f64,
    pub epochs: usize,
    pub eps: f64,
    pub num_episodes: usize,
}

impl Shared {
    /// Every shared field in its range, in the order the configs list them.
    ///
    /// # Errors
    /// [`PpoError::InvalidConfig`] naming the first field out of range and its range.
    pub(crate) fn check(self) -> Result<(), PpoError> {
        positive("actor_lr", self.actor_lr)?;
        positive("critic_lr", self.critic_lr)?;
        if self.hidden_dim == 0 {
            return Err(invalid("hidden_dim", 0, t("at least 1", "至少为 1")));
        }
        if !(self.gamma > 0.0 && self.gamma <= 1.0) {
            return Err(invalid(
                "gamma",
                self.gamma,
                t("a number in (0, 1]", "(0, 1] 内的数"),
            ));
        }
        if !(0.0..=1.0).contains(&self.lmbda) {
            return Err(invalid(
                "lmbda",
                self.lmbda,
                t("a number in [0, 1]", "[0, 1] 内的数"),
            ));
        }
        if self.epochs == 0 {
            return Err(invalid("epochs", 0, t("at least 1", "至少为 1")));
        }
        if !(self.eps > 0.0 && self.eps < 1.0) {
            return Err(invalid(
                "eps",
                self.eps,
                t("a number in (0, 1)", "(0, 1) 内的数"),
            ));
        }
        if self.num_episodes == 0 {
            return Err(invalid(
                "num_episodes",
                0,
                t("at least 1 episode", "至少 1 个回合"),
            ));
        }
        Ok(())
    }
}

/// Checks the shared fields of a config (any struct with the fields of [`Shared`]).
macro_rules! check_shared {
    ($config:expr) => {
        $crate::ppo::ranges::Shared {
            actor_lr: $config.actor_lr,
            critic_lr: $config.critic_lr,
            hidden_dim: $config.hidden_dim,
            gamma: $config.gamma,
            lmbda: $config.lmbda,
            epochs: $config.epochs,
            eps: $config.eps,
            num_episodes: $config.num_episodes,
        }
        .check()
    };
}

pub(crate) use check_shared;
