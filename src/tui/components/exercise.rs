//! The exercise panel (`g`, `h`): each function's status, the hints revealed, the last
//! grading, the reference solution once passed, and a gauge of exercises done.

use std::path::PathBuf;

use ratatui::buffer::Buffer;
use ratatui::layout::{Constraint, Layout, Margin, Rect};
use ratatui::text::{Line, Span};
use ratatui::widgets::{Gauge, Widget};

use super::{Component, Ctx, Reply, Scroll, centered, clear, panel};
use crate::grade::Report;
use crate::i18n::t;
use crate::lesson::{Lesson, Progress};
use crate::tr;
use crate::tui::keys::Action;
use crate::tui::theme::Theme;
use crate::tui::widgets::text;

/// The grading of one exercise function: its report, or why grading could not run.
#[derive(Debug, Clone)]
pub struct Graded {
    /// The function graded, as `ppo-tutor grade` names it.
    pub name: String,
    /// The grader's report, or why grading could not run.
    pub result: Result<Report, String>,
}

impl From<(String, Result<Report, String>)> for Graded {
    /// A `(name, result)` pair, as a grading loop builds it.
    fn from((name, result): (String, Result<Report, String>)) -> Self {
        Self { name, result }
    }
}

impl Graded {
    /// Whether the function was graded and passed every check.
    #[must_use]
    pub fn passed(&self) -> bool {
        self.result.as_ref().is_ok_and(Report::passed)
    }
}

/// The function names `lesson` grades (empty without an exercise).
#[must_use]
pub fn names(lesson: Option<&Lesson>) -> Vec<String> {
    lesson
        .and_then(|l| l.exercise.as_ref())
        .map(|e| e.names().into_iter().map(String::from).collect())
        .unwrap_or_default()
}

/// Whether every function of `lesson`'s exercise has passed (then its reference solution
/// may be shown).
#[must_use]
pub fn done(lesson: Option<&Lesson>, progress: &Progress) -> bool {
    let names = names(lesson);
    !names.is_empty() && names.iter().all(|n| progress.exercises_done.contains(n))
}

/// `lesson`'s exercise files, as `ppo-tutor grade` finds them (relative to the current
/// folder), each once.
#[must_use]
pub fn files(lesson: Option<&Lesson>) -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = names(lesson)
        .iter()
        .filter_map(|n| crate::grade::find(n).ok())
        .map(|e| PathBuf::from(e.starter_path()))
        .collect();
    files.sort();
    files.dedup();
    files
}

/// The open lesson's exercise: grading, its last result, the hints revealed, and the
/// panel's scroll.
#[derive(Debug, Clone, Default)]
pub struct ExercisePanel {
    /// A grading is running on a background thread.
    pub grading: bool,
    /// The last grading of this lesson's functions.
    pub graded: Vec<Graded>,
    /// How many of the lesson's hints are shown.
    pub hints_shown: usize,
    /// Functions to grade, taken by the event loop (which runs the grader off the UI thread).
    pub request: Option<Vec<String>>,
    /// A save came in while grading: grade again when this grading ends.
    pub regrade: bool,
    /// What the grading under way did last (its build, cargo's progress, its checks).
    pub progress: Option<crate::grade::GradeProgress>,
    scroll: Scroll,
}

impl ExercisePanel {
    /// Another lesson opened: its hints and gradings start afresh (a grading under way
    /// still ends, and is shown).
    pub fn lesson_changed(&mut self) {
        *self = Self {
            grading: self.grading,
            ..Self::default()
        };
    }

    /// The first line of the panel shown (for tests and the drawing).
    #[must_use]
    pub fn scroll(&self) -> u16 {
        self.scroll.offset()
    }

    /// Asks for `names` to be graded (unless a grading is under way) and says so.
    pub fn request_grade(&mut self, names: Vec<String>) -> String {
        self.scroll.top();
        if self.grading {
            return t("already grading…", "正在评分……").into();
        }
        self.grading = true;
        let status = tr!("grading {}…", "正在评分 {}……", names.join(", "));
        self.request = Some(names);
        status
    }

