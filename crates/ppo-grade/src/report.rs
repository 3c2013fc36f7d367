//! What grading found: one line per check, the first failure of each with its input,
//! expected and actual results, and a hint; rendered as plain text for the terminal.

use std::fmt::Write as _;

use crate::i18n::{Lang, Text, t};
use crate::tr;

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
    Crashed(Text),
    /// The function returned an error (the candle exercise): its message.
    Error(String),
}

/// The first failing case of a check.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Failure {
    /// What went wrong.
    pub problem: Problem,
    /// The input: `(parameter, value)` pairs.
    pub input: Vec<(Text, Text)>,
    /// The reference's result.
    pub expected: Text,
    /// The learner's result (empty when there is none).
    pub got: Text,
    /// Where the results first differ, or what happened instead of a result.
    pub detail: Text,
    /// The hint aimed at the likely mistake.
    pub hint: Text,
}

/// The state of one check.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum CheckStatus {
    /// Every case agrees with the reference.
    Passed,
    /// A case failed.
    Failed(Box<Failure>),
    /// Not run, and why.
    NotRun(Text),
}

/// One check: a named group of cases.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct CheckReport {
    /// What it tests, in both languages.
    pub name: Text,
    /// How many cases.
    pub cases: usize,
    /// The result.
    pub status: CheckStatus,
    /// What the learner's code printed on the case shown (the failing one, else the first
    /// that printed); empty when it printed nothing.
    pub printed: Printed,
}

/// How many lines of what the learner's code printed a report shows per check.
pub const PRINTED_LINES: usize = 5;

/// How many columns of each printed line a report shows.
pub const PRINTED_WIDTH: usize = 100;

/// What the learner's code printed (stdout and stderr, `println!`, `eprintln!`, `dbg!`)
/// while answering, kept short: the first [`PRINTED_LINES`] lines, each cut to
/// [`PRINTED_WIDTH`] columns, and how many more there were.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Printed {
    /// The first lines, as shown (control characters replaced, long lines cut with `…`).
    pub lines: Vec<String>,
    /// How many lines followed them.
    pub more: usize,
    /// How many other cases of the check printed too (their lines are not shown).
    pub other_cases: usize,
}

impl Printed {
    /// Adds a printed line (kept if there is room, else counted).
    pub fn push(&mut self, line: &str) {
        if self.lines.len() < PRINTED_LINES {
            self.lines.push(shown_line(line));
        } else {
            self.more += 1;
        }
    }

    /// Adds everything `other` holds after what this holds.
    pub fn append(&mut self, other: Self) {
        for line in other.lines {
            if self.lines.len() < PRINTED_LINES {
                self.lines.push(line);
            } else {
                self.more += 1;
            }
        }
        self.more += other.more;
        self.other_cases += other.other_cases;
    }

    /// Whether nothing was printed.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.lines.is_empty() && self.more == 0
    }
}

/// `line` as a report shows it: tabs as spaces, other control characters (a terminal's
/// escape sequences) as `�`, and cut to [`PRINTED_WIDTH`] columns with `…`.
fn shown_line(line: &str) -> String {
    let mut out = String::new();
    let mut columns = 0;
    for c in line.chars() {
        let c = match c {
            '\t' => ' ',
            c if c.is_control() => '\u{fffd}',
            c => c,
        };
        let w = crate::i18n::width(c.encode_utf8(&mut [0; 4]));
        if columns + w > PRINTED_WIDTH {
            out.push('…');
            return out;
        }
        columns += w;
        out.push(c);
    }
    out
}

