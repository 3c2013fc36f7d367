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
//!
//! A checkpoint says which agent it holds ([`CheckpointKind`]): the safetensors metadata
//! `{"env": "CartPole-v1", "algorithm": "ppo"}` (or `Pendulum-v1` / `ppo-continuous` for
//! [`PpoContinuous`](super::PpoContinuous)), and, for files without it (older ones, or
//! written by PyTorch), the parameter names: `actor.fc2` is the CartPole policy,
//! `actor.fc_mu` / `actor.fc_std` the Pendulum one. Loading one agent's checkpoint as
//! another is refused with a message naming what the file holds and what was asked for.

use crate::i18n::t;
use std::collections::HashMap;
use std::path::Path;

use candle_core::{DType, Device, Tensor};

use super::PpoError;
use super::model::{NamedWeights, WeightTensor};

/// Which agent a checkpoint holds: the environment and the algorithm it was trained for.
///
/// Each agent declares its own, beside its code, as [`OnPolicyAgent::CHECKPOINT`](super::OnPolicyAgent::CHECKPOINT)
/// ([`Agent`](crate::ppo::Agent)'s is `CartPole-v1` / `ppo`, [`PpoContinuous`](super::PpoContinuous)'s
/// `Pendulum-v1` / `ppo-continuous`); the core keeps no list of them. Telling which of several
/// agents a file holds takes the list of candidates ([`CheckpointKind::of_file`]), which the
/// course's registry of agents supplies.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct CheckpointKind {
    /// Gymnasium's id of the environment (`CartPole-v1`, `Pendulum-v1`).
    pub env: &'static str,
    /// The algorithm's name in the metadata (`ppo`, `ppo-continuous`).
    pub algorithm: &'static str,
    /// A parameter name only this kind has, by which files without metadata (older ones, or
    /// written by PyTorch) are recognised (`actor.fc2.weight`, `actor.fc_mu.weight`).
    pub telltale: &'static str,
    /// The flags `ppo-tutor train` needs, before `--save`, to write one (`""`, or
    /// `"--env Pendulum-v1 "`), for error messages.
    pub train_flags: &'static str,
}

impl CheckpointKind {
    /// How to write a checkpoint of this kind, for error messages.
    fn how_to_save(self) -> String {
        let flags = self.train_flags;
        crate::tr!(
            "write one with `ppo-tutor train {flags}--save FILE.safetensors`",
            "可用 `ppo-tutor train {flags}--save <文件>.safetensors` 生成一个"
        )
    }

    /// The safetensors metadata written with a checkpoint of this kind.
    #[must_use]
    pub fn metadata(self) -> HashMap<String, String> {
        HashMap::from([
            ("env".to_string(), self.env.to_string()),
            ("algorithm".to_string(), self.algorithm.to_string()),
        ])
    }

    /// Whether `metadata` names an agent at all (every file `write_checkpoint` wrote): then
    /// it alone says which, and the parameter names are not consulted.
    fn names_an_agent(metadata: &HashMap<String, String>) -> bool {
        metadata.contains_key("env") && metadata.contains_key("algorithm")
    }

    /// Whether `metadata` names this kind.
    fn named_by(self, metadata: &HashMap<String, String>) -> bool {
        metadata.get("env").map(String::as_str) == Some(self.env)
            && metadata.get("algorithm").map(String::as_str) == Some(self.algorithm)
    }

    /// Which of `kinds` the file at `path` holds, by its metadata or else its parameter
    /// names; `None` when it cannot be told (an unreadable file: loading it reports why).
    #[must_use]
    pub fn of_file(path: &Path, kinds: &[CheckpointKind]) -> Option<Self> {
        let bytes = std::fs::read(path).ok()?;
        let (_, header) = safetensors::SafeTensors::read_metadata(&bytes).ok()?;
        match header.metadata() {
            Some(metadata) if Self::names_an_agent(metadata) => {
                kinds.iter().copied().find(|k| k.named_by(metadata))
            }
            _ => {
                let names = header.offset_keys();
                kinds
                    .iter()
                    .copied()
                    .find(|k| names.iter().any(|n| n == k.telltale))
            }
        }
    }
}