    /// Shows one more of `total` hints, and says which.
    pub fn reveal_hint(&mut self, total: usize) -> String {
        self.scroll.top();
        if self.hints_shown < total {
            self.hints_shown += 1;
            tr!("hint {}/{total}", "提示 {}/{total}", self.hints_shown)
        } else {
            tr!("all {total} hints are shown", "{total} 条提示已全部显示")
        }
    }

    /// A grading ended: shows it, records the functions that passed in `progress`, and
    /// says how it went. Whether a save asked for another grading is [`Self::regrade`].
    pub fn on_graded(&mut self, graded: Vec<Graded>, progress: &mut Progress) -> String {
        self.grading = false;
        self.progress = None;
        let passed: Vec<&str> = graded
            .iter()
            .filter(|g| g.passed())
            .map(|g| g.name.as_str())
            .collect();
        for name in &passed {
            progress.exercises_done.insert((*name).to_string());
        }
        let status = if passed.len() == graded.len() {
            t(
                "passed: the reference solution is shown in the exercise panel",
                "通过：练习面板里显示了参考答案",
            )
            .into()
        } else {
            tr!(
                "{}/{} passed: see the exercise panel",
                "{}/{} 通过：详见练习面板",
                passed.len(),
                graded.len()
            )
        };
        self.graded = graded;
        status
    }

