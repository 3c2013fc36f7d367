//! What grading found: one line per check, the first failure of each with its input,
//! expected and actual results, and a hint; rendered as plain text for the terminal.

use std::fmt::Write as _;

use crate::i18n::{Lang, t};
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

    /// One short phrase in the current language: `passed`, `does not compile`,
    /// `panicked`, `3/5 checks`, ...
    #[must_use]
    pub fn summary(&self) -> String {
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
                tr!("{p}/{n} checks, panicked", "{p}/{n} 项检查，panic 了")
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
        let mut out = format!("{} ({})\n", self.exercise, self.file);
        if let Some((summary, compiler)) = &self.compile_error {
            let _ = writeln!(out, "  ✗ {}\n", phrase(summary));
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
            let name = check_name(&check.name);
            match &check.status {
                CheckStatus::Passed => {
                    let _ = writeln!(out, "  ✓ {name}{}", paren(&cases));
                }
                CheckStatus::NotRun(why) => {
                    let _ = writeln!(
                        out,
                        "  · {name}{}{}",
                        paren(&cases),
                        tr!(": not run, {}", "：未运行，{}", phrase(why))
                    );
                }
                CheckStatus::Failed(f) => {
                    let _ = writeln!(out, "  ✗ {name}{}", paren(&cases));
                    render_failure(&mut out, f);
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

/// The labels of the failure details, `(English, Chinese)`, each padded to 10 columns (a
/// Chinese character and the full-width colon are two columns each: `输入：` is 6). The
/// grader is built without the app's text-width crate (notebooks), so the padding is
/// written out; a test measures it.
const INPUT: (&str, &str) = ("input:    ", "输入：    ");
const EXPECTED: (&str, &str) = ("expected: ", "应为：    ");
const GOT: (&str, &str) = ("got:      ", "实际：    ");
const PANICKED: (&str, &str) = ("panicked: ", "panic：   ");
const CRASHED: (&str, &str) = ("crashed:  ", "崩溃：    ");
const ERROR: (&str, &str) = ("error:    ", "错误：    ");
const HINT: (&str, &str) = ("hint:     ", "提示：    ");
#[cfg(test)]
const LABELS: [(&str, &str); 7] = [INPUT, EXPECTED, GOT, PANICKED, CRASHED, ERROR, HINT];

fn label((en, zh): (&'static str, &'static str)) -> &'static str {
    t(en, zh)
}

fn render_failure(out: &mut String, f: &Failure) {
    let input: Vec<String> = f
        .input
        .iter()
        .map(|(n, v)| format!("{n} = {}", lists(v)))
        .collect();
    let _ = writeln!(out, "      {}{}", label(INPUT), input.join(", "));
    match &f.problem {
        Problem::Wrong => {
            let _ = writeln!(out, "      {}{}", label(EXPECTED), phrase(&f.expected));
            let _ = writeln!(out, "      {}{}", label(GOT), phrase(&f.got));
        }
        Problem::Panicked(m) => {
            let _ = writeln!(out, "      {}{m}", label(PANICKED));
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
            let _ = writeln!(out, "      {}{}", label(CRASHED), phrase(m));
        }
        Problem::Error(m) => {
            let _ = writeln!(out, "      {}{m}", label(ERROR));
        }
    }
    if !f.detail.is_empty() {
        let _ = writeln!(out, "      {}", paren(&phrase(&f.detail)).trim_start());
    }
    let _ = writeln!(out, "      {}{}", label(HINT), f.hint);
}

/// A check's name in the current language. The names are written in English where the
/// checks are defined (`grade/exercises/`); their Chinese is here, exact names first, then
/// the ones with numbers in them. A name without a translation is shown as it is.
#[must_use]
pub fn check_name(name: &str) -> String {
    if Lang::current() == Lang::En {
        return name.to_string();
    }
    if let Some(zh) = CHECK_NAMES
        .iter()
        .find_map(|(en, zh)| (*en == name).then_some(*zh))
    {
        return zh.to_string();
    }
    if let Some(n) = name.strip_suffix(" seeded random inputs") {
        return format!("{n} 组由随机种子生成的输入");
    }
    if let Some(rest) = name.strip_prefix("losses on ")
        && let Some(n) = rest.strip_suffix(" seeded random batches")
    {
        return format!("{n} 个由随机种子生成的批次上的损失");
    }
    if let Some(epochs) = name.strip_prefix("losses on the recorded PyTorch episodes, epochs ") {
        return format!("录制的 PyTorch 回合上的损失（第 {epochs} 轮）");
    }
    if let Some(rest) = name.strip_prefix("plugged into the agent, CartPole learns (")
        && let Some((episodes, seed)) = rest
            .strip_suffix(')')
            .and_then(|r| r.split_once(" episodes, seed "))
    {
        return format!("接入智能体后 CartPole 能学会（{episodes} 个回合，随机种子 {seed}）");
    }
    name.to_string()
}

/// The fixed English phrases a report carries as data (reasons a check did not run,
/// results described in words), in the current language; anything else as it is.
#[must_use]
pub fn phrase(text: &str) -> String {
    if Lang::current() == Lang::En {
        return text.to_string();
    }
    if let Some(zh) = PHRASES
        .iter()
        .find_map(|(en, zh)| (*en == text).then_some(*zh))
    {
        return zh.to_string();
    }
    if let Some(rest) = text.strip_prefix("in the first vector, ") {
        return format!("第一个向量中，{}", phrase(rest));
    }
    if let Some(rest) = text.strip_prefix("in the second vector, ") {
        return format!("第二个向量中，{}", phrase(rest));
    }
    if let Some(rest) = text.strip_prefix("first difference at [")
        && let Some((index, rest)) = rest.split_once("]: expected ")
        && let Some((want, got)) = rest.split_once(", got ")
    {
        return format!("第一处不同在 [{index}]：应为 {want}，实际为 {got}");
    }
    // `ppo_losses`'s gradients: `fc1.weight[3]: expected 0.1, got 0.2`
    if let Some((name, rest)) = text.split_once("]: expected ")
        && let Some((want, got)) = rest.split_once(", got ")
        && !name.contains(' ')
    {
        return format!("{name}]：应为 {want}，实际为 {got}");
    }
    if let Some(rest) = text.strip_prefix("expected ")
        && let Some((want, got)) = rest.split_once(" values, got ")
    {
        return format!("应有 {want} 个值，实际 {got} 个");
    }
    if let Some(mean) = text.strip_prefix("a mean of ") {
        return format!("平均 {mean}");
    }
    if let Some(rest) = text.strip_prefix("the program stopped (") {
        return format!("程序停止了（{rest}");
    }
    if let Some(rest) = text.strip_prefix("unexpected output '") {
        return format!("意外的输出 '{rest}");
    }
    if let Some(rest) = text.strip_prefix("unreadable result '") {
        return format!("无法读取的结果 '{rest}");
    }
    if let Some(rest) = text.strip_prefix("the grader failed: ") {
        return format!("评分器自身出错：{rest}");
    }
    lists(text)
}

/// Every shortened list in `text`, `[1.0, 2.0, … ] (149 values)`, with its count in the
/// current language.
fn lists(text: &str) -> String {
    if Lang::current() == Lang::En {
        return text.to_string();
    }
    let mut out = String::new();
    let mut rest = text;
    while let Some(at) = rest.find("… ] (") {
        let after = &rest[at + "… ] (".len()..];
        let digits = after.bytes().take_while(u8::is_ascii_digit).count();
        match after[digits..].strip_prefix(" values)") {
            Some(tail) if digits > 0 => {
                out.push_str(&rest[..at]);
                out.push_str(&format!("… ]（共 {} 个值）", &after[..digits]));
                rest = tail;
            }
            _ => {
                out.push_str(&rest[..at + "… ] (".len()]);
                rest = after;
            }
        }
    }
    out.push_str(rest);
    out
}

const PHRASES: &[(&str, &str)] = &[
    ("the file does not compile", "文件编译不通过"),
    ("the actor loss differs", "策略网络的损失不同"),
    ("the critic loss differs", "价值网络的损失不同"),
    (
        "the gradients could not be carried to the weights",
        "梯度无法传回到权重上",
    ),
    (
        "an earlier case stopped the program",
        "前面的用例让程序停止了",
    ),
    ("the reference could not be computed", "参考答案无法计算"),
    ("the grading thread stopped", "评分线程停止了"),
    ("training stopped", "训练中止了"),
    ("the program had stopped", "程序已经停止"),
    (
        "the learner's function gave no losses",
        "你的函数没有给出损失",
    ),
];

const CHECK_NAMES: &[(&str, &str)] = &[
    ("n = 1 is the TD target", "n = 1 就是 TD 目标"),
    (
        "no done at all: bootstrap at the rollout's end",
        "没有一步结束：在采样段末尾自举",
    ),
    ("an episode ends inside the window", "回合在窗口之内结束"),
    (
        "the same policy: every weight is 1",
        "同一个策略：每个权重都是 1",
    ),
    ("a rare action: a large weight", "罕见的动作：很大的权重"),
    ("six actions per row", "每行六个动作"),
    (
        "the old policy never takes some actions",
        "旧策略从不采取某些动作",
    ),
    (
        "rows where the two policies agree (0)",
        "两个策略一致的行（为 0）",
    ),
    (
        "PyTorch's kl_divergence of two Categoricals (recorded)",
        "PyTorch 对两个 Categorical 的 kl_divergence（录制）",
    ),
    (
        "values within eps of old: the plain half MSE",
        "新旧价值相差不超过 eps：就是普通的半均方误差",
    ),
    ("every value moved beyond eps", "每个价值都移动超过了 eps"),
    (
        "never stops: moves both ways that cancel",
        "从不停止：两个方向的变化相互抵消",
    ),
    (
        "every sampled action made more likely",
        "每个采样到的动作的概率都提高了",
    ),
    (
        "passes target_kl one epoch before 1.5 × target_kl",
        "越过 target_kl 比越过 1.5 × target_kl 早一轮",
    ),
    ("stops before the first step", "在第一步之前就停止"),
    ("dim = 1: the one-dimensional density", "dim = 1：一维密度"),
    ("a single row of six dimensions", "只有一行，六个维度"),
    ("actions many σ from μ", "离 μ 有许多个 σ 的动作"),
    (
        "log σ = 0 in every dimension (CleanRL's initial policy)",
        "每个维度 log σ = 0（CleanRL 的初始策略）",
    ),
    (
        "PyTorch's Normal.log_prob, recorded: each case one row of its dimensions",
        "录制的 PyTorch Normal.log_prob：每个用例是一行，含其各个维度",
    ),
    ("a single step", "只有一步"),
    ("a single row", "只有一行"),
    ("a single value", "只有一个值"),
    ("a single step, either way", "只有一步，两个方向"),
    ("every step done", "每一步都结束"),
    (
        "PyTorch's Normal.log_prob (recorded)",
        "PyTorch 的 Normal.log_prob（录制）",
    ),
    (
        "σ near 1e-3 (a nearly certain policy)",
        "σ 接近 1e-3（几乎确定的策略）",
    ),
    ("σ large", "σ 很大"),
    ("actions far from μ", "远离 μ 的动作"),
    ("no rows", "没有行"),
    (
        "the first epoch (equal log-probabilities)",
        "第一轮（对数概率相等）",
    ),
    ("ratios outside 1 ± ε", "比率落在 1 ± ε 之外"),
    ("ratios exactly at 1 ± ε", "比率恰好等于 1 ± ε"),
    (
        "ratios exactly at 1 ± ε, in float32",
        "比率恰好等于 1 ± ε（float32）",
    ),
    ("ratios exactly ε from 1", "比率与 1 恰好相差 ε"),
    ("negative advantages", "负的优势值"),
    (
        "near-certain and near-impossible actions",
        "几乎必然和几乎不可能的动作",
    ),
    ("each side of the band, each sign", "区间两侧，正负都有"),
    ("a zero advantage", "优势值为 0"),
    (
        "numpy's rl_utils.moving_average (recorded)",
        "numpy 版 rl_utils.moving_average（录制）",
    ),
    ("a window larger than the input", "窗口比输入长"),
    ("a window as long as the input", "窗口与输入一样长"),
    ("negative TD errors", "负的 TD 误差"),
    (
        "negative TD errors (the critic overestimates)",
        "负的 TD 误差（价值网络高估了）",
    ),
    ("λ = 0 and λ = 1", "λ = 0 和 λ = 1"),
    ("two rows", "两行"),
    ("every advantage equal", "所有优势值相等"),
    ("advantages smaller than 1", "小于 1 的优势值"),
    ("an episode cut by the time limit", "因时限中断的回合"),
    ("an episode where the pole fell", "杆倒下的回合"),
    ("terminated and truncated at once", "同时终止和时限中断"),
    ("the first epoch (nothing moved)", "第一轮（什么都没变）"),
    (
        "every action more likely than before",
        "每个动作的概率都比以前高",
    ),
    (
        "an action of probability 0 is never chosen",
        "概率为 0 的动作永远不会被选中",
    ),
    (
        "probabilities summing a hair below u",
        "概率之和比 u 略小一点",
    ),
    (
        "a time-limit cut, then a new episode",
        "时限中断后开始新回合",
    ),
    ("a fall, then a new episode", "杆倒下后开始新回合"),
    ("a rollout that ends mid-episode", "在回合中途结束的采样"),
    ("errors of both signs", "正负两种误差"),
    ("both sides of the band", "区间的两侧"),
    (
        "the first epoch (every ratio 1)",
        "第一轮（每个比率都是 1）",
    ),
    ("the recorded PyTorch episodes", "录制的 PyTorch 回合"),
    (
        "losses on edge cases (a single step, only negative advantages with every ratio outside 1 ± ε, every ratio exactly 1)",
        "边界情况上的损失（只有一步；优势值全为负且每个比率都在 1 ± ε 之外；每个比率恰为 1）",
    ),
];

#[cfg(test)]
mod tests {
    use super::*;

    fn failing() -> Report {
        Report {
            exercise: "td_target".into(),
            file: "lessons/07-td-target/exercise.rs".into(),
            compile_error: None,
            checks: vec![
                CheckReport {
                    name: "a single step".into(),
                    cases: 1,
                    status: CheckStatus::Passed,
                },
                CheckReport {
                    name: "every step done".into(),
                    cases: 3,
                    status: CheckStatus::Failed(Box::new(Failure {
                        problem: Problem::Wrong,
                        input: vec![("gamma".into(), "0.98".into())],
                        expected: "[1.0]".into(),
                        got: "[2.0]".into(),
                        detail: String::new(),
                        hint: "HINT".into(),
                    })),
                },
                CheckReport {
                    name: "8 seeded random inputs".into(),
                    cases: 8,
                    status: CheckStatus::NotRun("an earlier case stopped the program".into()),
                },
            ],
            mistake: None,
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
        assert!(zh.contains("      提示：    HINT"), "{zh}");
        assert!(zh.contains("8 组由随机种子生成的输入"), "{zh}");
        assert!(zh.contains("前面的用例让程序停止了"), "{zh}");
        assert!(zh.contains("1/3 项检查通过：尚未通过"), "{zh}");
        assert_eq!(en.lines().count(), zh.lines().count());
        let _zh = Lang::Zh.scoped();
        assert_eq!(
            phrase("first difference at [1]: expected -1.5, got 8.25"),
            "第一处不同在 [1]：应为 -1.5，实际为 8.25"
        );
        assert_eq!(
            phrase("fc1.weight[3]: expected 0.1, got 0.2"),
            "fc1.weight[3]：应为 0.1，实际为 0.2"
        );
        assert_eq!(phrase("the actor loss differs"), "策略网络的损失不同");
        assert_eq!(
            phrase("[1.0, 2.0, … ] (149 values)"),
            "[1.0, 2.0, … ]（共 149 个值）"
        );
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
    fn the_summary_follows_the_language() {
        let report = failing();
        let _g = Lang::Zh.scoped();
        assert_eq!(report.summary(), "1/3 项检查");
    }
}
