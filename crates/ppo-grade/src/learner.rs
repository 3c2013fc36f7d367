//! Where answers come from: the learner's program ([`LearnerProcess`], over a pipe) or their
//! function running in this process ([`InProcess`], on a worker thread). Both answer one
//! question at a time with the same [`Answer`], so one judge serves both.
//!
//! A panic is caught per question and reported with its message; a question not answered
//! by its deadline stops the learner (a program is killed; a thread is left behind, and in
//! a notebook the kernel must be restarted to stop it); later questions are not asked.

use std::io::{BufRead, BufReader, Read, Write};
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::process::{Child, ChildStdin, Command, Stdio};
use std::sync::mpsc::{self, Receiver, RecvTimeoutError};
use std::sync::{Mutex, MutexGuard, PoisonError};
use std::time::{Duration, Instant};

use super::build::Program;
use super::error::GradeError;
use crate::i18n::Text;
use crate::text;

/// The name a report gives to code graded in place (a notebook cell).
pub const IN_PLACE: Text = Text::new("notebook cell", "笔记本单元格");

/// How long a function graded in place may take: on all cases together (plain
/// exercises), or on each call (the candle exercise).
pub const IN_PLACE_LIMIT: Duration = Duration::from_secs(10);

/// A panic's message (`panic!("...")` with or without arguments), or a placeholder. (The
/// candle exercise's protocol has its own copy: it is compiled standalone into the
/// learner's program, with nothing but `std` and candle.)
#[must_use]
pub fn panic_message(payload: &(dyn std::any::Any + Send)) -> String {
    payload
        .downcast_ref::<&str>()
        .map(|s| (*s).to_string())
        .or_else(|| payload.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "a panic without a message".to_string())
}

/// What the learner's function did on one question.
#[derive(Debug, Clone, PartialEq)]
pub enum Answer<R> {
    /// It answered.
    Value(R),
    /// It returned an error (the candle exercise): the message.
    Error(String),
    /// It panicked: the message (and place, for a program).
    Panicked(String),
    /// No answer within the time limit (seconds).
    TimedOut(u64),
    /// The program died (stack overflow, `process::exit`, ...) or answered nonsense.
    Crashed(Text),
    /// Not asked: the learner had already stopped.
    NotRun,
}

impl Answer<String> {
    /// The answer with its text read by `read`; unreadable text is a crash.
    pub fn and_then<R>(self, read: impl FnOnce(String) -> Result<R, Text>) -> Answer<R> {
        match self {
            Self::Value(text) => read(text).map_or_else(Answer::Crashed, Answer::Value),
            Self::Error(m) => Answer::Error(m),
            Self::Panicked(m) => Answer::Panicked(m),
            Self::TimedOut(s) => Answer::TimedOut(s),
            Self::Crashed(m) => Answer::Crashed(m),
            Self::NotRun => Answer::NotRun,
        }
    }
}

/// Something that answers questions `Q` with replies `R`.
pub trait Learner<Q, R> {
    /// The answer to `question` by `deadline` (`limit` is what the deadline allows, for
    /// the report); [`Answer::NotRun`] once stopped.
    fn ask(&mut self, question: &Q, deadline: Instant, limit: Duration) -> Answer<R>;
    /// Whether the learner has stopped (timed out, crashed): later questions are not asked.
    fn is_stopped(&self) -> bool;
}

fn seconds(limit: Duration) -> u64 {
    limit.as_secs().max(1)
}

/// A running learner program: one question per line on stdin, one answer per line on
/// stdout (`ok <reply>`, `error <message>` or `panic <message>`).
#[derive(Debug)]
pub struct LearnerProcess {
    child: Child,
    stdin: Option<ChildStdin>,
    lines: Receiver<String>,
    stderr: Option<std::thread::JoinHandle<String>>,
    program: Program,
    display: String,
    stopped: bool,
}