    fn lines(&self, ctx: &Ctx<'_>, theme: Theme) -> Vec<Line<'static>> {
        let names = names(ctx.lesson);
        let file_of =
            |name: &str| crate::grade::starter(name).map_or(String::new(), |(path, _)| path);
        let mut files: Vec<String> = names.iter().map(|n| file_of(n)).collect();
        files.dedup();
        let heading = match files.as_slice() {
            [file] => tr!(
                " Write the function(s) in {file}",
                " 在 {file} 里写出下面的函数"
            ),
            _ => t(
                " Write each function in its file",
                " 在各自的文件里写出每个函数",
            )
            .to_string(),
        };
        let mut lines = vec![
            Line::styled(heading, theme.title()),
            Line::styled(
                t(
                    " g grade (saving the file regrades too) · h next hint · ↑↓ scroll · Esc close",
                    " g 评分（保存文件也会重新评分）· h 下一条提示 · ↑↓ 滚动 · Esc 关闭",
                ),
                theme.dim(),
            ),
            Line::raw(""),
        ];
        for name in &names {
            let mark = if ctx.progress.exercises_done.contains(name) {
                t("✓ done", "✓ 已完成")
            } else {
                t("· pending", "· 未完成")
            };
            let mut line = vec![
                Span::styled(format!(" {}", text::pad_right(mark, 10)), theme.key()),
                Span::raw(name.clone()),
            ];
            if files.len() > 1 {
                let width = names.iter().map(|n| text::width(n)).max().unwrap_or(0);
                let pad = " ".repeat(width.saturating_sub(text::width(name)) + 2);
                line.push(Span::styled(format!("{pad}{}", file_of(name)), theme.dim()));
            }
            lines.push(Line::from(line));
        }
        let hints = ctx
            .lesson
            .and_then(|l| l.exercise.as_ref())
            .map_or(&[][..], |e| e.hints.as_slice());
        if self.hints_shown > 0 {
            lines.push(Line::raw(""));
            lines.push(Line::styled(
                tr!(
                    " Hints ({}/{})",
                    " 提示（{}/{}）",
                    self.hints_shown,
                    hints.len()
                ),
                theme.title(),
            ));
            // A hint may hold code spans (`done`): drawn as code, as in the lesson text.
            for (i, hint) in hints.iter().take(self.hints_shown).enumerate() {
                let mut spans = vec![Span::raw(format!(" {}. ", i + 1))];
                spans.extend(text::inline(hint, theme));
                lines.push(Line::from(spans));
            }
        }
        if let (true, Some(progress)) = (self.grading, &self.progress) {
            lines.push(Line::raw(""));
            lines.push(Line::styled(format!(" {progress}"), theme.dim()));
        } else if self.grading {
            lines.push(Line::raw(""));
            let slow = names.iter().any(|n| {
                crate::grade::find(n)
                    .is_ok_and(|e| e.meta().backend == crate::grade::Backend::Cargo)
            });
            lines.push(Line::styled(
                if slow {
                    t(
                        " grading… (the first time compiles, a few seconds; for the candle exercise, \
                         a few minutes)",
                        " 评分中……（第一次要编译，需要几秒；candle 练习需要几分钟）",
                    )
                } else {
                    t(
                        " grading… (the first time compiles, a few seconds)",
                        " 评分中……（第一次要编译，需要几秒）",
                    )
                },
                theme.dim(),
            ));
        }
        for graded in &self.graded {
            lines.push(Line::raw(""));
            match &graded.result {
                Ok(report) => {
                    lines.extend(report.render().lines().map(|l| Line::raw(format!(" {l}"))));
                }
                Err(e) => {
                    let name = &graded.name;
                    lines.push(Line::raw(tr!(" {name}: {e}", " {name}：{e}")));
                }
            }
        }
        if done(ctx.lesson, ctx.progress) {
            if let Some(exercise) = ctx.lesson.and_then(|l| l.exercise.as_ref()) {
                lines.push(Line::raw(""));
                lines.push(Line::styled(
                    t(" What it tested", " 这个练习考查的思想"),
                    theme.title(),
                ));
                for (name, idea) in exercise.names().iter().zip(&exercise.ideas) {
                    let mut spans = vec![Span::raw(tr!(" {name}: ", " {name}："))];
                    spans.extend(text::inline(idea, theme));
                    lines.push(Line::from(spans));
                }
            }
            let mut solutions: Vec<&str> = names
                .iter()
                .filter_map(|n| crate::grade::solution(n))
                .collect();
            solutions.dedup();
            for code in solutions {
                lines.push(Line::raw(""));
                lines.push(Line::styled(
                    t(" The reference solution", " 参考答案"),
                    theme.title(),
                ));
                lines.extend(code.lines().map(|l| Line::raw(format!(" {l}"))));
            }
        }
        lines
    }
}

impl Component for ExercisePanel {
    fn handle(&mut self, action: Action, _: &Ctx<'_>) -> Reply {
        if self.scroll.key(action) {
            return Reply::Stay;
        }
        match action {
            Action::Quit => Reply::Quit,
            Action::Grade | Action::Hint => Reply::Pass(action),
            Action::Back | Action::Enter => Reply::Close,
            _ => Reply::Stay,
        }
    }

    fn render(&self, ctx: &Ctx<'_>, theme: Theme, area: Rect, buf: &mut Buffer) {
        let rect = centered(
            area,
            area.width.saturating_sub(8),
            area.height.saturating_sub(4),
        );
        clear(rect, buf);
        let [body, gauge] = Layout::vertical([Constraint::Min(0), Constraint::Length(1)])
            .areas(rect.inner(Margin::new(1, 1)));
        panel(t("exercise", "练习"), theme).render(rect, buf);
        let lines = text::wrap_hanging(self.lines(ctx, theme), body.width);
        self.scroll.render(lines, theme, body, buf);
        let total = crate::grade::exercise_names().len();
        let done = ctx.progress.exercises_done.len().min(total);
        Gauge::default()
            .gauge_style(theme.key())
            .ratio(if total == 0 {
                0.0
            } else {
                done as f64 / total as f64
            })
            .label(tr!(
                "exercises done {done}/{total}",
                "已完成练习 {done}/{total}"
            ))
            .render(gauge, buf);
    }
}