/// Writes `weights` to a safetensors file (f32, PyTorch names) with `kind`'s metadata,
/// atomically and with the permissions of any new file ([`crate::files::write_atomically`]:
/// not the `0o600` of safetensors' own temporary file).
///
/// # Errors
/// [`PpoError::File`] naming `path` when the file cannot be written.
pub fn write_checkpoint(
    path: &Path,
    weights: NamedWeights,
    kind: CheckpointKind,
) -> Result<(), PpoError> {
    let mut tensors = Vec::with_capacity(weights.len());
    for (name, w) in weights {
        tensors.push((name, Tensor::from_vec(w.data, w.shape, &Device::Cpu)?));
    }
    let cannot_write = |said: String| PpoError::File {
        file: path.display().to_string(),
        reason: crate::tr!(
            "cannot write the checkpoint: {said}",
            "无法写入检查点：{said}"
        ),
    };
    let bytes = safetensors::serialize(tensors, Some(kind.metadata()))
        .map_err(|e| cannot_write(crate::causes::message(&e)))?;
    crate::files::write_atomically(path, &bytes)
        .map_err(|e| cannot_write(crate::causes::message(&e)))
}

/// Reads a checkpoint's tensors as f32, refusing one that holds another kind of agent than
/// `want` (by its metadata, or else by its parameter names).
///
/// # Errors
/// [`PpoError::File`] for an unreadable file, one that is not safetensors, or one of another
/// kind (the message names both kinds); [`PpoError::WrongShape`] for a tensor that is not
/// a number type.
pub fn read_checkpoint(path: &Path, want: CheckpointKind) -> Result<NamedWeights, PpoError> {
    let file = path.display().to_string();
    let unreadable = |e: &(dyn std::error::Error + 'static)| {
        let (said, how) = (crate::causes::message(e), want.how_to_save());
        PpoError::File {
            file: file.clone(),
            reason: crate::tr!(
                "not a readable safetensors checkpoint ({said}); {how}",
                "不是可读取的 safetensors 检查点（{said}）；{how}"
            ),
        }
    };
    let bytes = std::fs::read(path).map_err(|e| unreadable(&e))?;
    let metadata = safetensors::SafeTensors::read_metadata(&bytes)
        .map_err(|e| unreadable(&e))?
        .1
        .metadata()
        .clone()
        .unwrap_or_default();
    let tensors =
        candle_core::safetensors::load_buffer(&bytes, &Device::Cpu).map_err(|e| unreadable(&e))?;
    let mismatch = match (metadata.get("env"), metadata.get("algorithm")) {
        // A file that names its agent (every file `write_checkpoint` wrote) says which.
        (Some(env), Some(algorithm)) => (!want.named_by(&metadata)).then(|| {
            crate::tr!(
                "this checkpoint holds a {algorithm} agent for {env} (its metadata says so), \
                 not a {} agent for {}: load it as a {env} agent, or {}",
                "这个检查点保存的是 {env} 上的 {algorithm} 智能体（文件的元数据如此标明），\
                 不是 {1} 上的 {0} 智能体：请把它当作 {env} 的智能体加载，或者{2}",
                want.algorithm,
                want.env,
                want.how_to_save()
            )
        }),
        // One without (written by PyTorch, say) must have the parameter only `want` has.
        _ => (!tensors.contains_key(want.telltale)).then(|| {
            let mut names: Vec<&str> = tensors.keys().map(String::as_str).collect();
            names.sort_unstable();
            let names = names.join(", ");
            crate::tr!(
                "this checkpoint has no metadata and no {}, so it is not a {} agent for {} \
                 (it has {names}); {}",
                "这个检查点没有元数据，也没有 {0}，所以不是 {2} 上的 {1} 智能体\
                 （文件中有 {names}）；{3}",
                want.telltale,
                want.algorithm,
                want.env,
                want.how_to_save()
            )
        }),
    };
    if let Some(reason) = mismatch {
        return Err(PpoError::File { file, reason });
    }
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
                expected: crate::i18n::t("an f32 tensor", "f32 张量").into(),
                got: format!("{:?} ({e})", t.dtype()),
            })?;
        weights.insert(name, WeightTensor { shape, data });
    }
    Ok(weights)
}