impl LearnerProcess {
    /// Starts `program`; `display` replaces its name for the learner's file in messages.
    ///
    /// # Errors
    /// [`GradeError::Run`] if it cannot be started.
    pub fn start(program: &Program, display: &str) -> Result<Self, GradeError> {
        let mut child = Command::new(&program.binary)
            .env("RAYON_NUM_THREADS", "1")
            .env("RUST_BACKTRACE", "0")
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .map_err(|e| GradeError::Run {
                binary: program.binary.clone(),
                reason: crate::error::reason(&e),
            })?;
        let (tx, lines) = mpsc::channel();
        if let Some(stdout) = child.stdout.take() {
            std::thread::spawn(move || {
                for line in BufReader::new(stdout).lines().map_while(Result::ok) {
                    if tx.send(line).is_err() {
                        return;
                    }
                }
            });
        }
        let stderr = child.stderr.take().map(|mut s| {
            std::thread::spawn(move || {
                let mut text = String::new();
                let _ = s.read_to_string(&mut text);
                text
            })
        });
        Ok(Self {
            stdin: child.stdin.take(),
            child,
            lines,
            stderr,
            program: program.clone(),
            display: display.to_string(),
            stopped: false,
        })
    }

    /// Whether the program has stopped (timed out, crashed).
    #[must_use]
    pub fn is_stopped(&self) -> bool {
        self.stopped
    }

    /// Sends `line` and waits until `deadline` for the answer; a value is the text after
    /// `ok `.
    pub fn ask(&mut self, line: &str, deadline: Instant, limit: Duration) -> Answer<String> {
        if self.stopped {
            return Answer::NotRun;
        }
        let sent = self.stdin.as_mut().is_some_and(|stdin| {
            writeln!(stdin, "{line}")
                .and_then(|()| stdin.flush())
                .is_ok()
        });
        let reply = if sent {
            self.lines
                .recv_timeout(deadline.saturating_duration_since(Instant::now()))
        } else {
            Err(RecvTimeoutError::Disconnected)
        };
        match reply {
            Ok(reply) => self.parse(&reply),
            Err(RecvTimeoutError::Timeout) => {
                self.stop();
                Answer::TimedOut(seconds(limit))
            }
            Err(RecvTimeoutError::Disconnected) => {
                let status = self.stop();
                let stderr = self
                    .stderr
                    .take()
                    .and_then(|h| h.join().ok())
                    .unwrap_or_default();
                let stderr = self.program.rename(stderr.trim(), &self.display);
                let last = stderr.lines().last().map(str::to_string);
                let last = last.map_or(Text::new("no message", "没有消息"), Text::same);
                Answer::Crashed(text!(
                    "the program stopped ({status}): {last}",
                    "程序停止了（{status}）：{last}",
                    status = status.get(),
                    last = last.get()
                ))
            }
        }
    }

    fn parse(&self, line: &str) -> Answer<String> {
        let rename = |m: &str| self.program.rename(m, &self.display);
        if let Some(payload) = line.strip_prefix("ok ") {
            Answer::Value(payload.to_string())
        } else if let Some(m) = line.strip_prefix("error ") {
            Answer::Error(rename(m))
        } else if let Some(m) = line.strip_prefix("panic ") {
            Answer::Panicked(rename(m))
        } else {
            Answer::Crashed(text!("unexpected output '{line}'", "意外的输出 '{line}'"))
        }
    }

    /// Kills the program (if still running) and says how it ended.
    fn stop(&mut self) -> Text {
        self.stopped = true;
        self.stdin = None;
        let _ = self.child.kill();
        match self.child.wait() {
            Ok(status) => exit_status(status),
            Err(e) => text!("its end unknown: {e}", "无法得知它如何结束：{e}"),
        }
    }
}

/// How a program ended: its exit code, or the signal that ended it.
fn exit_status(status: std::process::ExitStatus) -> Text {
    if let Some(code) = status.code() {
        return text!("exit code {code}", "退出码 {code}");
    }
    #[cfg(unix)]
    {
        use std::os::unix::process::ExitStatusExt as _;
        if let Some(signal) = status.signal() {
            return text!("signal {signal}", "信号 {signal}");
        }
    }
    Text::same(status.to_string())
}

