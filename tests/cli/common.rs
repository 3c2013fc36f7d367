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

/// The numbers of a JSON array (empty when `v` is not one).
#[must_use]
pub fn numbers(v: &serde_json::Value) -> Vec<f64> {
    v.as_array()
        .map(|a| a.iter().filter_map(serde_json::Value::as_f64).collect())
        .unwrap_or_default()
}

/// What `ppo-tutor` wrote to a pseudo-terminal, once it exited ([`in_terminal`]).
pub struct Terminal {
    /// How it exited.
    pub status: portable_pty::ExitStatus,
    /// Every byte it wrote.
    pub bytes: Vec<u8>,
    /// The screen those bytes leave, as text.
    pub screen: String,
}

/// Runs `ppo-tutor ARGS` in a `rows`×`cols` pseudo-terminal, in the C locale with no
/// language setting and no `RAYON_NUM_THREADS` (it re-runs itself as a user's would) but
/// `env`. Once `ready` is among what it wrote (at once when `ready` is empty), `keys` are
/// typed; then it runs to its end.
///
/// # Errors
/// The terminal cannot be opened, the program not started, or `ready` not seen in 120 s
/// (the error holds the screen).
pub fn in_terminal(
    args: &[&std::ffi::OsStr],
    env: &[(&str, &str)],
    (rows, cols): (u16, u16),
    (ready, keys): (&str, &[u8]),
) -> Result<Terminal, Box<dyn std::error::Error>> {
    use portable_pty::{CommandBuilder, PtySize, native_pty_system};
    use std::io::{Read as _, Write as _};
    let pty = native_pty_system().openpty(PtySize {
        rows,
        cols,
        pixel_width: 0,
        pixel_height: 0,
    })?;
    let mut cmd = CommandBuilder::new(env!("CARGO_BIN_EXE_ppo-tutor"));
    cmd.args(args);
    cmd.env("TERM", "xterm-256color");
    for key in [
        "PPO_TUTOR_LANG",
        "LC_ALL",
        "LC_MESSAGES",
        "RAYON_NUM_THREADS",
    ] {
        cmd.env_remove(key);
    }
    cmd.env("LANG", "C.UTF-8");
    for (key, value) in env {
        cmd.env(key, value);
    }
    let mut child = pty.slave.spawn_command(cmd)?;
    drop(pty.slave);
    let mut reader = pty.master.try_clone_reader()?;
    let (seen, shown) = std::sync::mpsc::channel::<()>();
    let wanted = ready.to_string();
    let reading = std::thread::spawn(move || {
        let mut bytes = Vec::new();
        let mut buf = [0_u8; 8192];
        let mut told = false;
        while let Ok(n) = reader.read(&mut buf) {
            if n == 0 {
                break;
            }
            bytes.extend_from_slice(&buf[..n]);
            if !told && String::from_utf8_lossy(&bytes).contains(&wanted) {
                told = seen.send(()).is_ok();
            }
        }
        bytes
    });
    let began = ready.is_empty()
        || shown
            .recv_timeout(std::time::Duration::from_secs(120))
            .is_ok();
    let mut writer = pty.master.take_writer()?;
    if !keys.is_empty() {
        writer.write_all(keys)?;
        writer.flush()?;
    }
    let status = child.wait()?;
    drop(writer);
    drop(pty.master);
    let bytes = reading.join().map_err(|_| "the reader panicked")?;
    let mut parser = vt100::Parser::new(rows, cols, 0);
    parser.process(&bytes);
    let screen = parser.screen().contents();
    if !began {
        return Err(format!("{ready:?} never on the screen: {screen}").into());
    }
    Ok(Terminal {
        status,
        bytes,
        screen,
    })
}
