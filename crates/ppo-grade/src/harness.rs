//! The serving loop of every program the grader builds: it reads one request per line on
//! stdin, answers each with the exercise's function, and keeps its answers apart from
//! whatever the learner's code prints.
//!
//! This file is compiled twice: into ppo-tutor (where it is tested), and, copied as text
//! next to the learner's file, into each learner program (a plain `rustc` build or the
//! candle project). It therefore uses nothing but `std`, and reads the same in editions
//! 2021 and 2024.
//!
//! The learner's code may print (`println!`, `eprintln!`, `dbg!`): its stdout and stderr
//! are the program's own. So that a print cannot pass for an answer, the grader gives the
//! program a marker (the environment variable [`MARKER_VAR`], fresh for every run) and
//! every line the harness writes starts with it, on a line of its own:
//!
//! ```text
//! stderr: \n<marker> end\n              after each request, what was printed to stderr ends
//! stdout: \n<marker> ok <result>\n      then the answer (or `error <message>`, `panic <message>`)
//! ```
//!
//! The newline before the marker ends a line the learner left open (`print!("x")`); the
//! grader drops the one empty line that newline makes when the learner's last line was
//! complete. Everything else on either stream is what the learner printed while answering
//! that request ([`crate::learner`] keeps a few lines of it per case for the report).
//!
//! A panic is caught per request: the panic hook keeps its message and place (printing
//! nothing), and the answer is `panic <message> (at file:line:column)`. The program exits
//! when stdin closes, and also when the grader that started it is gone (on Unix its parent
//! changes), so a learner's endless loop does not outlive an interrupted grading.

use std::io::{BufRead, Write};

/// The environment variable that carries the marker of the harness's own lines.
pub const MARKER_VAR: &str = "PPO_TUTOR_GRADE_MARKER";

/// The marker when the program is run by hand, without [`MARKER_VAR`].
pub const DEFAULT_MARKER: &str = "@@ppo-tutor-grade@@";

/// A panic's message (`panic!("...")` with or without arguments), or a placeholder.
#[must_use]
pub fn panic_text(payload: &(dyn std::any::Any + Send)) -> String {
    payload
        .downcast_ref::<&str>()
        .map(|s| (*s).to_string())
        .or_else(|| payload.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "a panic without a message".to_string())
}

/// Answers every request line on stdin with `answer` (which returns the reply line, `ok
/// ...` or `error ...`), until stdin closes.
pub fn serve(mut answer: impl FnMut(&str) -> String) {
    let marker = std::env::var(MARKER_VAR).unwrap_or_else(|_| DEFAULT_MARKER.to_string());
    let last_panic = std::sync::Arc::new(std::sync::Mutex::new(String::new()));
    let slot = std::sync::Arc::clone(&last_panic);
    std::panic::set_hook(Box::new(move |info| {
        let text = panic_text(info.payload());
        let place = info
            .location()
            .map(|l| format!(" (at {}:{}:{})", l.file(), l.line(), l.column()))
            .unwrap_or_default();
        if let Ok(mut m) = slot.lock() {
            *m = format!("{text}{place}");
        }
    }));
    exit_with_parent();
    let stdin = std::io::stdin();
    for line in stdin.lock().lines() {
        let Ok(line) = line else { break };
        let run = std::panic::AssertUnwindSafe(|| answer(&line));
        let reply = match std::panic::catch_unwind(run) {
            Ok(reply) => reply,
            Err(_) => {
                let m = last_panic.lock().map(|m| m.clone()).unwrap_or_default();
                format!("panic {m}")
            }
        };
        let reply = reply.replace('\n', " ");
        // Unbuffered: what the learner printed to stderr is in the pipe before this.
        let _ = write!(std::io::stderr(), "\n{marker} end\n");
        // The lock only while writing: a thread of the learner's may print too.
        let mut out = std::io::stdout().lock();
        if write!(out, "\n{marker} {reply}\n")
            .and_then(|()| out.flush())
            .is_err()
        {
            break;
        }
    }
}

/// Ends the program once the process that started it has gone (the grader was
/// interrupted): the grader runs the program in a process group of its own, which a
/// Ctrl-C in the terminal does not reach.
fn exit_with_parent() {
    #[cfg(unix)]
    {
        let parent = std::os::unix::process::parent_id();
        let _ = std::thread::Builder::new().spawn(move || {
            loop {
                std::thread::sleep(std::time::Duration::from_millis(200));
                if std::os::unix::process::parent_id() != parent {
                    std::process::exit(2);
                }
            }
        });
    }
}

#[cfg(test)]
mod tests {
    use crate::spec::Spec;

    #[test]
    fn every_learner_program_is_served_by_this_loop() {
        // The programs are text: each declares this file, carries it, and calls `serve`.
        let programs = [
            Spec::program(&crate::exercises::reverse_kl::EXERCISE),
            Spec::program(&crate::exercises::ppo_losses::EXERCISE),
        ];
        for program in programs {
            assert!(
                program.main.contains("#[path = \"harness.rs\"]"),
                "{}",
                program.main
            );
            assert!(program.main.contains("serve("), "{}", program.main);
            assert!(
                program
                    .files
                    .contains(&("harness.rs", crate::build::HARNESS))
            );
        }
    }
}
