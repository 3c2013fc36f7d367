//! The hyper-parameters: [`PpoContinuousConfig::default`] is the book's `PPOContinuous` run
//! on Pendulum (actor_lr 1e-4, critic_lr 5e-3, 2000 episodes, hidden 128, γ 0.9, λ 0.9,
//! 10 epochs, ε 0.2).
//!
//! The field names and ranges are [`PpoConfig`](crate::ppo::PpoConfig)'s; the discrete
//! agent's opt-in switches (entropy bonus, grad clipping, ...) are not offered here.
//!
//! ```
//! use ppo_rl::ppo::PpoContinuousConfig;
//!
//! let c = PpoContinuousConfig::default();
//! assert_eq!((c.actor_lr, c.critic_lr, c.gamma, c.lmbda), (1e-4, 5e-3, 0.9, 0.9));
//! assert!(c.validate().is_ok());
//! ```

use serde::{Deserialize, Serialize};

use crate::ppo::PpoError;

/// Everything that sets one continuous-action PPO run apart from another.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PpoContinuousConfig {
    /// Adam learning rate of the actor (the Gaussian policy); book: `1e-4`.
    pub actor_lr: f64,
    /// Adam learning rate of the critic (value network); book: `5e-3`.
    pub critic_lr: f64,
    /// Width of the hidden layer of both networks; book: 128.
    pub hidden_dim: usize,
    /// Discount factor γ in the TD target; book: 0.9.
    pub gamma: f64,
    /// GAE's λ (the book spells it `lmbda`); book: 0.9.
    pub lmbda: f64,
    /// Passes over each episode's batch per update; book: 10.
    pub epochs: usize,
    /// Clip range ε of the surrogate: the ratio is clamped to `[1-ε, 1+ε]`; book: 0.2.
    pub eps: f64,
    /// Episodes to train for (one update per episode); book: 2000.
    pub num_episodes: usize,
}

// ANCHOR: hyper_continuous
impl Default for PpoContinuousConfig {
    /// The book's hyper-parameters for `PPOContinuous` on Pendulum.
    fn default() -> Self {
        Self {
            actor_lr: 1e-4,
            critic_lr: 5e-3,
            hidden_dim: 128,
            gamma: 0.9,
            lmbda: 0.9,
            epochs: 10,
            eps: 0.2,
            num_episodes: 2000,
        }
    }
}
// ANCHOR_END: hyper_continuous

impl PpoContinuousConfig {
    /// Checks every field's range (the same ranges as the discrete agent's).
    ///
    /// # Errors
    /// [`PpoError::InvalidConfig`] naming the first field out of range and its valid range.
    pub fn validate(&self) -> Result<(), PpoError> {
        crate::ppo::ranges::check_shared!(self)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn default_is_the_book() {
        let c = PpoContinuousConfig::default();
        assert!(c.validate().is_ok());
        assert_eq!((c.hidden_dim, c.epochs, c.num_episodes), (128, 10, 2000));
        assert_eq!(c.eps, 0.2);
    }

    #[test]
    fn out_of_range_fields_are_named() {
        type Case = (fn(&mut PpoContinuousConfig), &'static str);
        let cases: [Case; 5] = [
            (|c| c.eps = 1.0, "eps"),
            (|c| c.gamma = 0.0, "gamma"),
            (|c| c.actor_lr = f64::NAN, "actor_lr"),
            (|c| c.lmbda = 1.5, "lmbda"),
            (|c| c.hidden_dim = 0, "hidden_dim"),
        ];
        for (set, name) in cases {
            let mut c = PpoContinuousConfig::default();
            set(&mut c);
            let err = c
                .validate()
                .err()
                .map(|e| e.to_string())
                .unwrap_or_default();
            assert!(err.contains(name), "{name}: {err}");
        }
    }
}
