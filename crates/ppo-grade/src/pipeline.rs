//! The one grading pipeline, over any [`Spec`].
//!
//! ```text
//! source ──build──▶ program ─┐                       ┌─▶ judge ──▶ report lines
//!                            ├─ask every question ──▶│
//! function (notebook cell) ──┘   (Answer per case)   └─▶ follow-up checks (training)
//! ```
//!
//! Grading options go down (time limit, cache), answers, progress and reports come up. A
//! learner's file whose function is still the starter's `todo!()` is reported as not
//! started before anything is built ([`super::not_started`]); any other is built by its
//! backend ([`super::build`]) and asked over a pipe; a function in
//! this process is asked on a worker thread ([`super::learner`]); both give the same
//! [`Answer`]s to the same [`Judge`].

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::time::{Duration, Instant};

use super::build::{self, Build};
use super::error::{GradeError, GradeOptions};
use super::judge::Judge;
use super::learner::{Answer, InProcess, Learner, LearnerProcess, Quiet, panic_message};
use super::not_started::todo_line;
use super::progress::GradeProgress;
use super::prose::Hints;
use super::report::{CheckReport, CheckStatus, Printed, Report};
use super::spec::{Cases, Spec};
use crate::i18n::Text;
use crate::text;

fn empty_report(name: &str, display: Text) -> Report {
    Report {
        exercise: name.to_string(),
        file: display,
        compile_error: None,
        checks: Vec::new(),
        mistake: None,
        not_started: None,
    }
}

/// A line per check (the follow-up ones too), none of them run, for `why`.
fn not_run<S: Spec>(spec: &S, cases: &Cases<S::Case, S::Kind>, why: &Text) -> Vec<CheckReport> {
    let line = |name: Text, cases| CheckReport {
        name,
        cases,
        status: CheckStatus::NotRun(why.clone()),
        printed: Printed::default(),
    };
    cases
        .checks
        .iter()
        .map(|c| line(c.name.clone(), c.cases.len()))
        .chain(spec.follow_up_names().into_iter().map(|n| line(n, 1)))
        .collect()
}

/// A report for a grading that could not run at all (the grader's own failure).
pub(crate) fn not_graded(name: &str, display: Text, why: Text) -> Report {
    Report {
        compile_error: Some((why, String::new())),
        ..empty_report(name, display)
    }
}

/// Grades `source` (a learner's file, shown as `display`) as `spec`, telling `progress`
/// each step. A function still the starter's `todo!()` is reported as not started
/// without a build.
///
/// # Errors
/// The backend cannot build (no compiler, unwritable cache), or the grader's own cases
/// cannot be made.
pub fn grade_source<S: Spec>(
    spec: &S,
    source: &str,
    display: &str,
    opts: &GradeOptions,
    progress: &mut dyn FnMut(&GradeProgress),
) -> Result<Report, GradeError> {
    let meta = spec.meta();
    let prose = Hints::of(meta.name)?;
    let cases = spec.cases()?;
    let mut report = empty_report(meta.name, Text::same(display));
    if let Some(line) = todo_line(source, meta.name) {
        report.not_started = Some(line);
        let why = Text::new("the function is still todo!()", "函数还是 todo!()");
        report.checks = not_run(spec, &cases, &why);
        return Ok(report);
    }
    let (program, signature) = (spec.program(), spec.signature());
    let request = build::Request {
        name: meta.name,
        backend: meta.backend,
        source: &program,
        signature: &signature,
        learner: source,
        display,
        cache: &opts.cache_dir,
    };
    let mut session = None;
    // A second try when another grading's pruning of the cache deleted the program
    // between its build and its start.
    for _ in 0..2 {
        let program = match build::build(&request, progress)? {
            Build::Ready(program) => program,
            Build::Failed { summary, compiler } => {
                report.compile_error = Some((summary, compiler));
                let why = Text::new("the file does not compile", "文件编译不通过");
                report.checks = not_run(spec, &cases, &why);
                return Ok(report);
            }
        };
        progress(&GradeProgress::Checking);
        match LearnerProcess::start(&program, display) {
            Ok(started) => {
                session = Some(started);
                break;
            }
            Err(GradeError::Run { .. }) if !program.binary.is_file() => {}
            Err(e) => return Err(e),
        }
    }
    let Some(mut session) = session else {
        return Err(GradeError::Cache {
            dir: opts.cache_dir.clone(),
            reason: Text::new(
                "the built program was deleted before it could run, twice",
                "编译好的程序两次都在运行前被删除了",
            ),
        });
    };
    let mut learner = Talk {
        spec,
        session: &mut session,
    };
    Ok(judged(
        spec,
        prose,
        report,
        &cases,
        &mut learner,
        opts.time_limit,
    ))
}

