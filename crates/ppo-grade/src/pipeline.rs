//! The one grading pipeline, over any [`Spec`].
//!
//! ```text
//! source ──build──▶ program ─┐                       ┌─▶ judge ──▶ report lines
//!                            ├─ask every question ──▶│
//! function (notebook cell) ──┘   (Answer per case)   └─▶ follow-up checks (training)
//! ```
//!
//! Grading options go down (time limit, cache), answers and reports come up. A learner's
//! file is built by its backend ([`super::build`]) and asked over a pipe; a function in
//! this process is asked on a worker thread ([`super::learner`]); both give the same
//! [`Answer`]s to the same [`Judge`].

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::time::{Duration, Instant};

use super::build::{self, Build, Program};
use super::error::{GradeError, GradeOptions};
use super::judge::Judge;
use super::learner::{Answer, InProcess, Learner, LearnerProcess, Quiet, panic_message};
use super::prose::Hints;
use super::report::{CheckReport, CheckStatus, Report};
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
    }
}

/// A report for a grading that could not run at all (the grader's own failure).
pub(crate) fn not_graded(name: &str, display: Text, why: Text) -> Report {
    Report {
        compile_error: Some((why, String::new())),
        ..empty_report(name, display)
    }
}

/// Grades `source` (a learner's file, shown as `display`) as `spec`.
///
/// # Errors
/// The backend cannot build (no compiler, unwritable cache), or the grader's own cases
/// cannot be made.
pub fn grade_source<S: Spec>(
    spec: &S,
    source: &str,
    display: &str,
    opts: &GradeOptions,
) -> Result<Report, GradeError> {
    let meta = spec.meta();
    let prose = Hints::of(meta.name)?;
    let cases = spec.cases()?;
    let mut report = empty_report(meta.name, Text::same(display));
    let program: Program = match build::build(
        meta.name,
        meta.backend,
        &spec.program(),
        &spec.signature(),
        source,
        display,
        &opts.cache_dir,
    )? {
        Build::Ready(program) => program,
        Build::Failed { summary, compiler } => {
            report.compile_error = Some((summary, compiler));
            let not_run = |name: Text, cases| CheckReport {
                name,
                cases,
                status: CheckStatus::NotRun(Text::new(
                    "the file does not compile",
                    "文件编译不通过",
                )),
            };
            report.checks = cases
                .checks
                .iter()
                .map(|c| not_run(c.name.clone(), c.cases.len()))
                .chain(spec.follow_up_names().into_iter().map(|n| not_run(n, 1)))
                .collect();
            return Ok(report);
        }
    };
    let mut session = LearnerProcess::start(&program, display)?;
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
    let answers: Vec<Answer<S::Reply>> = cases
        .all
        .iter()
        .map(|case| {
            let deadline = if spec.limit_per_question() {
                Instant::now() + limit
            } else {
                start + limit
            };
            learner.ask(spec.question(case), deadline, limit)
        })
        .collect();
    let judge = Judge::new(spec, prose, &cases.all, answers);
    for check in &cases.checks {
        report.checks.push(judge.report_line(check));
    }
    report.mistake = judge.any_diagnosis().map(str::to_string);
    let follow_up = spec.follow_up(learner, limit, judge.any_diagnosis(), prose);
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
}
