//! A replay file of either agent: the seed's discrete PPO ([`super::replay`]) or the book's
//! `PPOContinuous` ([`super::continuous::replay`]), told apart by the keys of its weights.

use serde_json::Value;

use super::PpoError;
use super::continuous::replay::{ContinuousReplayCase, parse_continuous_replay};
use super::replay::{ReplayCase, parse_replay};

/// A replay file of either agent, told apart by its keys.
#[derive(Debug, Clone)]
pub enum AnyReplay {
    /// `ppo_update_pytorch.json`: the seed's discrete PPO on CartPole.
    Discrete(Vec<ReplayCase>),
    /// `ppo_continuous_update_pytorch.json`: the book's `PPOContinuous` on Pendulum.
    Continuous(Vec<ContinuousReplayCase>),
}

/// Parses a replay file of either agent: one whose first case's `weights_before` holds
/// `actor.fc_mu.weight` (a Gaussian policy) is the continuous agent's, any other the
/// discrete agent's; `file` names it in errors.
///
/// # Errors
/// As [`parse_replay`] and [`parse_continuous_replay`].
pub fn parse_any_replay(text: &str, file: &str) -> Result<AnyReplay, PpoError> {
    let root: Value = serde_json::from_str(text).map_err(|e| PpoError::File {
        file: file.into(),
        reason: format!("not valid JSON ({e})"),
    })?;
    let continuous = root
        .get("cases")
        .and_then(|c| c.get(0))
        .and_then(|c| c.get("weights_before"))
        .is_some_and(|w| w.get("actor.fc_mu.weight").is_some());
    if continuous {
        Ok(AnyReplay::Continuous(parse_continuous_replay(text, file)?))
    } else {
        Ok(AnyReplay::Discrete(parse_replay(text, file)?))
    }
}
