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
use super::report::Printed;
use crate::i18n::Text;
use crate::text;

/// The name a report gives to code graded in place (a notebook cell).
pub const IN_PLACE: Text = Text::new("notebook cell", "笔记本单元格");

/// How long a function graded in place may take: on all cases together (plain
/// exercises), or on each call (the candle exercise).
pub const IN_PLACE_LIMIT: Duration = Duration::from_secs(10);

/// A panic's message (`panic!("...")` with or without arguments), or a placeholder: the
/// words a learner's program uses too ([`crate::harness::panic_text`]).
#[must_use]
pub fn panic_message(payload: &(dyn std::any::Any + Send)) -> String {
    crate::harness::panic_text(payload)
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
    /// What the learner's code printed since the last call (a program's stdout and stderr;
    /// nothing for a function in this process, whose prints go where this process's do).
    fn take_printed(&mut self) -> Printed {
        Printed::default()
    }
}

fn seconds(limit: Duration) -> u64 {
    limit.as_secs().max(1)
}

/// The longest line read from a learner program: a longer line (printed without a
/// newline, say) is cut there, so a flood of output cannot fill the grader's memory.
const LINE_LIMIT: u64 = 8 << 20;

/// How much of a line the learner printed is kept for the report (see [`Printed`]).
const PRINTED_KEPT: usize = 1024;

/// One of the learner program's two output streams.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Stream {
    Out,
    Err,
}

/// What a reader thread saw on one stream.
#[derive(Debug)]
enum Seen {
    /// A line the learner printed.
    Printed(Stream, String),
    /// A harness line: the text after the marker.
    Marked(Stream, String),
    /// The stream closed (the program ended).
    Closed(Stream),
}

/// A running learner program: one question per line on stdin; on stdout, between what the
/// learner's code prints, one marked answer per question (`ok <reply>`, `error <message>`
/// or `panic <message>`), and on stderr a marked end of each question's output (see
/// [`crate::harness`]). What the learner printed while answering is kept per question
/// ([`LearnerProcess::take_printed`]).
///
/// The program runs in a process group of its own (on Unix): stopping it ends the whole
/// group, so processes the learner's code started do not outlive the grading.
#[derive(Debug)]
pub struct LearnerProcess {
    child: Child,
    stdin: Option<ChildStdin>,
    seen: Receiver<Seen>,
    program: Program,
    display: String,
    stopped: bool,
    /// What was printed on stdout and on stderr since the last [`Self::take_printed`].
    printed_out: Printed,
    printed_err: Printed,
    /// The last line printed to stderr since its last marked end (a crash's message).
    last_err: Option<String>,
    /// Marked ends of stderr output, and answers, seen so far.
    ends: usize,
    answers: usize,
    err_open: bool,
}