/// Checks that `weights` holds exactly the tensors of `shapes` (name, shape for hidden width
/// `hidden_dim`), with finite values; `only` says what an unknown tensor should have been.
/// Both agents' checkpoints are checked with it.
///
/// # Errors
/// [`PpoError::MissingKey`] or [`PpoError::WrongShape`] naming the tensor in `source`.
pub(crate) fn check_against(
    weights: &NamedWeights,
    shapes: &[(&'static str, Vec<usize>)],
    hidden_dim: usize,
    source: &str,
    only: &str,
) -> Result<(), PpoError> {
    for (name, shape) in shapes {
        let Some(w) = weights.get(*name) else {
            return Err(PpoError::MissingKey {
                file: source.into(),
                key: (*name).into(),
                expected: crate::tr!(
                    "an f32 tensor of shape {shape:?}",
                    "形状 {shape:?} 的 f32 张量"
                ),
            });
        };
        if w.shape != *shape || w.data.len() != shape.iter().product::<usize>() {
            return Err(PpoError::WrongShape {
                file: source.into(),
                key: (*name).into(),
                expected: crate::tr!(
                    "shape {shape:?} (hidden width {hidden_dim})",
                    "形状 {shape:?}（隐藏层宽度 {hidden_dim}）"
                ),
                got: crate::tr!("shape {:?}", "形状 {:?}", w.shape),
            });
        }
        if let Some(i) = w.data.iter().position(|x| !x.is_finite()) {
            return Err(PpoError::WrongShape {
                file: source.into(),
                key: (*name).into(),
                expected: t("finite values", "有限数值").into(),
                got: crate::tr!("{} at flat index {i}", "展平后下标 {i} 处的 {}", w.data[i]),
            });
        }
    }
    if let Some(extra) = weights.keys().find(|k| !shapes.iter().any(|(n, _)| n == k)) {
        return Err(PpoError::WrongShape {
            file: source.into(),
            key: extra.clone(),
            expected: only.into(),
            got: t("an unknown tensor", "一个未知的张量").into(),
        });
    }
    Ok(())
}

/// Reads a checkpoint of `kind` whose first layer takes `state_dim` inputs: its weights,
/// the hidden width they have (which overrides the config's), and the file's name for
/// errors. Both agents' `load` start here.
///
/// # Errors
/// As [`read_checkpoint`], and [`PpoError::MissingKey`] / [`PpoError::WrongShape`] for a
/// first layer missing or not of shape `[hidden, state_dim]`.
pub fn read_sized(
    path: &Path,
    kind: CheckpointKind,
    state_dim: usize,
) -> Result<(NamedWeights, usize, String), PpoError> {
    let file = path.display().to_string();
    let weights = read_checkpoint(path, kind)?;
    let key = "actor.fc1.weight";
    let hidden_dim = match weights.get(key).map(|w| w.shape.as_slice()) {
        Some(&[h, n]) if h > 0 && n == state_dim => h,
        Some(other) => {
            return Err(PpoError::WrongShape {
                file,
                key: key.into(),
                expected: crate::tr!("shape [hidden, {state_dim}]", "形状 [hidden, {state_dim}]"),
                got: crate::tr!("shape {other:?}", "形状 {other:?}"),
            });
        }
        None => {
            return Err(PpoError::MissingKey {
                file,
                key: key.into(),
                expected: crate::tr!(
                    "an f32 tensor of shape [hidden, {state_dim}]",
                    "形状 [hidden, {state_dim}] 的 f32 张量"
                ),
            });
        }
    };
    Ok((weights, hidden_dim, file))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ppo::{Agent, PpoConfig};

    /// A checkpoint is a new file like any other: the mode `File::create` gives here (0o644
    /// under the umask 022; safetensors' own writer left 0o600), and no temporary file is
    /// left beside it, written or not.
    #[test]
    fn a_checkpoint_has_the_usual_mode_and_leaves_nothing_else()
    -> Result<(), Box<dyn std::error::Error>> {
        let dir = tempfile::tempdir()?;
        let path = dir.path().join("agent.safetensors");
        let weights = Agent::new(&PpoConfig::default(), 0)?.weights()?;
        write_checkpoint(
            &path,
            weights.clone(),
            <Agent as crate::ppo::OnPolicyAgent>::CHECKPOINT,
        )?;
        #[cfg(unix)]
        {
            use std::os::unix::fs::PermissionsExt as _;
            let reference = dir.path().join("reference");
            std::fs::File::create(&reference)?;
            let mode = |p: &Path| std::fs::metadata(p).map(|m| m.permissions().mode() & 0o777);
            assert_eq!(mode(&path)?, mode(&reference)?);
            std::fs::remove_file(&reference)?;
        }
        let folder = dir.path().join("a-folder");
        std::fs::create_dir(&folder)?;
        let err = write_checkpoint(
            &folder,
            weights,
            <Agent as crate::ppo::OnPolicyAgent>::CHECKPOINT,
        )
        .err()
        .map(|e| e.to_string())
        .unwrap_or_default();
        assert!(
            err.contains("a-folder: cannot write the checkpoint"),
            "{err}"
        );
        let names: Vec<String> = std::fs::read_dir(dir.path())?
            .map(|e| e.map(|e| e.file_name().to_string_lossy().into_owned()))
            .collect::<Result<_, _>>()?;
        assert_eq!(names.len(), 2, "{names:?}");
        Ok(())
    }
}
