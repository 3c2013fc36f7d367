//! The seed's agent as a safetensors checkpoint with PyTorch's names, marked as a
//! CartPole-v1 agent ([`OnPolicyAgent::CHECKPOINT`]: `CartPole-v1` / `ppo`).

use std::path::Path;

use super::{ACTION_DIM, Agent, PpoConfig, STATE_DIM};
use crate::ppo::OnPolicyAgent;
use crate::ppo::PpoError;
use crate::ppo::checkpoint::{check_against, read_sized, write_checkpoint};
use crate::ppo::model::NamedWeights;

/// Every parameter's name and shape for hidden width `hidden_dim`, in PyTorch's order.
#[must_use]
pub fn parameter_shapes(hidden_dim: usize) -> [(&'static str, Vec<usize>); 8] {
    let h = hidden_dim;
    [
        ("actor.fc1.weight", vec![h, STATE_DIM]),
        ("actor.fc1.bias", vec![h]),
        ("actor.fc2.weight", vec![ACTION_DIM, h]),
        ("actor.fc2.bias", vec![ACTION_DIM]),
        ("critic.fc1.weight", vec![h, STATE_DIM]),
        ("critic.fc1.bias", vec![h]),
        ("critic.fc2.weight", vec![1, h]),
        ("critic.fc2.bias", vec![1]),
    ]
}

/// Checks that `weights` holds exactly the eight parameters with the shapes `hidden_dim`
/// gives, and finite values.
///
/// # Errors
/// [`PpoError::MissingKey`] or [`PpoError::WrongShape`] naming the tensor in `source`.
pub fn check_weights(
    weights: &NamedWeights,
    hidden_dim: usize,
    source: &str,
) -> Result<(), PpoError> {
    check_against(
        weights,
        &parameter_shapes(hidden_dim),
        hidden_dim,
        source,
        crate::i18n::t(
            "only the eight actor./critic. parameters",
            "只有 actor./critic. 的八个参数",
        ),
    )
}

impl Agent {
    /// Writes the weights to a safetensors file (f32, PyTorch names), marked as a
    /// `CartPole-v1` / `ppo` checkpoint ([`CheckpointKind`]).
    ///
    /// # Errors
    /// [`PpoError::File`] when the file cannot be written.
    pub fn save(&self, path: &Path) -> Result<(), PpoError> {
        write_checkpoint(path, self.weights()?, <Agent as OnPolicyAgent>::CHECKPOINT)
    }

    /// Reads a checkpoint written by [`Agent::save`]; the hidden width comes from the file
    /// and overrides `config.hidden_dim`. Adam starts fresh; actions are sampled with `seed`.
    ///
    /// # Errors
    /// [`PpoError::File`] for an unreadable file, one that is not safetensors, or one of a
    /// Pendulum agent; [`PpoError::MissingKey`] / [`PpoError::WrongShape`] naming the tensor and its
    /// expected shape.
    pub fn load(path: &Path, config: &PpoConfig, seed: u64) -> Result<Self, PpoError> {
        let (weights, hidden_dim, file) =
            read_sized(path, <Agent as OnPolicyAgent>::CHECKPOINT, STATE_DIM)?;
        let config = PpoConfig {
            hidden_dim,
            ..config.clone()
        };
        Agent::from_weights(&config, &weights, seed, &file)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn weights_round_trip_through_a_file() -> Result<(), Box<dyn std::error::Error>> {
        let dir = tempfile::tempdir()?;
        let path = dir.path().join("agent.safetensors");
        let agent = Agent::new(&PpoConfig::default(), 5)?;
        agent.save(&path)?;
        let loaded = Agent::load(&path, &PpoConfig::default(), 0)?;
        assert_eq!(agent.weights()?, loaded.weights()?);
        Ok(())
    }

    #[test]
    fn wrong_shapes_are_named() -> Result<(), Box<dyn std::error::Error>> {
        let mut w = Agent::new(&PpoConfig::default(), 0)?.weights()?;
        if let Some(t) = w.get_mut("critic.fc2.weight") {
            t.shape = vec![2, 64];
        }
        let err = check_weights(&w, 128, "x.safetensors")
            .err()
            .map(|e| e.to_string());
        let err = err.unwrap_or_default();
        assert!(
            err.contains("critic.fc2.weight") && err.contains("[1, 128]"),
            "{err}"
        );
        w.remove("actor.fc2.bias");
        let err = check_weights(&w, 128, "x")
            .err()
            .map(|e| e.to_string())
            .unwrap_or_default();
        assert!(
            err.contains("actor.fc2.bias") && err.contains("[2]"),
            "{err}"
        );
        Ok(())
    }
}