impl Drop for LearnerProcess {
    fn drop(&mut self) {
        if !self.stopped {
            self.stop();
        }
    }
}

/// A function running on a worker thread of this process: the in-place counterpart of
/// [`LearnerProcess`].
pub struct InProcess<Q, R> {
    requests: Option<mpsc::Sender<Q>>,
    replies: Receiver<Answer<R>>,
    stopped: bool,
}

impl<Q: Send + 'static, R: Send + 'static> InProcess<Q, R> {
    /// Starts the worker thread around `function` (an `Err` is the function's error).
    ///
    /// # Errors
    /// The thread cannot be started.
    pub fn start(
        function: impl Fn(&Q) -> Result<R, String> + Send + 'static,
    ) -> std::io::Result<Self> {
        let (requests, inbox) = mpsc::channel::<Q>();
        let (outbox, replies) = mpsc::channel();
        std::thread::Builder::new()
            .name("ppo-tutor-grade".into())
            .spawn(move || {
                for question in inbox {
                    let answer = match catch_unwind(AssertUnwindSafe(|| function(&question))) {
                        Ok(Ok(reply)) => Answer::Value(reply),
                        Ok(Err(e)) => Answer::Error(e),
                        Err(payload) => Answer::Panicked(panic_message(payload.as_ref())),
                    };
                    if outbox.send(answer).is_err() {
                        return;
                    }
                }
            })?;
        Ok(Self {
            requests: Some(requests),
            replies,
            stopped: false,
        })
    }

    fn stop(&mut self, answer: Answer<R>) -> Answer<R> {
        self.stopped = true;
        self.requests = None;
        answer
    }
}

impl<Q: Clone + Send + 'static, R: Send + 'static> Learner<Q, R> for InProcess<Q, R> {
    fn ask(&mut self, question: &Q, deadline: Instant, limit: Duration) -> Answer<R> {
        if self.stopped {
            return Answer::NotRun;
        }
        let stopped = || Answer::Crashed(Text::new("the grading thread stopped", "评分线程停止了"));
        let sent = self
            .requests
            .as_ref()
            .is_some_and(|r| r.send(question.clone()).is_ok());
        if !sent {
            return self.stop(stopped());
        }
        match self
            .replies
            .recv_timeout(deadline.saturating_duration_since(Instant::now()))
        {
            Ok(answer) => answer,
            Err(RecvTimeoutError::Timeout) => self.stop(Answer::TimedOut(seconds(limit))),
            Err(RecvTimeoutError::Disconnected) => self.stop(stopped()),
        }
    }

    fn is_stopped(&self) -> bool {
        self.stopped
    }
}

/// Serialises in-place gradings: each silences the panic hook (a panic belongs in the
/// report, not on stderr) and must restore the one it found.
static QUIET: Mutex<()> = Mutex::new(());

type PanicHook = dyn Fn(&std::panic::PanicHookInfo<'_>) + Sync + Send + 'static;

/// The panic hook, silenced while an in-place grading runs; dropping this restores the
/// hook it found.
pub struct Quiet {
    _lock: Result<MutexGuard<'static, ()>, PoisonError<MutexGuard<'static, ()>>>,
    previous: Option<Box<PanicHook>>,
}

impl Quiet {
    /// Silences the panic hook until dropped.
    #[must_use]
    pub fn start() -> Self {
        let lock = QUIET.lock();
        let previous = std::panic::take_hook();
        std::panic::set_hook(Box::new(|_| {}));
        Self {
            _lock: lock,
            previous: Some(previous),
        }
    }
}

impl Drop for Quiet {
    fn drop(&mut self) {
        if let Some(previous) = self.previous.take()
            && !std::thread::panicking()
        {
            std::panic::set_hook(previous);
        }
    }
}