/// The whole grading of one exercise.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Report {
    /// The exercise (function) name.
    pub exercise: String,
    /// The file graded, as given (or [`crate::in_process::DISPLAY`], a notebook cell).
    pub file: Text,
    /// Set when the file did not build: a one-line summary and the compiler's output.
    pub compile_error: Option<(Text, String)>,
    /// The checks, in order.
    pub checks: Vec<CheckReport>,
    /// The id of the known mistake the answer matches, if any.
    pub mistake: Option<String>,
    /// Set when the function is still the starter's `todo!()` (nothing was built or run):
    /// the line of that `todo!()` in the file.
    pub not_started: Option<usize>,
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

    /// One short phrase in the current language: `passed`, `does not compile`,
    /// `panicked`, `3/5 checks`, ...
    #[must_use]
    pub fn summary(&self) -> String {
        if self.not_started.is_some() {
            return t("not started (todo!() left)", "尚未开始（还留着 todo!()）").into();
        }
        if self.compile_error.is_some() {
            return t("does not compile", "编译不通过").into();
        }
        if self.passed() {
            return t("passed", "通过").into();
        }
        let (p, n) = self.score();
        match self.first_failure().map(|f| &f.problem) {
            Some(Problem::Panicked(m)) if m.contains("not yet implemented") => {
                t("not started (todo!() left)", "尚未开始（还留着 todo!()）").into()
            }
            Some(Problem::Panicked(_)) => {
                tr!(
                    "{p}/{n} checks, panicked",
                    "{p}/{n} 项检查，发生异常（panic）"
                )
            }
            Some(Problem::TimedOut(_)) => {
                tr!("{p}/{n} checks, never returned", "{p}/{n} 项检查，没有返回")
            }
            Some(Problem::Crashed(_)) => tr!("{p}/{n} checks, crashed", "{p}/{n} 项检查，程序崩溃"),
            Some(Problem::Error(_)) => {
                tr!(
                    "{p}/{n} checks, returned an error",
                    "{p}/{n} 项检查，返回了错误"
                )
            }
            _ => tr!("{p}/{n} checks", "{p}/{n} 项检查"),
        }
    }

    /// The report as text, in the current language: a heading, one marked line per
    /// check, and the details of each failure.
    #[must_use]
    pub fn render(&self) -> String {
        let mut out = format!("{}{}\n", self.exercise, paren(&self.file.to_string()));
        if let Some(line) = self.not_started {
            let name = &self.exercise;
            let _ = writeln!(
                out,
                "  ✗ {}",
                tr!(
                    "not started: the body of `{name}` is still the starter's todo!() (line {line}); \
                     nothing was built or run",
                    "尚未开始：`{name}` 的函数体还是初始代码里的 todo!()（第 {line} 行），所以没有编译，也没有运行"
                )
            );
            let _ = writeln!(out, "      {}{}", label(HINT), crate::hints::not_started());
        }
        if let Some((summary, compiler)) = &self.compile_error {
            let _ = writeln!(out, "  ✗ {summary}\n");
            for line in compiler.trim_end().lines() {
                let _ = writeln!(out, "    {line}");
            }
            return out;
        }
        for check in &self.checks {
            let cases = match (Lang::current(), check.cases) {
                (Lang::En, 1) => "1 case".to_string(),
                (Lang::En, n) => format!("{n} cases"),
                (Lang::Zh, n) => format!("{n} 个用例"),
            };
            let name = &check.name;
            match &check.status {
                CheckStatus::Passed => {
                    let _ = writeln!(out, "  ✓ {}", with_cases(name, &cases));
                    render_printed(&mut out, &check.printed);
                }
                CheckStatus::NotRun(why) => {
                    let _ = writeln!(
                        out,
                        "  · {}{}",
                        with_cases(name, &cases),
                        tr!(": not run, {why}", "：未运行，{why}")
                    );
                }
                CheckStatus::Failed(f) => {
                    let _ = writeln!(out, "  ✗ {}", with_cases(name, &cases));
                    render_failure(&mut out, f, &check.printed);
                }
            }
        }
        let (p, n) = self.score();
        let _ = if self.passed() {
            writeln!(
                out,
                "  {}",
                tr!(
                    "{p}/{n} checks passed: passed",
                    "{p}/{n} 项检查通过：全部通过"
                )
            )
        } else {
            writeln!(
                out,
                "  {}",
                tr!(
                    "{p}/{n} checks passed: not yet",
                    "{p}/{n} 项检查通过：尚未通过"
                )
            )
        };
        out
    }
}

