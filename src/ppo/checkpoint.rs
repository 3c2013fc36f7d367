//! Saving and loading an agent's weights as safetensors, with PyTorch's parameter names.
//!
//! A checkpoint holds eight f32 tensors, shapes for hidden width `H`:
//!
//! ```text
//! actor.fc1.weight (H, 4)   actor.fc1.bias (H)   actor.fc2.weight (2, H)   actor.fc2.bias (2)
//! critic.fc1.weight (H, 4)  critic.fc1.bias (H)  critic.fc2.weight (1, H)  critic.fc2.bias (1)
//! ```
//!
//! The names and `(out, in)` layout are PyTorch's `state_dict()` of the seed's networks
//! (prefixed `actor.` / `critic.`), so a checkpoint converts to and from
//! `torch.save({**actor.state_dict(), ...})` by renaming nothing. `H` is read from
//! `actor.fc1.weight`; every other shape is then checked against it.

use std::collections::HashMap;
use std::path::Path;

use candle_core::{DType, Device, Tensor};

use super::model::{NamedWeights, WeightTensor};
use super::{ACTION_DIM, Agent, PpoConfig, PpoError, STATE_DIM};

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
    for (name, shape) in parameter_shapes(hidden_dim) {
        let Some(w) = weights.get(name) else {
            return Err(PpoError::MissingKey {
                file: source.into(),
                key: name.into(),
                expected: format!("an f32 tensor of shape {shape:?}"),
            });
        };
        if w.shape != shape || w.data.len() != shape.iter().product::<usize>() {
            return Err(PpoError::WrongShape {
                file: source.into(),
                key: name.into(),
                expected: format!("shape {shape:?} (hidden width {hidden_dim})"),
                got: format!("shape {:?}", w.shape),
            });
        }
        if let Some(i) = w.data.iter().position(|x| !x.is_finite()) {
            return Err(PpoError::WrongShape {
                file: source.into(),
                key: name.into(),
                expected: "finite values".into(),
                got: format!("{} at flat index {i}", w.data[i]),
            });
        }
    }
    if let Some(extra) = weights
        .keys()
        .find(|k| !parameter_shapes(0).iter().any(|(n, _)| n == k))
    {
        return Err(PpoError::WrongShape {
            file: source.into(),
            key: extra.clone(),
            expected: "only the eight actor./critic. parameters".into(),
            got: "an unknown tensor".into(),
        });
    }
    Ok(())
}

impl Agent {
    /// Writes the weights to a safetensors file (f32, PyTorch names).
    ///
    /// # Errors
    /// [`PpoError::File`] when the file cannot be written.
    pub fn save(&self, path: &Path) -> Result<(), PpoError> {
        let mut tensors = HashMap::new();
        for (name, w) in self.weights()? {
            tensors.insert(name, Tensor::from_vec(w.data, w.shape, &Device::Cpu)?);
        }
        candle_core::safetensors::save(&tensors, path).map_err(|e| PpoError::File {
            file: path.display().to_string(),
            reason: format!("cannot write the checkpoint: {e}"),
        })
    }

    /// Reads a checkpoint written by [`Agent::save`]; the hidden width comes from the file
    /// and overrides `config.hidden_dim`. Adam starts fresh; actions are sampled with `seed`.
    ///
    /// # Errors
    /// [`PpoError::File`] for an unreadable file or one that is not safetensors;
    /// [`PpoError::MissingKey`] / [`PpoError::WrongShape`] naming the tensor and its
    /// expected shape.
    pub fn load(path: &Path, config: &PpoConfig, seed: u64) -> Result<Self, PpoError> {
        let file = path.display().to_string();
        let tensors = candle_core::safetensors::load(path, &Device::Cpu).map_err(|e| {
            PpoError::File {
                file: file.clone(),
                reason: format!("not a readable safetensors checkpoint ({e}); write one with `ppo-tutor train --save FILE.safetensors`"),
            }
        })?;
        let mut weights = NamedWeights::new();
        for (name, t) in tensors {
            let shape = t.dims().to_vec();
            let data = t
                .to_dtype(DType::F32)
                .and_then(|t| t.flatten_all())
                .and_then(|t| t.to_vec1::<f32>())
                .map_err(|e| PpoError::WrongShape {
                    file: file.clone(),
                    key: name.clone(),
                    expected: "an f32 tensor".into(),
                    got: format!("{:?} ({e})", t.dtype()),
                })?;
            weights.insert(name, WeightTensor { shape, data });
        }
        let hidden_dim = match weights.get("actor.fc1.weight").map(|w| w.shape.as_slice()) {
            Some(&[h, STATE_DIM]) if h > 0 => h,
            Some(other) => {
                return Err(PpoError::WrongShape {
                    file,
                    key: "actor.fc1.weight".into(),
                    expected: format!("shape [hidden, {STATE_DIM}]"),
                    got: format!("shape {other:?}"),
                });
            }
            None => {
                return Err(PpoError::MissingKey {
                    file,
                    key: "actor.fc1.weight".into(),
                    expected: format!("an f32 tensor of shape [hidden, {STATE_DIM}]"),
                });
            }
        };
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
