//! Ctrl-C during `train`: the run stops at the end of the episode
//! under way, says where it stopped and what was written, and exits with 130 (128 + SIGINT,
//! what a shell reports for a program that Ctrl-C ended). A second Ctrl-C ends the process
//! at once, with the same code.
//!
//! On Unix `ppo-tutor` re-runs itself with one candle thread by replacing its process
//! (`exec`, see `cli::rerun`), so the signal reaches this process and no other. Elsewhere
//! the first process waits for its child: it ignores Ctrl-C (`ignore_in_parent`) so that
//! the child's message and exit code are what the user sees.

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

use crate::tr;

/// Exit code of a run stopped by Ctrl-C: 128 + SIGINT (2).
pub const EXIT_INTERRUPTED: u8 = 130;

/// Whether Ctrl-C was pressed since [`Interrupt::install`].
#[derive(Debug, Clone)]
pub struct Interrupt {
    pressed: Arc<AtomicBool>,
}

impl Interrupt {
    /// Catches Ctrl-C (SIGINT) from now on: the first sets the flag [`Self::pressed`]
    /// reads, the next ends the process with [`EXIT_INTERRUPTED`]. Where the handler cannot
    /// be installed, Ctrl-C keeps its default (the process ends at once).
    #[must_use]
    pub fn install() -> Self {
        let pressed = Arc::new(AtomicBool::new(false));
        let code = i32::from(EXIT_INTERRUPTED);
        // The shutdown goes first: it ends the process only when the flag is already set.
        let _ = signal_hook::flag::register_conditional_shutdown(
            signal_hook::consts::SIGINT,
            code,
            Arc::clone(&pressed),
        )
        .and_then(|_| {
            signal_hook::flag::register(signal_hook::consts::SIGINT, Arc::clone(&pressed))
        });
        Self { pressed }
    }

    /// Whether Ctrl-C was pressed.
    #[must_use]
    pub fn pressed(&self) -> bool {
        self.pressed.load(Ordering::Relaxed)
    }
}

/// The line a run stopped by Ctrl-C prints: after `done` of `total` episodes, and what was
/// written: nothing, or the outputs in `written` (and not those in `not_written`).
#[must_use]
pub fn stopped_line(
    done: usize,
    total: usize,
    written: &[String],
    not_written: &[String],
) -> String {
    let outputs = if written.is_empty() {
        if not_written.is_empty() {
            tr!("nothing was saved", "没有保存任何内容")
        } else {
            let list = not_written.join(", ");
            tr!(
                "nothing was saved ({list} not written)",
                "没有保存任何内容（{list} 均未写入）"
            )
        }
    } else {
        let list = written.join(", ");
        if not_written.is_empty() {
            tr!("written: {list}", "已写入：{list}")
        } else {
            let missing = not_written.join(", ");
            tr!(
                "written: {list}; not written: {missing}",
                "已写入：{list}；未写入：{missing}"
            )
        }
    };
    if done < total {
        tr!(
            "stopped by Ctrl-C after {done} of {total} episodes; {outputs}",
            "已按 Ctrl-C 中止：训练了 {done} 个回合（共 {total} 个）后停止；{outputs}"
        )
    } else {
        tr!(
            "stopped by Ctrl-C after all {total} episodes; {outputs}",
            "已按 Ctrl-C 中止：全部 {total} 个回合已训练完；{outputs}"
        )
    }
}

/// In the first process of a re-run that waits for its child (not on Unix, where the re-run
/// replaces the process): ignores Ctrl-C, which the child gets too and answers.
#[cfg(not(unix))]
pub(crate) fn ignore_in_parent() {
    let _ = signal_hook::flag::register(
        signal_hook::consts::SIGINT,
        Arc::new(AtomicBool::new(false)),
    );
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::i18n::Lang;

    #[test]
    fn the_line_says_where_and_what() {
        let _en = Lang::En.scoped();
        let none = stopped_line(137, 500, &[], &[]);
        assert_eq!(
            none,
            "stopped by Ctrl-C after 137 of 500 episodes; nothing was saved"
        );
        let asked = stopped_line(3, 500, &[], &["--save a.safetensors".into()]);
        assert!(
            asked.ends_with("(--save a.safetensors not written)"),
            "{asked}"
        );
        let some = stopped_line(
            500,
            500,
            &["--json run.json".into()],
            &["--plot r.svg".into()],
        );
        assert!(
            some.contains("after all 500 episodes")
                && some.contains("written: --json run.json; not written: --plot r.svg"),
            "{some}"
        );
        let _zh = Lang::Zh.scoped();
        assert!(stopped_line(137, 500, &[], &[]).contains("训练了 137 个回合（共 500 个）"));
    }
}
