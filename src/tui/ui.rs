//! Drawing only: the app's state to a frame. Nothing here changes state.

use ratatui::buffer::Buffer;
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, Borders, Clear, Gauge, Paragraph, Widget};

use super::app::{App, Overlay, TrainState};
use super::keys::{help, language_label};
use super::sandbox::Field;
use super::theme::Theme;
use super::widgets::{
    cartpole::CartPoleView, clip::ClipChart, lab::LabPanel, pendulum::PendulumView,
    plot::ReturnPlot, tensors, text,
};
use crate::i18n::t;
use crate::lesson::{Environment, TensorView, VIEWS};
use crate::tr;

/// The bottom of the return plot's y-axis in a Pendulum run (returns are negative; a
/// random policy scores around −1200).
const PENDULUM_PLOT_FLOOR: f64 = -1800.0;

/// The smallest terminal the layout fits.
pub const MIN_SIZE: (u16, u16) = (80, 24);

/// Everything `draw` needs beside the app.
pub struct View<'a> {
    /// The app state.
    pub app: &'a App,
    /// Styles.
    pub theme: Theme,
}

impl Widget for &View<'_> {
    fn render(self, area: Rect, buf: &mut Buffer) {
        let (app, theme) = (self.app, self.theme);
        if area.width < MIN_SIZE.0 || area.height < MIN_SIZE.1 {
            let msg = tr!(
                "The terminal is {}×{}; ppo-tutor needs at least {}×{}. Enlarge it, or press q to quit.",
                "终端只有 {}×{}，ppo-tutor 至少需要 {}×{}。请把窗口放大，或按 q 退出。",
                area.width,
                area.height,
                MIN_SIZE.0,
                MIN_SIZE.1
            );
            Paragraph::new(text::wrap([Line::raw(msg)], area.width)).render(area, buf);
            return;
        }
        let [header, body, footer] = Layout::vertical([
            Constraint::Length(1),
            Constraint::Min(0),
            Constraint::Length(2),
        ])
        .areas(area);
        draw_header(app, theme, header, buf);
        draw_body(app, theme, body, buf);
        draw_footer(app, theme, footer, buf);
        match app.overlay {
            Overlay::None => {}
            Overlay::Help => draw_help(theme, area, buf),
            Overlay::Lessons(i) => draw_lessons(app, theme, i, area, buf),
            Overlay::Sandbox => draw_sandbox(app, theme, area, buf),
            Overlay::Exercise(scroll) => draw_exercise(app, theme, scroll, area, buf),
            Overlay::Quiz(i) => draw_quiz(app, theme, i, area, buf),
        }
    }
}

fn draw_header(app: &App, theme: Theme, area: Rect, buf: &mut Buffer) {
    let (pos, total) = app.position();
    let (number, name, counter) = app.current_lesson().map_or_else(Default::default, |l| {
        (
            format!(" {:02}/{:02} ", l.order, app.course.lessons.len()),
            l.title.clone(),
            tr!(
                " · step {}/{}",
                " · 第 {}/{} 节",
                app.step + 1,
                l.steps.len()
            ),
        )
    });
    let train = match app.train {
        TrainState::Running => t("training", "训练中"),
        TrainState::Paused => t("paused", "已暂停"),
        TrainState::Finished => t("finished", "已完成"),
    };
    let last = app.snapshot.returns.last().map_or(String::new(), |r| {
        tr!(
            " · last return {}",
            " · 上回合回报 {}",
            super::app::return_text(*r)
        )
    });
    let right = tr!(
        "episode {}{last} · {train} · {pos}/{total} ",
        "回合 {}{last} · {train} · {pos}/{total} ",
        app.snapshot.episodes
    );
    // The counters on the right and the step number always show; a lesson title too long
    // for the rest is cut by columns, with an ellipsis.
    let width = usize::from(area.width);
    let room = width
        .saturating_sub(text::width(&right) + 1)
        .saturating_sub(text::width(&number) + text::width(&counter));
    let name = if text::width(&name) > room {
        format!("{}…", text::truncate(&name, room.saturating_sub(1)))
    } else {
        name
    };
    let title = text::truncate(&format!("{number}{name}{counter}"), width);
    let pad = width.saturating_sub(text::width(&title) + text::width(&right));
    Line::from(vec![
        Span::styled(title, theme.title()),
        Span::raw(" ".repeat(pad)),
        Span::styled(right, theme.dim()),
    ])
    .render(area, buf);
}

