//! The `ppo-tutor` binary: parses the command line and hands it to the library.

use std::process::ExitCode;

fn main() -> ExitCode {
    ppo_tutor::cli::main_with_args(std::env::args_os())
}
