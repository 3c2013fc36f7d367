//! What the binary's tests share.

use std::process::Command;

/// The binary in English whatever the machine's locale: `PPO_TUTOR_LANG=en`, and no
/// `LC_ALL`/`LC_MESSAGES`, `LANG=C.UTF-8` (a Chinese CI locale must not change what the
/// English tests read).
#[must_use]
pub fn english() -> Command {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_ppo-tutor"));
    cmd.env("PPO_TUTOR_LANG", "en")
        .env_remove("LC_ALL")
        .env_remove("LC_MESSAGES")
        .env("LANG", "C.UTF-8");
    cmd
}

/// The binary with no language setting at all but `env` (the locale variables and
/// `PPO_TUTOR_LANG` are removed first).
#[must_use]
pub fn with_env(env: &[(&str, &str)]) -> Command {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_ppo-tutor"));
    for key in ["PPO_TUTOR_LANG", "LC_ALL", "LC_MESSAGES", "LANG"] {
        cmd.env_remove(key);
    }
    cmd.envs(env.iter().copied());
    cmd
}

/// The tensors of a CartPole checkpoint, zeros, with `critic.fc2.weight` of the wrong shape
/// (`[1, 64]`: the hidden width is 128), for the tests of a checkpoint that does not fit.
///
/// # Errors
/// candle cannot make a tensor.
pub fn cartpole_tensors_with_a_wrong_shape()
-> candle_core::Result<std::collections::HashMap<&'static str, candle_core::Tensor>> {
    use candle_core::{DType, Device, Tensor};
    let mut tensors = std::collections::HashMap::new();
    for (name, shape) in [
        ("actor.fc1.weight", vec![128, 4]),
        ("actor.fc1.bias", vec![128]),
        ("actor.fc2.weight", vec![2, 128]),
        ("actor.fc2.bias", vec![2]),
        ("critic.fc1.weight", vec![128, 4]),
        ("critic.fc1.bias", vec![128]),
        ("critic.fc2.weight", vec![1, 64]),
        ("critic.fc2.bias", vec![1]),
    ] {
        tensors.insert(name, Tensor::zeros(shape, DType::F32, &Device::Cpu)?);
    }
    Ok(tensors)
}