fn panel(title: &str, theme: Theme) -> Block<'static> {
    Block::default()
        .borders(Borders::ALL)
        .border_style(theme.border())
        .title(Span::styled(format!(" {title} "), theme.title()))
}

fn draw_body(app: &App, theme: Theme, area: Rect, buf: &mut Buffer) {
    let Some(step) = app.current_step() else {
        return;
    };
    let [left, right] =
        Layout::horizontal([Constraint::Percentage(45), Constraint::Percentage(55)]).areas(area);
    let body = crate::lesson::details::fold(
        &step.text(crate::lesson::face::Face::Terminal),
        app.details_open,
    );
    let columns = usize::from(left.width.saturating_sub(2));
    let lines = text::wrap(
        text::markdown(&body, theme, columns),
        left.width.saturating_sub(2),
    );
    Paragraph::new(lines)
        .block(panel(&step.title, theme))
        .scroll((app.text_scroll, 0))
        .render(left, buf);
    let env = app
        .current_lesson()
        .map_or_else(Default::default, |l| l.env);
    let mut code = code_lines(step, env, theme, usize::from(right.width.saturating_sub(2)));
    let code_height = (code.len() as u16 + 2).min(right.height / 3).max(5);
    let [code_area, live] =
        Layout::vertical([Constraint::Length(code_height), Constraint::Min(0)]).areas(right);
    // Lines below the pane's last row: the last row says how many (issue 25, section 2).
    let rows = usize::from(code_area.height.saturating_sub(2));
    if code.len() > rows && rows > 0 {
        let hidden = code.len() + 1 - rows;
        code.truncate(rows - 1);
        code.push(Line::styled(
            tr!("… {hidden} more lines", "… 还有 {hidden} 行"),
            theme.dim(),
        ));
    }
    Paragraph::new(code)
        .block(panel(t("the code that runs", "实际运行的代码"), theme))
        .render(code_area, buf);
    draw_live(app, theme, step, live, buf);
}

/// The step's code for a pane `columns` wide: a line too long for it is cut with a dim
/// `…` in its last column, so that it shows it goes on (issue 25, section 2).
fn code_lines(
    step: &crate::lesson::Step,
    env: crate::lesson::Environment,
    theme: Theme,
    columns: usize,
) -> Vec<Line<'static>> {
    let mut lines = Vec::new();
    if !step.python.is_empty() {
        // Whose PyTorch program the lines quote (`Environment::python_source`).
        let source = match env {
            Environment::CartPole => t("the seed", "原教程代码"),
            Environment::Pendulum => t("the book", "书中的代码"),
        };
        lines.push(Line::styled(
            tr!("# {source} (PyTorch)", "# {source}（PyTorch）"),
            theme.dim(),
        ));
        lines.extend(
            step.python
                .lines()
                .map(|l| Line::styled(l.to_string(), theme.python())),
        );
    }
    if let Some((path, code)) = (!step.code.is_empty())
        .then(|| crate::lesson::anchor::find(&step.code))
        .flatten()
    {
        lines.push(Line::styled(
            format!("// ppo-tutor: src/{path}"),
            theme.dim(),
        ));
        lines.extend(
            code.lines()
                .map(|l| Line::styled(l.to_string(), theme.code())),
        );
    }
    if lines.is_empty() {
        lines.push(Line::styled(
            t("(no code in this step)", "（本节没有代码）"),
            theme.dim(),
        ));
    }
    lines
        .into_iter()
        .map(|l| text::cut(l, columns, Span::styled("…", theme.dim())))
        .collect()
}

