//! The `ppo-tutor` binary: parses the command line and hands it to the library.

use std::process::ExitCode;

fn main() -> ExitCode {
    // With the notebook runner built in (`dev notebooks`), evcxr re-runs this binary as its
    // runtime: the runtime must take over first.
    #[cfg(feature = "notebook-runner")]
    ppo_tutor::generator::kernel::runtime_hook();
    ppo_tutor::cli::main_with_args(std::env::args_os())
}
