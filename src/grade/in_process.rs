//! Grading a function that lives in the running program: a notebook cell.
//!
//! The notebooks cannot hand the grader a file (a cell's text is not visible to the code it
//! defines), so the learner passes the function itself: `grade::in_process::td_target(td_target)`.
//! It runs on exactly the cases of `ppo-tutor grade`, is compared with the same reference
//! and tolerance, and a failure gets the same diagnosis and hint; only the compile step is
//! the notebook's own. Each case runs on a worker thread: a panic is caught and reported
//! with its message, and a function that has not answered within the time limit is
//! reported as never returning (the thread is left behind; in a notebook, restart the
//! kernel to stop it).
//!
//! The candle exercise is graded the same way: `grade::in_process::ppo_losses(ppo_losses)`
//! runs the checks of `ppo-tutor grade ppo_losses` (losses and gradients, then CartPole
//! trained with the function) on the function itself instead of a program built from a
//! file, with a time limit on each call.
//!
//! ```
//! use ppo_tutor::grade::in_process;
//!
//! fn critic_loss(values: &[f32], td_target: &[f32]) -> f32 {
//!     let n = values.len() as f32;
//!     values.iter().zip(td_target).map(|(v, y)| (v - y) * (v - y)).sum::<f32>() / n
//! }
//! let report = in_process::critic_loss(critic_loss);
//! assert!(report.passed(), "{}", report.render());
//! ```

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::sync::mpsc;
use std::sync::{Arc, Mutex, MutexGuard, PoisonError};
use std::time::{Duration, Instant};

use super::catalog::{Args, CheckCases, Spec};
use super::ppo_losses::protocol::panic_message;
use super::ppo_losses::{
    self,
    project::Answer as LossesAnswer,
    protocol::{self, Inputs, LossesFn},
};
use super::value::Output;
use super::{Answer, Report, judge, spec};

/// The name a report gives to the graded code.
pub const DISPLAY: &str = "notebook cell";

/// How long the learner's function may take on all cases together.
pub const TIME_LIMIT: Duration = Duration::from_secs(10);