fn draw_live(app: &App, theme: Theme, step: &crate::lesson::Step, area: Rect, buf: &mut Buffer) {
    let views: Vec<&str> = step
        .show
        .iter()
        .map(String::as_str)
        .filter(|s| VIEWS.contains(s))
        .collect();
    let names: Vec<&str> = step
        .show
        .iter()
        .map(String::as_str)
        .filter(|s| !VIEWS.contains(s))
        .collect();
    let (view_area, tensor_area) = match (views.is_empty(), names.is_empty()) {
        (true, _) => (Rect::default(), area),
        (false, true) => (area, Rect::default()),
        (false, false) => {
            let [a, b] = Layout::vertical([Constraint::Percentage(55), Constraint::Percentage(45)])
                .areas(area);
            (a, b)
        }
    };
    if !views.is_empty() {
        let areas = Layout::horizontal(vec![Constraint::Ratio(1, views.len() as u32); views.len()])
            .split(view_area);
        for (view, a) in views.iter().zip(areas.iter()) {
            draw_view(app, theme, view, *a, buf);
        }
    }
    if tensor_area.height > 0 {
        let shown: Vec<TensorView> = names
            .iter()
            .filter_map(|n| app.snapshot.tensor(n))
            .collect();
        let block = panel(t("live values", "实时数值"), theme);
        let inner = block.inner(tensor_area);
        block.render(tensor_area, buf);
        if shown.is_empty() && !names.is_empty() {
            let line = Line::styled(
                tr!(
                    "{} appear after the first episode: press e (one episode) or t (train).",
                    "{} 在第一个回合之后出现：按 e 训练一个回合，或按 t 连续训练。",
                    names.join(", ")
                ),
                theme.dim(),
            );
            Paragraph::new(text::wrap([line], inner.width)).render(inner, buf);
        } else {
            Paragraph::new(tensors::lines(
                &shown,
                app.tensor_scroll,
                inner.height as usize,
                theme,
            ))
            .render(inner, buf);
        }
    }
}

fn draw_view(app: &App, theme: Theme, view: &str, area: Rect, buf: &mut Buffer) {
    let s = &app.snapshot;
    let previous = app
        .previous
        .as_ref()
        .map(|p| (p.label(), p.values.as_slice()));
    match view {
        "plot" => ReturnPlot {
            returns: &s.returns,
            average: &s.moving_average,
            previous: previous
                .as_ref()
                .map(|(label, values)| (label.as_str(), *values)),
            max_return: match app.env {
                Environment::CartPole => f64::from(app.config.env_id.max_episode_steps()),
                Environment::Pendulum => 0.0,
            },
            min_return: match app.env {
                Environment::CartPole => 0.0,
                Environment::Pendulum => PENDULUM_PLOT_FLOOR,
            },
            block: panel(
                &match app.env {
                    Environment::CartPole => {
                        tr!("PPO on {}", "PPO 训练 {}", app.config.env_id)
                    }
                    Environment::Pendulum => {
                        tr!("PPO on {}", "PPO 训练 {}", Environment::Pendulum.as_str())
                    }
                },
                theme,
            ),
            theme,
        }
        .render(area, buf),
        "cartpole" => {
            let obs = s.observation(app.frame).unwrap_or([0.0; 4]);
            let title = tr!(
                "the latest episode, step {}/{}",
                "最近一个回合，时间步 {}/{}",
                app.frame,
                s.observation_count().saturating_sub(1)
            );
            CartPoleView {
                obs,
                block: panel(&title, theme),
                color: theme.color,
            }
            .render(area, buf);
        }
        "pendulum" => {
            let (theta, torque) = s
                .pendulum_frame(app.frame)
                .unwrap_or((std::f64::consts::PI, 0.0));
            let title = tr!(
                "the latest episode, step {}/{}",
                "最近一个回合，时间步 {}/{}",
                app.frame,
                s.observation_count().saturating_sub(1)
            );
            PendulumView {
                theta,
                torque,
                block: panel(&title, theme),
                color: theme.color,
            }
            .render(area, buf);
        }
        "lab" => {
            let Some(experiment) = app.current_step().and_then(|s| s.lab) else {
                return;
            };
            let base = app.lab_base();
            LabPanel {
                experiment,
                arms: experiment
                    .arms(&base)
                    .into_iter()
                    .map(|a| a.label)
                    .collect(),
                seeds: crate::tui::app::LAB_SEEDS.len(),
                episodes: base.num_episodes,
                state: app.labs.get(&experiment),
                block: panel(
                    &tr!("clip lab: {}", "截断实验室：{}", experiment.name()),
                    theme,
                ),
                theme,
            }
            .render(area, buf);
        }
        _ => {
            let trace = s.trace.as_ref();
            ClipChart {
                eps: app.config.eps,
                epoch: trace.and_then(|t| t.epochs.last()),
                advantage: trace.map_or(&[], |t| t.advantage.as_slice()),
                block: panel(t("L^CLIP against the ratio", "L^CLIP 随比率的变化"), theme),
                theme,
            }
            .render(area, buf);
        }
    }
}

