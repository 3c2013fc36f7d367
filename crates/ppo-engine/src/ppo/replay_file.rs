//! A replay file of any agent (the seed's discrete PPO, the book's `PPOContinuous`, ...),
//! told apart by the weights of its first case ([`OnPolicyAgent::replays`]).

use serde_json::Value;

use super::PpoError;
use super::on_policy::{AgentConfig, OnPolicyAgent, Replayed};
use crate::lesson::live::session::LiveAgent;
use crate::run::{Environment, RunConfig, RunVisitor};

/// Replays every case of a recorded PyTorch update of any agent: the agent whose weights
/// the first case's `weights_before` holds (the first agent, the seed's PPO, when none
/// claims them); `file` names it in errors. One result per case.
///
/// # Errors
/// [`PpoError::File`] for a file that is not JSON; as [`OnPolicyAgent::replay`] for one
/// that is not that agent's cases.
#[allow(clippy::type_complexity)]
pub fn replay_any(text: &str, file: &str) -> Result<Vec<Result<Replayed, PpoError>>, PpoError> {
    let root: Value = serde_json::from_str(text).map_err(|e| PpoError::File {
        file: file.into(),
        reason: format!("not valid JSON ({e})"),
    })?;
    let weights = root
        .get("cases")
        .and_then(|c| c.get(0))
        .and_then(|c| c.get("weights_before"))
        .unwrap_or(&Value::Null);
    let env = Environment::ALL
        .into_iter()
        .find(|env| RunConfig::default_for(*env).visit(Claims(weights)))
        .unwrap_or_default();
    RunConfig::default_for(env).visit(Replay { text, file })
}

/// Whether an agent claims a replay file's weights.
struct Claims<'a>(&'a Value);

impl RunVisitor for Claims<'_> {
    type Output = bool;

    fn visit<C: AgentConfig>(self, _config: &C) -> bool
    where
        C::Agent: LiveAgent,
    {
        C::Agent::replays(self.0)
    }
}

/// Replays a file as an agent's.
struct Replay<'a> {
    text: &'a str,
    file: &'a str,
}

impl RunVisitor for Replay<'_> {
    type Output = Result<Vec<Result<Replayed, PpoError>>, PpoError>;

    fn visit<C: AgentConfig>(self, _config: &C) -> Self::Output
    where
        C::Agent: LiveAgent,
    {
        C::Agent::replay(self.text, self.file)
    }
}