impl LearnerProcess {
    /// Starts `program`; `display` replaces its name for the learner's file in messages.
    ///
    /// # Errors
    /// [`GradeError::Run`] if it cannot be started.
    pub fn start(program: &Program, display: &str) -> Result<Self, GradeError> {
        use std::hash::BuildHasher as _;
        let marker = format!(
            "@@ppo-tutor-grade-{:016x}@@",
            std::hash::RandomState::new().hash_one(std::process::id())
        );
        let mut command = Command::new(&program.binary);
        command
            .env("RAYON_NUM_THREADS", "1")
            .env("RUST_BACKTRACE", "0")
            .env(crate::harness::MARKER_VAR, &marker)
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped());
        #[cfg(unix)]
        {
            use std::os::unix::process::CommandExt as _;
            command.process_group(0);
        }
        let mut child = command.spawn().map_err(|e| GradeError::Run {
            binary: program.binary.clone(),
            reason: crate::error::reason(&e),
        })?;
        let (tx, seen) = mpsc::channel();
        if let Some(stdout) = child.stdout.take() {
            let (tx, marker) = (tx.clone(), marker.clone());
            std::thread::spawn(move || read_stream(stdout, Stream::Out, &marker, &tx));
        }
        if let Some(stderr) = child.stderr.take() {
            std::thread::spawn(move || read_stream(stderr, Stream::Err, &marker, &tx));
        }
        Ok(Self {
            stdin: child.stdin.take(),
            child,
            seen,
            program: program.clone(),
            display: display.to_string(),
            stopped: false,
            printed_out: Printed::default(),
            printed_err: Printed::default(),
            last_err: None,
            ends: 0,
            answers: 0,
            err_open: true,
        })
    }

    /// Whether the program has stopped (timed out, crashed).
    #[must_use]
    pub fn is_stopped(&self) -> bool {
        self.stopped
    }

    /// What the learner's code printed since the last call, a few lines of it: stdout's
    /// lines, then stderr's (two pipes do not keep the order between them).
    pub fn take_printed(&mut self) -> Printed {
        let mut printed = std::mem::take(&mut self.printed_out);
        printed.append(std::mem::take(&mut self.printed_err));
        printed
    }

    /// Takes in what a reader thread saw.
    fn note(&mut self, seen: Seen) -> Option<String> {
        match seen {
            Seen::Printed(stream, line) => {
                // `dbg!` and panics name the learner's file as the program knows it.
                let line = self.program.rename(&line, &self.display);
                match stream {
                    Stream::Out => self.printed_out.push(&line),
                    Stream::Err => self.printed_err.push(&line),
                }
                if stream == Stream::Err && !line.is_empty() {
                    self.last_err = Some(line);
                }
            }
            Seen::Marked(Stream::Err, _) => {
                self.ends += 1;
                self.last_err = None;
            }
            Seen::Marked(Stream::Out, answer) => {
                self.answers += 1;
                return Some(answer);
            }
            Seen::Closed(Stream::Err) => self.err_open = false,
            Seen::Closed(Stream::Out) => {}
        }
        None
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
        if !sent {
            return self.crashed();
        }
        let mut answer = None;
        loop {
            // The answer, and the end of what was printed on stderr before it (the harness
            // writes that first, so it is in the pipe already).
            if answer.is_some() && (self.ends >= self.answers || !self.err_open) {
                break;
            }
            let wait = deadline.saturating_duration_since(Instant::now());
            match self.seen.recv_timeout(wait) {
                Ok(Seen::Closed(Stream::Out)) if answer.is_none() => return self.crashed(),
                Ok(seen) => {
                    if let Some(a) = self.note(seen) {
                        answer = Some(a);
                    }
                }
                Err(_) if answer.is_some() => break,
                Err(RecvTimeoutError::Timeout) => {
                    self.stop();
                    return Answer::TimedOut(seconds(limit));
                }
                Err(RecvTimeoutError::Disconnected) => return self.crashed(),
            }
        }
        match answer {
            Some(a) => self.parse(&a),
            None => self.crashed(),
        }
    }

    /// The program died before answering: how it ended, and the last line it printed on
    /// stderr (a stack overflow's message, say).
    fn crashed(&mut self) -> Answer<String> {
        let status = self.stop();
        // The group is ended: the rest of stderr comes at once.
        let until = Instant::now() + Duration::from_secs(2);
        while self.err_open {
            match self
                .seen
                .recv_timeout(until.saturating_duration_since(Instant::now()))
            {
                Ok(seen) => {
                    self.note(seen);
                }
                Err(_) => break,
            }
        }
        let last = self.last_err.as_deref().map(str::trim).unwrap_or_default();
        let last = self.program.rename(last, &self.display);
        let last = if last.is_empty() {
            Text::new("no message", "没有消息")
        } else {
            Text::same(last)
        };
        Answer::Crashed(text!(
            "the program stopped ({status}): {last}",
            "程序停止了（{status}）：{last}",
            status = status.get(),
            last = last.get()
        ))
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
            Answer::Crashed(text!("unexpected answer '{line}'", "意外的回答 '{line}'"))
        }
    }

    /// Ends the program and every process it started (if still running) and says how the
    /// program ended.
    fn stop(&mut self) -> Text {
        self.stopped = true;
        self.stdin = None;
        // Before the program is reaped, so its group's id cannot have been reused.
        end_group(&self.child);
        let _ = self.child.kill();
        match self.child.wait() {
            Ok(status) => exit_status(status),
            Err(e) => text!("its end unknown: {e}", "无法得知它如何结束：{e}"),
        }
    }
}

/// Ends the process group the learner's program leads (it and whatever it started).
#[cfg(unix)]
fn end_group(child: &Child) {
    use nix::sys::signal::{Signal, killpg};
    use nix::unistd::Pid;
    if let Ok(pid) = i32::try_from(child.id()) {
        let _ = killpg(Pid::from_raw(pid), Signal::SIGKILL);
    }
}

/// Elsewhere the program alone is ended.
#[cfg(not(unix))]
fn end_group(_child: &Child) {}

/// Reads `stream` line by line until it closes, telling marked lines (the harness's) from
/// what the learner printed, and drops the one empty line the harness's newline before
/// each marker makes after a complete line.
fn read_stream(reader: impl Read, stream: Stream, marker: &str, tx: &mpsc::Sender<Seen>) {
    let mut reader = BufReader::new(reader);
    let mut buf = Vec::new();
    let mut empty_pending = false;
    loop {
        buf.clear();
        match (&mut reader).take(LINE_LIMIT).read_until(b'\n', &mut buf) {
            Ok(0) | Err(_) => break,
            Ok(_) => {}
        }
        if buf.last() == Some(&b'\n') {
            buf.pop();
            if buf.last() == Some(&b'\r') {
                buf.pop();
            }
        } else if buf.len() as u64 >= LINE_LIMIT {
            let _ = reader.skip_until(b'\n');
        }
        let line = String::from_utf8_lossy(&buf);
        let seen = if let Some(rest) = line.strip_prefix(marker) {
            empty_pending = false;
            Seen::Marked(stream, rest.trim_start().to_string())
        } else {
            if std::mem::replace(&mut empty_pending, line.is_empty())
                && tx.send(Seen::Printed(stream, String::new())).is_err()
            {
                return;
            }
            if line.is_empty() {
                continue;
            }
            let kept = line
                .char_indices()
                .nth(PRINTED_KEPT)
                .map_or(line.len(), |(i, _)| i);
            Seen::Printed(stream, line[..kept].to_string())
        };
        if tx.send(seen).is_err() {
            return;
        }
    }
    if empty_pending {
        let _ = tx.send(Seen::Printed(stream, String::new()));
    }
    let _ = tx.send(Seen::Closed(stream));
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
    /// Ends the program and whatever it started, answered or not.
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