fn draw_footer(app: &App, theme: Theme, area: Rect, buf: &mut Buffer) {
    let keys = [
        ("←/→", t("step", "翻页")),
        ("l", t("lessons", "课程")),
        ("t", t("train/pause", "训练/暂停")),
        ("e", t("one episode", "一个回合")),
        ("r", t("reset", "重置")),
        ("s", t("sandbox", "沙盒")),
        ("L", language_label()),
        ("?", t("help", "帮助")),
        ("q", t("quit", "退出")),
    ];
    // On a narrow terminal the least essential keys go first (`?` lists them all), so that
    // stepping, training, help and quit always show (issue 25: at 80×24 in Chinese `q 退出`
    // was cut to `q`).
    const DROP_ORDER: [&str; 6] = ["e", "r", "s", "L", "l", "t"];
    let width_of = |(k, what): &(&str, &str)| 3 + text::width(k) + text::width(what);
    let mut shown: Vec<(&str, &str)> = keys.to_vec();
    for drop in DROP_ORDER {
        if shown.iter().map(width_of).sum::<usize>() <= usize::from(area.width) {
            break;
        }
        shown.retain(|(k, _)| *k != drop);
    }
    let mut spans = Vec::new();
    for (k, what) in shown {
        spans.push(Span::styled(format!(" {k}"), theme.key()));
        spans.push(Span::raw(format!(" {what} ")));
    }
    // What stays first (the open exercise, the counts), the latest message last: a long
    // message is cut at the right edge, the counts never are. A warning (a corrupt progress
    // file, a grader that cannot start) goes first instead, so it is read whole.
    let mut parts = Vec::new();
    let warning = super::app::is_warning(&app.status);
    if warning {
        parts.push(app.status.clone());
    }
    let exercise = app.exercise_names();
    if !exercise.is_empty() {
        let state = if app.exercise_done() {
            t("done", "已完成")
        } else {
            t("pending", "未完成")
        };
        parts.push(tr!(
            "exercise {}: {state} (g grade, h hint)",
            "练习 {}：{state}（g 评测，h 提示）",
            exercise.join(", ")
        ));
    }
    let (answered, right, questions) = app.quiz_score();
    parts.push(tr!(
        "lessons done {}/{}",
        "已学完 {}/{} 课",
        app.progress.lessons_done.len(),
        app.course.lessons.len()
    ));
    parts.push(tr!(
        "exercises done {}/{}",
        "已完成练习 {}/{}",
        app.progress.exercises_done.len(),
        crate::grade::exercise_names().len()
    ));
    parts.push(tr!(
        "quiz {right}/{questions} right ({answered} answered)",
        "小测验答对 {right}/{questions}（已答 {answered}）"
    ));
    if !app.status.is_empty() && !warning {
        parts.push(app.status.clone());
    }
    let status = format!(" {}", parts.join(" · "));
    Paragraph::new(vec![Line::from(spans), Line::styled(status, theme.dim())]).render(area, buf);
}

/// Clears `rect` for an overlay, and the wide glyph (a CJK character) of the text below
/// that straddles its left edge: the overlay's border would cut that glyph in half, and a
/// terminal would draw neither.
fn clear(rect: Rect, buf: &mut Buffer) {
    Clear.render(rect, buf);
    if rect.x == 0 {
        return;
    }
    for y in rect.top()..rect.bottom() {
        let cell = &mut buf[(rect.x - 1, y)];
        if text::width(cell.symbol()) > 1 {
            cell.set_symbol(" ");
        }
    }
}

fn centered(area: Rect, width: u16, height: u16) -> Rect {
    let w = width.min(area.width);
    let h = height.min(area.height);
    Rect {
        x: area.x + (area.width - w) / 2,
        y: area.y + (area.height - h) / 2,
        width: w,
        height: h,
    }
}

fn draw_help(theme: Theme, area: Rect, buf: &mut Buffer) {
    let width = 72.min(area.width);
    let lines = text::wrap(
        help().into_iter().map(|(k, what)| {
            Line::from(vec![
                Span::styled(format!(" {}", text::pad_right(k, 16)), theme.key()),
                Span::raw(what),
            ])
        }),
        width.saturating_sub(2),
    );
    let rect = centered(
        area,
        width,
        u16::try_from(lines.len() + 2).unwrap_or(u16::MAX),
    );
    clear(rect, buf);
    Paragraph::new(lines)
        .block(panel(t("keys (Esc closes)", "按键（Esc 关闭）"), theme))
        .render(rect, buf);
}