/// ` (text)` in English, `（text）` in Chinese (full-width, no space before).
fn paren(text: &str) -> String {
    match Lang::current() {
        Lang::En => format!(" ({text})"),
        Lang::Zh => format!("（{text}）"),
    }
}

/// A check's name with its count of cases: `name (3 cases)`, `名称（3 个用例）`. A Chinese
/// name that already ends in parentheses takes the count inside them (`名称（说明；3 个用例）`),
/// never two pairs side by side.
fn with_cases(name: &Text, cases: &str) -> String {
    let name = name.to_string();
    match (Lang::current(), name.strip_suffix('）')) {
        (Lang::Zh, Some(open)) => format!("{open}；{cases}）"),
        _ => format!("{name}{}", paren(cases)),
    }
}

/// The labels of the failure details, `(English, Chinese)`, each padded to 10 columns (a
/// Chinese character and the full-width colon are two columns each: `输入：` is 6). The
/// grader is built without the app's text-width crate (notebooks), so the padding is
/// written out; a test measures it.
const INPUT: (&str, &str) = ("input:    ", "输入：    ");
const EXPECTED: (&str, &str) = ("expected: ", "应为：    ");
const GOT: (&str, &str) = ("got:      ", "实际：    ");
const PANICKED: (&str, &str) = ("panicked: ", "异常：    ");
const CRASHED: (&str, &str) = ("crashed:  ", "崩溃：    ");
const ERROR: (&str, &str) = ("error:    ", "错误：    ");
const HINT: (&str, &str) = ("hint:     ", "提示：    ");
const PRINTED: (&str, &str) = ("printed:  ", "输出：    ");
#[cfg(test)]
const LABELS: [(&str, &str); 8] = [
    INPUT, EXPECTED, GOT, PANICKED, CRASHED, ERROR, PRINTED, HINT,
];

fn label((en, zh): (&'static str, &'static str)) -> &'static str {
    t(en, zh)
}

/// A panic's message as the learner's program printed it (Rust's own words), with the
/// place the harness adds (` (at file:line:column)`) in the current language.
fn panic_line(message: &str) -> String {
    match message.rsplit_once(" (at ") {
        Some((said, place)) if place.ends_with(')') => {
            let place = &place[..place.len() - 1];
            tr!("{said} (at {place})", "{said}（位于 {place}）")
        }
        _ => message.to_string(),
    }
}

/// What the learner's code printed, under a check's line: a few lines beside the label,
/// and how much more there was.
fn render_printed(out: &mut String, printed: &Printed) {
    if printed.is_empty() {
        return;
    }
    let indent = " ".repeat(6 + 10);
    for (i, line) in printed.lines.iter().enumerate() {
        let line = if i == 0 {
            format!("      {}{line}", label(PRINTED))
        } else {
            format!("{indent}{line}")
        };
        let _ = writeln!(out, "{}", line.trim_end());
    }
    let (more, others) = (printed.more, printed.other_cases);
    let more = match (Lang::current(), more) {
        (_, 0) => None,
        (Lang::En, 1) => Some("1 more line".to_string()),
        (Lang::En, n) => Some(format!("{n} more lines")),
        (Lang::Zh, n) => Some(format!("还有 {n} 行")),
    };
    let others = match (Lang::current(), others) {
        (_, 0) => None,
        (Lang::En, 1) => Some("1 other case printed too".to_string()),
        (Lang::En, n) => Some(format!("{n} other cases printed too")),
        (Lang::Zh, n) => Some(format!("另有 {n} 个用例也有输出")),
    };
    let tail: Vec<String> = more.into_iter().chain(others).collect();
    if !tail.is_empty() {
        let _ = writeln!(out, "{indent}{}{}", t("… ", "……"), tail.join(t("; ", "；")));
    }
}

