//! Training, showing live values and grading run candle, whose matrix products are faster
//! on one thread here: the command re-runs itself with `RAYON_NUM_THREADS=1`.

use std::process::ExitCode;

/// Re-runs this `ppo-tutor` process with `RAYON_NUM_THREADS=1` when it is unset.
///
/// Without the variable, candle asks the OS for the number of physical cores (by reading
/// `/proc/cpuinfo`) on every matrix product: ~30 µs each, ~50% of the time of the seed's
/// default run with 4x128 networks (measured 7.2 s vs 3.4 s for 500 episodes). Setting the
/// variable in-process needs `unsafe` (`std::env::set_var`, edition 2024), which this crate
/// forbids; re-running the binary costs a millisecond. A value set by the user is kept.
/// Returns `None` to go on in this process (variable set, or not the `ppo-tutor` binary,
/// as when a test calls [`super::run`] in-process).
pub(super) fn rerun_with_one_candle_thread() -> Option<anyhow::Result<ExitCode>> {
    if std::env::var_os("RAYON_NUM_THREADS").is_some() {
        return None;
    }
    let exe = std::env::current_exe().ok()?;
    if exe.file_stem().and_then(|s| s.to_str()) != Some("ppo-tutor") {
        return None;
    }
    let mut command = std::process::Command::new(&exe);
    command
        .args(std::env::args_os().skip(1))
        .env("RAYON_NUM_THREADS", "1");
    Some(rerun(command, &exe))
}

/// Runs `command`, this program again with one candle thread. On Unix it replaces this
/// process (the same PID, so a signal meant for `ppo-tutor` reaches it, and nothing is left
/// running when it is killed: a child used to outlive a SIGTERM); `exec` returns only when
/// it fails.
#[cfg(unix)]
fn rerun(mut command: std::process::Command, exe: &std::path::Path) -> anyhow::Result<ExitCode> {
    use std::os::unix::process::CommandExt as _;
    let e = command.exec();
    Err(anyhow::Error::new(e).context(format!("re-running {}", exe.display())))
}

/// Runs `command`, this program again with one candle thread, and exits with its code.
/// Ctrl-C reaches both processes: this one ignores it, so that the child's answer
/// ([`super::interrupt`]) and exit code are what the user sees.
#[cfg(not(unix))]
fn rerun(mut command: std::process::Command, exe: &std::path::Path) -> anyhow::Result<ExitCode> {
    interrupt::ignore_in_parent();
    match command.status() {
        Ok(status) => Ok(status
            .code()
            .and_then(|c| u8::try_from(c).ok())
            .map_or(ExitCode::FAILURE, ExitCode::from)),
        Err(e) => Err(anyhow::Error::new(e).context(format!("re-running {}", exe.display()))),
    }
}