fn draw_lessons(app: &App, theme: Theme, selected: usize, area: Rect, buf: &mut Buffer) {
    let rect = centered(area, 76, app.course.lessons.len() as u16 + 4);
    clear(rect, buf);
    let lines: Vec<Line> = app
        .course
        .lessons
        .iter()
        .enumerate()
        .map(|(i, l)| {
            let mark = if app.progress.lessons_done.contains(&l.id) {
                "✓"
            } else {
                " "
            };
            let text = format!(" {mark} {:02} {}", l.order, l.title);
            // Cut at the panel's edge by columns (a Chinese title is twice as wide).
            let text = text::truncate(&text, usize::from(rect.width.saturating_sub(2)));
            if i == selected {
                Line::styled(text, theme.highlight())
            } else {
                Line::raw(text)
            }
        })
        .collect();
    Paragraph::new(lines)
        .block(panel(
            t(
                "lessons (↑↓, Enter opens, Esc closes)",
                "课程（↑↓ 选择，Enter 打开，Esc 关闭）",
            ),
            theme,
        ))
        .render(rect, buf);
}

fn draw_sandbox(app: &App, theme: Theme, area: Rect, buf: &mut Buffer) {
    let rect = centered(area, 64, Field::ALL.len() as u16 + 7);
    clear(rect, buf);
    let sandbox = &app.sandbox;
    let mut lines: Vec<Line> = Field::ALL
        .iter()
        .map(|&field| {
            let text = format!(" {:<26} {}", field.name(), sandbox.value(field));
            if field == sandbox.selected {
                Line::styled(text, theme.highlight())
            } else if sandbox.applies(field) {
                Line::raw(text)
            } else {
                Line::styled(text, theme.dim())
            }
        })
        .collect();
    lines.push(Line::raw(""));
    lines.push(Line::styled(
        t(
            " ↑↓ choose · +/− or ←/→ change · Enter retrains",
            " ↑↓ 选择 · +/− 或 ←/→ 修改 · Enter 重新训练",
        ),
        theme.dim(),
    ));
    lines.push(Line::styled(
        t(
            " (the current curve stays on the plot for comparison)",
            " （当前曲线会留在图上作对比）",
        ),
        theme.dim(),
    ));
    Paragraph::new(lines)
        .block(panel(t("sandbox", "沙盒"), theme))
        .render(rect, buf);
}

