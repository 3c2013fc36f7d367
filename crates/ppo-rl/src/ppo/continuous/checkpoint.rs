//! Saving and loading a [`PpoContinuous`] as safetensors, with PyTorch's parameter names.
//!
//! A checkpoint holds ten f32 tensors, shapes for hidden width `H`:
//!
//! ```text
//! actor.fc1.weight (H, 3)      actor.fc1.bias (H)
//! actor.fc_mu.weight (1, H)    actor.fc_mu.bias (1)
//! actor.fc_std.weight (1, H)   actor.fc_std.bias (1)
//! critic.fc1.weight (H, 3)     critic.fc1.bias (H)
//! critic.fc2.weight (1, H)     critic.fc2.bias (1)
//! ```
//!
//! the book's `state_dict()`s prefixed `actor.` / `critic.`, and the metadata
//! `{"env": "Pendulum-v1", "algorithm": "ppo-continuous"}`
//! ([`OnPolicyAgent::CHECKPOINT`]). A CartPole checkpoint given to
//! [`PpoContinuous::load`] is refused with a message saying what it holds, and the other way
//! round. The names and shapes come from [`super::params`], which the agent and the replay
//! share.

use std::path::Path;

use super::agent::PpoContinuous;
use super::{PpoContinuousConfig, STATE_DIM};
use crate::ppo::OnPolicyAgent;
use crate::ppo::PpoError;
use crate::ppo::checkpoint::{read_sized, write_checkpoint};

impl PpoContinuous {
    /// Writes the weights to a safetensors file (f32, PyTorch names), marked as a
    /// `Pendulum-v1` / `ppo-continuous` checkpoint.
    ///
    /// # Errors
    /// [`PpoError::File`] when the file cannot be written.
    pub fn save(&self, path: &Path) -> Result<(), PpoError> {
        write_checkpoint(
            path,
            self.weights()?,
            <PpoContinuous as OnPolicyAgent>::CHECKPOINT,
        )
    }

    /// Reads a checkpoint written by [`PpoContinuous::save`]; the hidden width comes from the
    /// file and overrides `config.hidden_dim`. Adam starts fresh; torques are sampled with
    /// `seed`.
    ///
    /// # Errors
    /// [`PpoError::File`] for an unreadable file, one that is not safetensors, or one of a
    /// CartPole agent; [`PpoError::MissingKey`] / [`PpoError::WrongShape`] naming the tensor
    /// and its expected shape.
    pub fn load(path: &Path, config: &PpoContinuousConfig, seed: u64) -> Result<Self, PpoError> {
        let (weights, hidden_dim, file) = read_sized(
            path,
            <PpoContinuous as OnPolicyAgent>::CHECKPOINT,
            STATE_DIM,
        )?;
        let config = PpoContinuousConfig {
            hidden_dim,
            ..config.clone()
        };
        Self::from_weights(&config, &weights, seed, &file)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ppo::continuous::params::{check_weights, parameter_names};
    use crate::ppo::{Agent, PpoConfig};

    #[test]
    fn weights_round_trip_through_a_file() -> Result<(), Box<dyn std::error::Error>> {
        let dir = tempfile::tempdir()?;
        let path = dir.path().join("pendulum.safetensors");
        let config = PpoContinuousConfig {
            hidden_dim: 16,
            ..PpoContinuousConfig::default()
        };
        let agent = PpoContinuous::new(&config, 5)?;
        agent.save(&path)?;
        let loaded = PpoContinuous::load(&path, &PpoContinuousConfig::default(), 0)?;
        assert_eq!(loaded.config().hidden_dim, 16);
        assert_eq!(agent.weights()?, loaded.weights()?);
        let names: Vec<String> = agent.weights()?.into_keys().collect();
        let mut want: Vec<&str> = parameter_names().to_vec();
        want.sort_unstable();
        assert_eq!(names, want);
        Ok(())
    }

    /// A CartPole checkpoint is refused as a Pendulum agent and the other way round, with a
    /// message naming both environments.
    #[test]
    fn the_other_agents_checkpoint_is_refused() -> Result<(), Box<dyn std::error::Error>> {
        let dir = tempfile::tempdir()?;
        let cartpole = dir.path().join("cartpole.safetensors");
        let pendulum = dir.path().join("pendulum.safetensors");
        Agent::new(&PpoConfig::default(), 0)?.save(&cartpole)?;
        PpoContinuous::new(&PpoContinuousConfig::default(), 0)?.save(&pendulum)?;

        let err = PpoContinuous::load(&cartpole, &PpoContinuousConfig::default(), 0)
            .err()
            .map(|e| e.to_string())
            .unwrap_or_default();
        assert!(
            err.contains("ppo agent for CartPole-v1")
                && err.contains("not a ppo-continuous agent for Pendulum-v1"),
            "{err}"
        );
        let err = Agent::load(&pendulum, &PpoConfig::default(), 0)
            .err()
            .map(|e| e.to_string())
            .unwrap_or_default();
        assert!(
            err.contains("ppo-continuous agent for Pendulum-v1")
                && err.contains("not a ppo agent for CartPole-v1"),
            "{err}"
        );
        Ok(())
    }

    /// A file without metadata (as PyTorch's `safetensors.torch.save_file` writes it) is
    /// recognised by its parameter names.
    #[test]
    fn files_without_metadata_are_recognised_by_their_names()
    -> Result<(), Box<dyn std::error::Error>> {
        let dir = tempfile::tempdir()?;
        let path = dir.path().join("plain.safetensors");
        let agent = PpoContinuous::new(&PpoContinuousConfig::default(), 2)?;
        let mut tensors = std::collections::HashMap::new();
        for (name, w) in agent.weights()? {
            let t = candle_core::Tensor::from_vec(w.data, w.shape, &candle_core::Device::Cpu)?;
            tensors.insert(name, t);
        }
        candle_core::safetensors::save(&tensors, &path)?;
        let loaded = PpoContinuous::load(&path, &PpoContinuousConfig::default(), 0)?;
        assert_eq!(loaded.weights()?, agent.weights()?);
        let err = Agent::load(&path, &PpoConfig::default(), 0)
            .err()
            .map(|e| e.to_string())
            .unwrap_or_default();
        assert!(
            err.contains("no metadata and no actor.fc2.weight")
                && err.contains("actor.fc_mu.weight"),
            "{err}"
        );
        Ok(())
    }

    #[test]
    fn wrong_shapes_are_named() -> Result<(), Box<dyn std::error::Error>> {
        let mut w = PpoContinuous::new(&PpoContinuousConfig::default(), 0)?.weights()?;
        if let Some(t) = w.get_mut("actor.fc_std.weight") {
            t.shape = vec![2, 64];
        }
        let err = check_weights(&w, 128, "x")
            .err()
            .map(|e| e.to_string())
            .unwrap_or_default();
        assert!(
            err.contains("actor.fc_std.weight") && err.contains("[1, 128]"),
            "{err}"
        );
        Ok(())
    }
}