/// Grades `function`, running in this process (a notebook cell), as `spec`: the same
/// cases, judge, hints and messages as a file, each question asked on a worker thread.
#[must_use]
pub fn grade_in_place<S: Spec>(
    spec: &S,
    function: impl Fn(&S::Question) -> Result<S::Reply, String> + Send + 'static,
    display: Text,
    limit: Duration,
) -> Report {
    let name = spec.meta().name;
    let _quiet = Quiet::start();
    let graded = catch_unwind(AssertUnwindSafe(|| {
        let prose = Hints::of(name).map_err(|e| Text::in_each(|| e.to_string()))?;
        let cases = spec.cases().map_err(|e| Text::in_each(|| e.to_string()))?;
        let mut learner = InProcess::start(function)
            .map_err(|e| text!("cannot start a thread: {e}", "无法启动线程：{e}"))?;
        Ok::<_, Text>(judged(
            spec,
            prose,
            empty_report(name, display.clone()),
            &cases,
            &mut learner,
            limit,
        ))
    }));
    match graded {
        Ok(Ok(report)) => report,
        Ok(Err(why)) => not_graded(name, display, why),
        Err(payload) => not_graded(
            name,
            display,
            text!(
                "the grader failed: {}",
                "评分器自身出错：{}",
                panic_message(payload.as_ref())
            ),
        ),
    }
}

/// The mistakes of `spec` that agree with the reference on every case.
///
/// # Errors
/// The cases cannot be made.
pub fn uncaught_mistakes<S: Spec>(spec: &S) -> Result<Vec<&'static str>, GradeError> {
    let cases = spec.cases()?;
    let value = |case: &S::Case, reply: Option<S::Reply>| spec.value(case, reply?).ok();
    Ok(spec
        .mistakes()
        .into_iter()
        .enumerate()
        .filter(|&(index, (_, part))| {
            !cases.all.iter().any(|case| {
                let want = value(case, spec.reference(case));
                let got = value(case, spec.mistake(index, case));
                matches!((got, want), (Some(g), Some(w)) if !spec.agrees(&g, &w, part))
            })
        })
        .map(|(_, (id, _))| id)
        .collect())
}

/// The mistakes of `spec` that the judge does not name when a learner makes exactly that
/// mistake (answers every case as the mistake does), each with what it named instead
/// (`None`: only the exercise's own hint). A catalogue check: it must be empty, which also
/// means every pair of mistakes is told apart by some case.
///
/// # Errors
/// The cases or the prose cannot be made.
pub fn misdiagnosed_mistakes<S: Spec>(
    spec: &S,
) -> Result<Vec<(&'static str, Option<&'static str>)>, GradeError> {
    let prose = Hints::of(spec.meta().name)?;
    let cases = spec.cases()?;
    let mut wrong = Vec::new();
    for (index, (id, part)) in spec.mistakes().into_iter().enumerate() {
        let answers = cases
            .all
            .iter()
            .map(
                |case| match spec.mistake(index, case).or_else(|| spec.reference(case)) {
                    Some(reply) => Answer::Value(reply),
                    None => Answer::NotRun,
                },
            )
            .collect();
        let named = Judge::new(spec, prose, &cases.all, answers).diagnosis(part);
        if named != Some(id) {
            wrong.push((id, named));
        }
    }
    Ok(wrong)
}

/// `report` with a line per check and the follow-up checks, from `learner`'s answers.
fn judged<S: Spec>(
    spec: &S,
    prose: Hints,
    mut report: Report,
    cases: &Cases<S::Case, S::Kind>,
    learner: &mut dyn Learner<S::Question, S::Reply>,
    limit: Duration,
) -> Report {
    let start = Instant::now();
    let mut printed = Vec::with_capacity(cases.all.len());
    let answers: Vec<Answer<S::Reply>> = cases
        .all
        .iter()
        .map(|case| {
            let deadline = if spec.limit_per_question() {
                Instant::now() + limit
            } else {
                start + limit
            };
            let answer = learner.ask(spec.question(case), deadline, limit);
            printed.push(learner.take_printed());
            answer
        })
        .collect();
    let judge = Judge::new(spec, prose, &cases.all, answers);
    for check in &cases.checks {
        report.checks.push(judge.report_line(check, &printed));
    }
    report.mistake = judge.any_diagnosis().map(str::to_string);
    let mut follow_up =
        spec.follow_up(learner, limit, judge.any_diagnosis(), prose, &report.checks);
    // What was printed during the follow-up checks (a training run asks many questions)
    // goes with the last of them.
    let printed = learner.take_printed();
    if let Some(last) = follow_up.last_mut()
        && !matches!(last.status, CheckStatus::NotRun(_))
    {
        last.printed = printed;
    }
    report.checks.extend(follow_up);
    report
}

/// A learner's program, asked through `spec`'s encoding.
struct Talk<'a, S> {
    spec: &'a S,
    session: &'a mut LearnerProcess,
}

impl<S: Spec> Learner<S::Question, S::Reply> for Talk<'_, S> {
    fn ask(
        &mut self,
        question: &S::Question,
        deadline: Instant,
        limit: Duration,
    ) -> Answer<S::Reply> {
        let line = self.spec.encode(question);
        self.session
            .ask(&line, deadline, limit)
            .and_then(|payload| {
                self.spec.decode(question, &payload).ok_or_else(|| {
                    text!(
                        "unreadable result '{payload}'",
                        "无法读取的结果 '{payload}'"
                    )
                })
            })
    }

    fn is_stopped(&self) -> bool {
        self.session.is_stopped()
    }

    fn take_printed(&mut self) -> Printed {
        self.session.take_printed()
    }
}