/// The exercise panel: status of each function, revealed hints, the last grading, the
/// reference solution once passed, and a progress bar of exercises done.
fn draw_exercise(app: &App, theme: Theme, scroll: u16, area: Rect, buf: &mut Buffer) {
    let rect = centered(
        area,
        area.width.saturating_sub(8),
        area.height.saturating_sub(4),
    );
    clear(rect, buf);
    let names = app.exercise_names();
    let file_of = |name: &str| crate::grade::starter(name).map_or(String::new(), |(path, _)| path);
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
                " g 评测（保存文件也会重新评测）· h 下一条提示 · ↑↓ 滚动 · Esc 关闭",
            ),
            theme.dim(),
        ),
        Line::raw(""),
    ];
    for name in &names {
        let done = app.progress.exercises_done.contains(name);
        let mark = if done {
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
    let hints = app
        .current_lesson()
        .and_then(|l| l.exercise.as_ref())
        .map_or(&[][..], |e| e.hints.as_slice());
    if app.exercise.hints_shown > 0 {
        lines.push(Line::raw(""));
        lines.push(Line::styled(
            tr!(
                " Hints ({}/{})",
                " 提示（{}/{}）",
                app.exercise.hints_shown,
                hints.len()
            ),
            theme.title(),
        ));
        for (i, hint) in hints.iter().take(app.exercise.hints_shown).enumerate() {
            lines.push(Line::raw(format!(" {}. {hint}", i + 1)));
        }
    }
    if app.exercise.grading {
        lines.push(Line::raw(""));
        let slow = names.iter().any(|n| {
            crate::grade::find(n).is_ok_and(|e| e.meta().backend == crate::grade::Backend::Cargo)
        });
        lines.push(Line::styled(
            if slow {
                t(
                    " grading… (the first time compiles, a few seconds; for the candle exercise, \
                     a few minutes)",
                    " 评测中……（第一次要编译，需要几秒；candle 练习需要几分钟）",
                )
            } else {
                t(
                    " grading… (the first time compiles, a few seconds)",
                    " 评测中……（第一次要编译，需要几秒）",
                )
            },
            theme.dim(),
        ));
    }
    for graded in &app.exercise.graded {
        lines.push(Line::raw(""));
        match &graded.result {
            Ok(report) => lines.extend(report.render().lines().map(|l| Line::raw(format!(" {l}")))),
            Err(e) => lines.push(Line::raw(format!(" {}: {e}", graded.name))),
        }
    }
    if app.exercise_done() {
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
    let [text, gauge] = Layout::vertical([Constraint::Min(0), Constraint::Length(1)])
        .areas(rect.inner(ratatui::layout::Margin::new(1, 1)));
    panel(t("exercise", "练习"), theme).render(rect, buf);
    Paragraph::new(text::wrap(lines, text.width))
        .scroll((scroll, 0))
        .render(text, buf);
    let total = crate::grade::exercise_names().len();
    let done = app.progress.exercises_done.len().min(total);
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

fn draw_quiz(app: &App, theme: Theme, i: usize, area: Rect, buf: &mut Buffer) {
    use crate::lesson::quiz::{QuestionKind, letter_of};
    let (Some(lesson), Some(question)) = (app.current_lesson(), app.quiz_question(i)) else {
        return;
    };
    let width = area.width.saturating_sub(8).min(100);
    let mut lines = vec![
        Line::styled(
            tr!(
                " Check your understanding: question {}/{}",
                " 检验一下：第 {}/{} 题",
                i + 1,
                lesson.quiz.len()
            ),
            theme.title(),
        ),
        Line::raw(""),
        Line::raw(format!(" {}", question.prompt)),
        Line::raw(""),
    ];
    let keys = match &question.kind {
        QuestionKind::Choice { choices, .. } => {
            for (k, choice) in choices.iter().enumerate() {
                lines.push(Line::from(vec![
                    Span::styled(format!(" {}) ", letter_of(k)), theme.key()),
                    Span::raw(choice.clone()),
                ]));
            }
            tr!(
                " a–{} answer",
                " a–{} 作答",
                letter_of(choices.len().saturating_sub(1))
            )
        }
        QuestionKind::Predict { tolerance, .. } => {
            lines.push(Line::from(vec![
                Span::styled(t(" your prediction: ", " 你的预测："), theme.key()),
                Span::raw(format!("{}▏", app.quiz.input)),
                Span::styled(
                    tr!(
                        "  (within ±{tolerance} counts)",
                        "  （误差在 ±{tolerance} 以内算对）"
                    ),
                    theme.dim(),
                ),
            ]));
            if app.snapshot.trace.is_none() {
                lines.push(Line::styled(
                    t(
                        " the live value comes from the agent: train an episode first (e or t)",
                        " 实时数值来自智能体：先训练一个回合（e 或 t）",
                    ),
                    theme.dim(),
                ));
            }
            t(
                " type a number, Enter reveals the live value",
                " 输入一个数，按 Enter 揭晓实时数值",
            )
            .to_string()
        }
    };
    if let Some(verdict) = &app.quiz.verdict {
        lines.push(Line::raw(""));
        lines.extend(verdict.text.lines().map(|l| Line::raw(format!(" {l}"))));
    }
    lines.push(Line::raw(""));
    lines.push(Line::styled(
        tr!(
            "{keys} · n next · p previous · Esc back to the lesson",
            "{keys} · n 下一题 · p 上一题 · Esc 回到课文"
        ),
        theme.dim(),
    ));
    // As tall as the wrapped text needs, at most the screen.
    let lines = text::wrap(lines, width.saturating_sub(2));
    let height = u16::try_from(lines.len() + 2).unwrap_or(u16::MAX);
    let rect = centered(area, width, height.min(area.height.saturating_sub(4)));
    clear(rect, buf);
    panel(t("quiz", "小测验"), theme).render(rect, buf);
    Paragraph::new(lines).render(rect.inner(ratatui::layout::Margin::new(1, 1)), buf);
}
