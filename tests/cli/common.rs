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