fn render_failure(out: &mut String, f: &Failure, printed: &Printed) {
    let input: Vec<String> = f.input.iter().map(|(n, v)| format!("{n} = {v}")).collect();
    let _ = writeln!(out, "      {}{}", label(INPUT), input.join(", "));
    match &f.problem {
        Problem::Wrong => {
            let _ = writeln!(out, "      {}{}", label(EXPECTED), f.expected);
            let _ = writeln!(out, "      {}{}", label(GOT), f.got);
        }
        Problem::Panicked(m) => {
            let _ = writeln!(out, "      {}{}", label(PANICKED), panic_line(m));
        }
        Problem::TimedOut(s) => {
            let _ = writeln!(
                out,
                "      {}",
                tr!(
                    "never returned within {s} s (an endless loop?)",
                    "{s} 秒内没有返回（是不是死循环？）"
                )
            );
        }
        Problem::Crashed(m) => {
            let _ = writeln!(out, "      {}{m}", label(CRASHED));
        }
        Problem::Error(m) => {
            let _ = writeln!(out, "      {}{m}", label(ERROR));
        }
    }
    if !f.detail.is_empty() {
        let _ = writeln!(out, "      {}", paren(f.detail.get()).trim_start());
    }
    render_printed(out, printed);
    let _ = writeln!(out, "      {}{}", label(HINT), f.hint);
}

#[cfg(test)]
mod tests {
    use super::*;

    fn failing() -> Report {
        Report {
            exercise: "td_target".into(),
            file: Text::same("lessons/07-td-target/exercise.rs"),
            compile_error: None,
            checks: vec![
                CheckReport {
                    name: Text::new("a single step", "只有一步"),
                    cases: 1,
                    status: CheckStatus::Passed,
                    printed: Printed::default(),
                },
                CheckReport {
                    name: Text::new("every step done", "每一步都结束"),
                    cases: 3,
                    status: CheckStatus::Failed(Box::new(Failure {
                        problem: Problem::Wrong,
                        input: vec![(Text::same("gamma"), Text::same("0.98"))],
                        expected: Text::same("[1.0]"),
                        got: Text::same("[2.0]"),
                        detail: Text::default(),
                        hint: Text::new("HINT", "提示文字"),
                    })),
                    printed: Printed::default(),
                },
                CheckReport {
                    name: crate::text!("{} seeded random inputs", "{} 组由随机种子生成的输入", 8),
                    cases: 8,
                    status: CheckStatus::NotRun(Text::new(
                        "an earlier case stopped the program",
                        "前面的用例让程序停止了",
                    )),
                    printed: Printed::default(),
                },
            ],
            mistake: None,
            not_started: None,
        }
    }

    #[test]
    fn a_report_reads_in_either_language_with_the_same_structure() {
        let report = failing();
        let en = {
            let _g = Lang::En.scoped();
            report.render()
        };
        let zh = {
            let _g = Lang::Zh.scoped();
            report.render()
        };
        assert!(en.contains("  ✓ a single step (1 case)"), "{en}");
        assert!(en.contains("      hint:     HINT"), "{en}");
        assert!(en.contains("1/3 checks passed: not yet"), "{en}");
        assert!(zh.contains("  ✓ 只有一步（1 个用例）"), "{zh}");
        assert!(zh.contains("      提示：    提示文字"), "{zh}");
        assert!(zh.contains("8 组由随机种子生成的输入"), "{zh}");
        assert!(zh.contains("前面的用例让程序停止了"), "{zh}");
        assert!(zh.contains("1/3 项检查通过：尚未通过"), "{zh}");
        assert_eq!(en.lines().count(), zh.lines().count());
        // The values are shown as they are.
        assert!(zh.contains("gamma = 0.98") && zh.contains("[2.0]"), "{zh}");
    }