/// A learner's function, adapted to take a case's arguments and return its result.
pub type Learner = Arc<dyn Fn(Args<'_>) -> Output + Send + Sync>;

/// Serialises gradings: each silences the panic hook (a panic belongs in the report, not
/// on stderr) and must restore the one it found.
static QUIET: Mutex<()> = Mutex::new(());

/// The panic hook, silenced while a grading runs (a panic belongs in the report, not on
/// stderr); dropping this restores the hook it found.
struct Quiet {
    _lock: Result<MutexGuard<'static, ()>, PoisonError<MutexGuard<'static, ()>>>,
    previous: Option<Box<PanicHook>>,
}

type PanicHook = dyn Fn(&std::panic::PanicHookInfo<'_>) + Sync + Send + 'static;

impl Quiet {
    fn start() -> Self {
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

/// Runs `learner` on every case of `checks`, in order, on a worker thread.
fn answers(learner: Learner, checks: &[CheckCases], limit: Duration) -> Vec<Answer> {
    let cases: Vec<Vec<super::value::Arg>> = checks
        .iter()
        .flat_map(|c| c.cases.iter().cloned())
        .collect();
    let total = cases.len();
    let (tx, rx) = mpsc::channel::<Answer>();
    let quiet = Quiet::start();
    let worker = std::thread::Builder::new()
        .name("ppo-tutor-grade".into())
        .spawn(move || {
            for case in &cases {
                let answer = match catch_unwind(AssertUnwindSafe(|| learner(Args(case)))) {
                    Ok(out) => Answer::Value(out),
                    Err(payload) => Answer::Panicked(panic_message(payload.as_ref())),
                };
                if tx.send(answer).is_err() {
                    return;
                }
            }
        });
    let mut out = Vec::with_capacity(total);
    match worker {
        Ok(_) => {
            let deadline = Instant::now() + limit;
            while out.len() < total {
                let left = deadline.saturating_duration_since(Instant::now());
                match rx.recv_timeout(left) {
                    Ok(answer) => out.push(answer),
                    Err(mpsc::RecvTimeoutError::Timeout) => {
                        out.push(Answer::TimedOut(limit.as_secs().max(1)));
                        break;
                    }
                    Err(mpsc::RecvTimeoutError::Disconnected) => {
                        out.push(Answer::Crashed("the grading thread stopped".into()));
                        break;
                    }
                }
            }
        }
        Err(e) => out.push(Answer::Crashed(format!("cannot start a thread: {e}"))),
    }
    drop(quiet);
    out.resize(total, Answer::NotRun);
    out
}

/// Grades `learner` as exercise `spec`, within `limit`.
#[must_use]
pub fn grade_with(spec: &Spec, learner: Learner, limit: Duration) -> Report {
    let checks = (spec.checks)();
    let answers = answers(learner, &checks, limit);
    let (mistake, lines) = judge(spec, &checks, &answers);
    Report {
        exercise: spec.name.to_string(),
        file: DISPLAY.to_string(),
        compile_error: None,
        checks: lines,
        mistake,
    }
}

fn by_name(name: &str, learner: Learner) -> Report {
    match spec(name) {
        Ok(spec) => grade_with(spec, learner, TIME_LIMIT),
        // The names below are the catalogue's own; this is unreachable in a built crate.
        Err(e) => Report {
            exercise: name.to_string(),
            file: DISPLAY.to_string(),
            compile_error: Some((e.to_string(), String::new())),
            checks: Vec::new(),
            mistake: None,
        },
    }
}

/// Grades a `sample_action` (lesson 6).
pub fn sample_action(f: fn(&[f32], f32) -> usize) -> Report {
    by_name(
        "sample_action",
        Arc::new(move |a: Args<'_>| Output::Usize(f(a.f32s(0), a.f32(1)))),
    )
}

/// The signature of `td_target`.
pub type TdTarget = fn(&[f32], &[f32], &[bool], f32) -> Vec<f32>;

/// Grades a `td_target` (lesson 7).
pub fn td_target(f: TdTarget) -> Report {
    by_name(
        "td_target",
        Arc::new(move |a: Args<'_>| Output::F32s(f(a.f32s(0), a.f32s(1), a.bools(2), a.f32(3)))),
    )
}

/// Grades a `td_delta` (lesson 7).
pub fn td_delta(f: fn(&[f32], &[f32]) -> Vec<f32>) -> Report {
    by_name(
        "td_delta",
        Arc::new(move |a: Args<'_>| Output::F32s(f(a.f32s(0), a.f32s(1)))),
    )
}

/// Grades a `compute_advantage` (lesson 8).
pub fn compute_advantage(f: fn(f32, f32, &[f32]) -> Vec<f32>) -> Report {
    by_name(
        "compute_advantage",
        Arc::new(move |a: Args<'_>| Output::F32s(f(a.f32(0), a.f32(1), a.f32s(2)))),
    )
}

/// Grades a `log_prob_of_actions` (lesson 9).
pub fn log_prob_of_actions(f: fn(&[[f32; 2]], &[usize]) -> Vec<f32>) -> Report {
    by_name(
        "log_prob_of_actions",
        Arc::new(move |a: Args<'_>| Output::F32s(f(a.pairs(0), a.usizes(1)))),
    )
}

/// Grades a `ratio` (lesson 9).
pub fn ratio(f: fn(&[f32], &[f32]) -> Vec<f32>) -> Report {
    by_name(
        "ratio",
        Arc::new(move |a: Args<'_>| Output::F32s(f(a.f32s(0), a.f32s(1)))),
    )
}

/// Grades an `actor_loss` (lesson 10).
pub fn actor_loss(f: fn(&[f32], &[f32], f32) -> f32) -> Report {
    by_name(
        "actor_loss",
        Arc::new(move |a: Args<'_>| Output::F32(f(a.f32s(0), a.f32s(1), a.f32(2)))),
    )
}

/// Grades a `critic_loss` (lesson 11).
pub fn critic_loss(f: fn(&[f32], &[f32]) -> f32) -> Report {
    by_name(
        "critic_loss",
        Arc::new(move |a: Args<'_>| Output::F32(f(a.f32s(0), a.f32s(1)))),
    )
}

/// Grades a `moving_average` (lesson 12).
pub fn moving_average(f: fn(&[f64], usize) -> Vec<f64>) -> Report {
    by_name(
        "moving_average",
        Arc::new(move |a: Args<'_>| Output::F64s(f(a.f64s(0), a.usize(1)))),
    )
}

/// A candle losses function running on a worker thread of this process: the in-place
/// counterpart of the learner's program ([`Session`](super::ppo_losses::project::Session)).
/// A panic is caught per request; a request not answered within its limit stops the
/// worker (the thread is left behind).
struct LossesWorker {
    requests: Option<mpsc::Sender<Inputs>>,
    replies: mpsc::Receiver<LossesAnswer>,
    stopped: bool,
}

impl LossesWorker {
    fn start(f: LossesFn) -> std::io::Result<Self> {
        let (requests, inbox) = mpsc::channel::<Inputs>();
        let (outbox, replies) = mpsc::channel();
        std::thread::Builder::new()
            .name("ppo-tutor-grade".into())
            .spawn(move || {
                for inputs in inbox {
                    let run = AssertUnwindSafe(|| protocol::evaluate(f, &inputs));
                    let answer = match catch_unwind(run) {
                        Ok(Ok(reply)) => LossesAnswer::Reply(reply),
                        Ok(Err(e)) => LossesAnswer::Error(e),
                        Err(payload) => LossesAnswer::Panicked(panic_message(payload.as_ref())),
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

    fn stop(&mut self, answer: LossesAnswer) -> LossesAnswer {
        self.stopped = true;
        self.requests = None;
        answer
    }
}

impl ppo_losses::Learner for LossesWorker {
    fn ask(&mut self, inputs: &Inputs, limit: Duration) -> LossesAnswer {
        if self.stopped {
            return LossesAnswer::NotRun;
        }
        let stopped = || LossesAnswer::Crashed("the grading thread stopped".into());
        let sent = self
            .requests
            .as_ref()
            .is_some_and(|r| r.send(inputs.clone()).is_ok());
        if !sent {
            return self.stop(stopped());
        }
        match self.replies.recv_timeout(limit) {
            Ok(answer) => answer,
            Err(mpsc::RecvTimeoutError::Timeout) => {
                self.stop(LossesAnswer::TimedOut(limit.as_secs().max(1)))
            }
            Err(mpsc::RecvTimeoutError::Disconnected) => self.stop(stopped()),
        }
    }

    fn is_stopped(&self) -> bool {
        self.stopped
    }
}

/// A report for a grading that could not run at all (the grader's own failure).
fn not_graded(name: &str, why: String) -> Report {
    Report {
        exercise: name.to_string(),
        file: DISPLAY.to_string(),
        compile_error: Some((why, String::new())),
        checks: Vec::new(),
        mistake: None,
    }
}

/// Grades a `ppo_losses` on candle tensors (lesson 11), within `limit` per call: the
/// checks of `ppo-tutor grade ppo_losses` (losses and gradients on every case, then
/// CartPole trained with the function), same diagnosis, hints and messages.
#[must_use]
pub fn ppo_losses_with(f: LossesFn, limit: Duration) -> Report {
    let _quiet = Quiet::start();
    let graded = catch_unwind(AssertUnwindSafe(|| {
        let mut worker =
            LossesWorker::start(f).map_err(|e| format!("cannot start a thread: {e}"))?;
        ppo_losses::grade_learner(&mut worker, DISPLAY, limit).map_err(|e| e.to_string())
    }));
    match graded {
        Ok(Ok(report)) => report,
        Ok(Err(why)) => not_graded(ppo_losses::NAME, why),
        Err(payload) => not_graded(
            ppo_losses::NAME,
            format!("the grader failed: {}", panic_message(payload.as_ref())),
        ),
    }
}

/// Grades a `ppo_losses` on candle tensors (lesson 11): [`ppo_losses_with`] with
/// [`TIME_LIMIT`] per call.
///
/// ```no_run
/// use ppo_tutor::candle_core::{Result, Tensor};
/// # fn ppo_losses(
/// #     probs: &Tensor, actions: &Tensor, old_log_probs: &Tensor, advantage: &Tensor,
/// #     values: &Tensor, td_target: &Tensor, eps: f64,
/// # ) -> Result<(Tensor, Tensor)> { todo!() }
/// let report = ppo_tutor::grade::in_process::ppo_losses(ppo_losses);
/// println!("{}", report.render());
/// ```
#[must_use]
pub fn ppo_losses(f: LossesFn) -> Report {
    ppo_losses_with(f, TIME_LIMIT)
}
