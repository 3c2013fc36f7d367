//! What grading found: one line per check, the first failure of each with its input,
//! expected and actual results, and a hint; rendered as plain text for the terminal.

use std::fmt::Write as _;

/// How a check failed.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Problem {
    /// A result differs from the reference's.
    Wrong,
    /// The function panicked (the message, with the learner's file and line).
    Panicked(String),
    /// The function did not return within the time limit (seconds).
    TimedOut(u64),
    /// The program died (stack overflow, `process::exit`, ...): what it printed.
    Crashed(String),
    /// The function returned an error (the candle exercise): its message.
    Error(String),
}

/// The first failing case of a check.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Failure {
    /// What went wrong.
    pub problem: Problem,
    /// The input: `(parameter, value)` pairs.
    pub input: Vec<(String, String)>,
    /// The reference's result.
    pub expected: String,
    /// The learner's result (empty when there is none).
    pub got: String,
    /// Where the results first differ, or what happened instead of a result.
    pub detail: String,
    /// The hint aimed at the likely mistake.
    pub hint: String,
}

/// The state of one check.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum CheckStatus {
    /// Every case agrees with the reference.
    Passed,
    /// A case failed.
    Failed(Box<Failure>),
    /// Not run, and why.
    NotRun(String),
}

/// One check: a named group of cases.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct CheckReport {
    /// What it tests.
    pub name: String,
    /// How many cases.
    pub cases: usize,
    /// The result.
    pub status: CheckStatus,
}

/// The whole grading of one exercise.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Report {
    /// The exercise (function) name.
    pub exercise: String,
    /// The file graded, as given.
    pub file: String,
    /// Set when the file did not build: a one-line summary and the compiler's output.
    pub compile_error: Option<(String, String)>,
    /// The checks, in order.
    pub checks: Vec<CheckReport>,
    /// The id of the known mistake the answer matches, if any.
    pub mistake: Option<String>,
}

impl Report {
    /// Whether every check passed (and the file built).
    #[must_use]
    pub fn passed(&self) -> bool {
        self.compile_error.is_none()
            && !self.checks.is_empty()
            && self.checks.iter().all(|c| c.status == CheckStatus::Passed)
    }

    /// `(checks passed, checks)`.
    #[must_use]
    pub fn score(&self) -> (usize, usize) {
        let passed = self
            .checks
            .iter()
            .filter(|c| c.status == CheckStatus::Passed)
            .count();
        (passed, self.checks.len())
    }

    /// The first failure, if any.
    #[must_use]
    pub fn first_failure(&self) -> Option<&Failure> {
        self.checks.iter().find_map(|c| match &c.status {
            CheckStatus::Failed(f) => Some(f.as_ref()),
            _ => None,
        })
    }

    /// One short phrase: `passed`, `does not compile`, `panicked`, `3/5 checks`, ...
    #[must_use]
    pub fn summary(&self) -> String {
        if self.compile_error.is_some() {
            return "does not compile".into();
        }
        if self.passed() {
            return "passed".into();
        }
        let (p, n) = self.score();
        match self.first_failure().map(|f| &f.problem) {
            Some(Problem::Panicked(m)) if m.contains("not yet implemented") => {
                "not started (todo!() left)".into()
            }
            Some(Problem::Panicked(_)) => format!("{p}/{n} checks, panicked"),
            Some(Problem::TimedOut(_)) => format!("{p}/{n} checks, never returned"),
            Some(Problem::Crashed(_)) => format!("{p}/{n} checks, crashed"),
            Some(Problem::Error(_)) => format!("{p}/{n} checks, returned an error"),
            _ => format!("{p}/{n} checks"),
        }
    }

    /// The report as text: a heading, one marked line per check, and the details of
    /// each failure.
    #[must_use]
    pub fn render(&self) -> String {
        let mut out = format!("{} ({})\n", self.exercise, self.file);
        if let Some((summary, compiler)) = &self.compile_error {
            let _ = writeln!(out, "  ✗ {summary}\n");
            for line in compiler.trim_end().lines() {
                let _ = writeln!(out, "    {line}");
            }
            return out;
        }
        for check in &self.checks {
            let cases = if check.cases == 1 {
                "1 case".to_string()
            } else {
                format!("{} cases", check.cases)
            };
            match &check.status {
                CheckStatus::Passed => {
                    let _ = writeln!(out, "  ✓ {} ({cases})", check.name);
                }
                CheckStatus::NotRun(why) => {
                    let _ = writeln!(out, "  · {} ({cases}): not run, {why}", check.name);
                }
                CheckStatus::Failed(f) => {
                    let _ = writeln!(out, "  ✗ {} ({cases})", check.name);
                    render_failure(&mut out, f);
                }
            }
        }
        let (p, n) = self.score();
        let verdict = if self.passed() { "passed" } else { "not yet" };
        let _ = writeln!(out, "  {p}/{n} checks passed: {verdict}");
        out
    }
}

fn render_failure(out: &mut String, f: &Failure) {
    let input: Vec<String> = f.input.iter().map(|(n, v)| format!("{n} = {v}")).collect();
    let _ = writeln!(out, "      input:    {}", input.join(", "));
    match &f.problem {
        Problem::Wrong => {
            let _ = writeln!(out, "      expected: {}", f.expected);
            let _ = writeln!(out, "      got:      {}", f.got);
        }
        Problem::Panicked(m) => {
            let _ = writeln!(out, "      panicked: {m}");
        }
        Problem::TimedOut(s) => {
            let _ = writeln!(out, "      never returned within {s} s (an endless loop?)");
        }
        Problem::Crashed(m) => {
            let _ = writeln!(out, "      crashed:  {m}");
        }
        Problem::Error(m) => {
            let _ = writeln!(out, "      error:    {m}");
        }
    }
    if !f.detail.is_empty() {
        let _ = writeln!(out, "      ({})", f.detail);
    }
    let _ = writeln!(out, "      hint:     {}", f.hint);
}