    #[test]
    fn the_failure_labels_are_ten_columns_in_both_languages() {
        // Two columns for each CJK character and full-width colon, one for the rest.
        let width = |s: &str| -> usize {
            s.chars()
                .map(|c| if (c as u32) >= 0x2E80 { 2 } else { 1 })
                .sum()
        };
        for (en, zh) in LABELS {
            assert_eq!((width(en), width(zh)), (10, 10), "{en:?} {zh:?}");
        }
    }

    #[test]
    fn a_panic_s_place_reads_in_the_current_language() {
        let m = "not yet implemented (at lessons/07-td-target/exercise.rs:37:5)";
        let _zh = Lang::Zh.scoped();
        assert_eq!(
            panic_line(m),
            "not yet implemented（位于 lessons/07-td-target/exercise.rs:37:5）"
        );
        assert_eq!(panic_line("index out of bounds"), "index out of bounds");
        let _en = Lang::En.scoped();
        assert_eq!(panic_line(m), m);
    }

    #[test]
    fn the_summary_follows_the_language() {
        let report = failing();
        let _g = Lang::Zh.scoped();
        assert_eq!(report.summary(), "1/3 项检查");
    }

    #[test]
    fn printed_lines_are_bounded_cut_and_cleaned() {
        let mut printed = Printed::default();
        for i in 0..8 {
            printed.push(&format!("line {i}"));
        }
        assert_eq!(printed.lines.len(), PRINTED_LINES);
        assert_eq!(printed.more, 8 - PRINTED_LINES);
        let mut other = Printed::default();
        other.push("\u{1b}[31mred\tline");
        other.push(&"宽".repeat(80));
        assert_eq!(other.lines[0], "\u{fffd}[31mred line");
        // Two columns a character: 50 of them fill the width.
        assert_eq!(
            other.lines[1],
            format!("{}…", "宽".repeat(PRINTED_WIDTH / 2))
        );
        let mut first = Printed::default();
        first.push("a");
        first.append(other);
        assert_eq!(first.lines.len(), 3);
        printed.append(first);
        assert_eq!((printed.lines.len(), printed.more), (PRINTED_LINES, 3 + 3));
    }

    #[test]
    fn printed_lines_sit_under_their_check_in_both_languages() {
        let mut report = failing();
        let mut printed = Printed::default();
        for line in ["x = 1", "", "x = 2"] {
            printed.push(line);
        }
        printed.other_cases = 2;
        report.checks[0].printed = printed.clone();
        printed.other_cases = 0;
        printed.more = 1;
        report.checks[1].printed = printed;
        let en = {
            let _g = Lang::En.scoped();
            report.render()
        };
        assert!(
            en.contains(
                "  ✓ a single step (1 case)\n      printed:  x = 1\n\n                x = 2\n                … 2 other cases printed too\n"
            ),
            "{en}"
        );
        assert!(
            en.contains("      printed:  x = 1\n\n                x = 2\n                … 1 more line\n      hint:     HINT"),
            "{en}"
        );
        let zh = {
            let _g = Lang::Zh.scoped();
            report.render()
        };
        assert!(zh.contains("      输出：    x = 1\n"), "{zh}");
        assert!(zh.contains("……另有 2 个用例也有输出"), "{zh}");
        assert!(zh.contains("……还有 1 行\n      提示："), "{zh}");
        assert_eq!(en.lines().count(), zh.lines().count());
    }

    #[test]
    fn a_report_not_started_says_where_the_todo_is() {
        let mut report = failing();
        report.not_started = Some(37);
        let _g = Lang::En.scoped();
        assert_eq!(report.summary(), "not started (todo!() left)");
        let text = report.render();
        assert!(
            text.contains("still the starter's todo!() (line 37)"),
            "{text}"
        );
        assert!(text.contains("todo!() is still there"), "{text}");
    }
}
