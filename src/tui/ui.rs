//! Drawing only: the app's state to a frame (the header, the lesson view, the footer; each
//! open face draws itself, `super::components`). Nothing here changes state.

use ratatui::buffer::Buffer;
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::text::{Line, Span};
use ratatui::widgets::{Paragraph, Widget};

use super::app::{App, Overlay, TrainState};
use super::components::{Component, panel};
use super::keys::language_label;
use super::theme::Theme;
use super::widgets::lab::Guess;
use super::widgets::{
    cartpole::CartPoleView, clip::ClipChart, pendulum::PendulumView, plot::ReturnPlot, tensors,
    text,
};
use crate::i18n::t;
use crate::lesson::{TensorView, View as StepView};
use crate::tr;

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
        let status = status_lines(app, usize::from(area.width));
        let rows = u16::try_from(status.len()).unwrap_or(1);
        let [header, body, footer] = Layout::vertical([
            Constraint::Length(1),
            Constraint::Min(0),
            Constraint::Length(1 + rows),
        ])
        .areas(area);
        draw_header(app, theme, header, buf);
        draw_body(app, theme, body, buf);
        draw_footer(theme, &status, footer, buf);
        let ctx = app.ctx();
        match app.overlay {
            Overlay::None => {}
            Overlay::Help => app.help.render(&ctx, theme, area, buf),
            Overlay::Lessons => app.lesson_list.render(&ctx, theme, area, buf),
            Overlay::Sandbox => app.sandbox.render(&ctx, theme, area, buf),
            Overlay::Exercise => app.exercise.render(&ctx, theme, area, buf),
            Overlay::Quiz => app.quiz.render(&ctx, theme, area, buf),
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
    let train = match app.run.train {
        TrainState::Running => t("training", "训练中"),
        TrainState::Paused => t("paused", "已暂停"),
        TrainState::Finished => t("finished", "已完成"),
    };
    let last = app.run.snapshot.returns.last().map_or(String::new(), |r| {
        tr!(
            " · last return {}",
            " · 上回合回报 {}",
            super::run::return_text(*r)
        )
    });
    // While the live agent does not run the lessons' settings, the header says so.
    let own = if app.run.changed_settings().is_empty() {
        ""
    } else {
        t("your settings · ", "你的设置 · ")
    };
    let right = tr!(
        "{own}episode {}{last} · {train} · {pos}/{total} ",
        "{own}回合 {}{last} · {train} · {pos}/{total} ",
        app.run.snapshot.episodes
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

fn draw_body(app: &App, theme: Theme, area: Rect, buf: &mut Buffer) {
    let Some(step) = app.current_step() else {
        return;
    };
    let [left, right] =
        Layout::horizontal([Constraint::Percentage(45), Constraint::Percentage(55)]).areas(area);
    app.explanation.render(&app.ctx(), theme, left, buf);
    let lesson = app.current_lesson();
    let env = lesson.map_or_else(Default::default, |l| l.env);
    let order = lesson.map_or(0, |l| l.order);
    let passed = |e: &str| app.progress.exercises_done.contains(e);
    let columns = usize::from(right.width.saturating_sub(2));
    let code: Vec<Line<'static>> = code_lines(step, (env, order), &passed, theme, columns)
        .into_iter()
        .flat_map(|l| wrap_code(l, columns, theme))
        .collect();
    let code_height = (code.len() as u16 + 2).min(right.height / 3).max(5);
    let [code_area, live] =
        Layout::vertical([Constraint::Length(code_height), Constraint::Min(0)]).areas(right);
    let rows = usize::from(code_area.height.saturating_sub(2));
    let code = scroll_code(app, code, rows, theme);
    Paragraph::new(code)
        .block(panel(t("the code that runs", "实际运行的代码"), theme))
        .render(code_area, buf);
    draw_live(app, theme, step, live, buf);
}

/// A code line wider than `columns` as several rows: the rest continues on the next row
/// after a dim `↪`, so nothing is cut.
fn wrap_code(line: Line<'static>, columns: usize, theme: Theme) -> Vec<Line<'static>> {
    if line.width() <= columns || columns < 8 {
        return vec![line];
    }
    let mut rows = Vec::new();
    let mut current: Vec<Span<'static>> = Vec::new();
    let mut used = 0;
    for span in line.spans {
        let mut rest: &str = &span.content;
        while !rest.is_empty() {
            let room = columns - used;
            let kept = text::truncate(rest, room);
            if kept.is_empty() {
                rows.push(Line::from(std::mem::take(&mut current)));
                current.push(Span::styled("↪ ", theme.dim()));
                used = 2;
                continue;
            }
            used += text::width(&kept);
            rest = &rest[kept.len()..];
            current.push(Span::styled(kept, span.style));
        }
    }
    if !current.is_empty() {
        rows.push(Line::from(current));
    }
    rows
}

/// The code pane's `rows` rows from [`App::code_scroll`]: when lines are hidden, the first
/// row says how many are above and the last how many below, with the keys that scroll.
fn scroll_code(
    app: &App,
    code: Vec<Line<'static>>,
    rows: usize,
    theme: Theme,
) -> Vec<Line<'static>> {
    let marks = super::components::Marks {
        up: |n| {
            tr!(
                "↑ {n} lines above: [ scrolls",
                "↑ 上面还有 {n} 行：按 [ 滚动"
            )
        },
        down: |n| {
            tr!(
                "↓ {n} more lines: ] scrolls",
                "↓ 下面还有 {n} 行：按 ] 滚动"
            )
        },
    };
    let (shown, max) = super::components::window(code, rows, app.code_scroll, &marks, theme);
    app.code_max.set(max);
    shown
}

/// The step's code for a pane `columns` wide (the drawing wraps a line too long for it,
/// [`wrap_code`]). Code an exercise asks for is a dim note until `passed` holds for it
/// ([`crate::lesson::reveal`]), wrapped to `columns`; once shown, a line points to the
/// learner's own file for each exercise of the step's lesson (`order`) it shows.
fn code_lines(
    step: &crate::lesson::Step,
    (env, order): (crate::lesson::AgentKind, u32),
    passed: &dyn Fn(&str) -> bool,
    theme: Theme,
    columns: usize,
) -> Vec<Line<'static>> {
    let mut lines = Vec::new();
    if !step.python.is_empty() {
        // Whose PyTorch program the lines quote (`AgentKind::python_source`).
        let source = env.source_name();
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
    if let Some(listing) = (!step.code.is_empty())
        .then(|| crate::lesson::reveal::listing(&step.code, passed))
        .flatten()
    {
        let (krate, path) = (listing.krate, &listing.path);
        lines.push(Line::styled(format!("// {krate}: {path}"), theme.dim()));
        for gate in listing.shown.iter().filter(|g| g.lesson == order) {
            if let Ok(ex) = crate::grade::find(&gate.exercise) {
                let (name, file) = (&gate.exercise, ex.meta().starter);
                let folder = &gate.folder;
                lines.push(Line::styled(
                    tr!(
                        "// your {name}: lessons/{folder}/{file}",
                        "// 你写的 {name}：lessons/{folder}/{file}"
                    ),
                    theme.dim(),
                ));
            }
        }
        for row in &listing.rows {
            match row {
                crate::lesson::reveal::Row::Code(code) => {
                    lines.push(Line::styled(code.clone(), theme.code()));
                }
                crate::lesson::reveal::Row::Hidden { indent, by } => {
                    lines.extend(note_lines(*indent, by, theme, columns));
                }
            }
        }
    }
    if lines.is_empty() {
        lines.push(Line::styled(
            t("(no code in this step)", "（本节没有代码）"),
            theme.dim(),
        ));
    }
    lines
}

/// The text of `lesson`'s step `step`'s code pane, as the app draws it for a learner who has
/// passed the exercises for which `passed` holds, in a pane wide enough for every line:
/// what a test reads to check that no answer shows before its exercise is passed.
#[must_use]
pub fn code_pane_text(
    lesson: &crate::lesson::Lesson,
    step: usize,
    passed: &dyn Fn(&str) -> bool,
) -> String {
    let Some(s) = lesson.steps.get(step) else {
        return String::new();
    };
    let theme = Theme { color: false };
    code_lines(s, (lesson.env, lesson.order), passed, theme, usize::MAX)
        .iter()
        .map(|l| {
            l.spans
                .iter()
                .map(|s| s.content.as_ref())
                .collect::<String>()
        })
        .collect::<Vec<_>>()
        .join("\n")
}

/// A hidden region's note ([`crate::lesson::reveal::note`]) as dim comment lines at
/// `indent`, wrapped to `columns`.
fn note_lines(
    indent: usize,
    by: &[crate::lesson::reveal::Gate],
    theme: Theme,
    columns: usize,
) -> Vec<Line<'static>> {
    let prefix = format!("{}// ", " ".repeat(indent));
    let room = columns.saturating_sub(text::width(&prefix)).max(12);
    let note = crate::lesson::reveal::note(by);
    let wrapped = text::wrap([Line::raw(note)], u16::try_from(room).unwrap_or(u16::MAX));
    wrapped
        .into_iter()
        .map(|l| {
            let words: String = l.spans.iter().map(|s| s.content.as_ref()).collect();
            Line::styled(format!("{prefix}{}", words.trim_end()), theme.dim())
        })
        .collect()
}

fn draw_live(app: &App, theme: Theme, step: &crate::lesson::Step, area: Rect, buf: &mut Buffer) {
    if app.live_hidden() {
        // The open question asks for a number these values show: they wait for the answer.
        let block = panel(t("live values", "实时数值"), theme);
        let inner = block.inner(area);
        block.render(area, buf);
        let line = Line::styled(
            t(
                "hidden while the quiz question is open: they would give its answer away. Answer it, and they come back.",
                "小测验题目打开时先隐藏：它们会泄露答案。作答之后就会重新显示。",
            ),
            theme.dim(),
        );
        Paragraph::new(text::wrap([line], inner.width)).render(inner, buf);
        return;
    }
    let views: Vec<StepView> = step
        .show
        .iter()
        .filter_map(|s| StepView::from_name(s))
        .collect();
    let names: Vec<&str> = step
        .show
        .iter()
        .map(String::as_str)
        .filter(|s| StepView::from_name(s).is_none())
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
            draw_view(app, theme, *view, *a, buf);
        }
    }
    if tensor_area.height > 0 {
        let shown: Vec<TensorView> = names
            .iter()
            .filter_map(|n| app.run.snapshot.tensor(n))
            .collect();
        let block = panel(t("live values", "实时数值"), theme);
        let inner = block.inner(tensor_area);
        block.render(tensor_area, buf);
        let notes = text::wrap(missing_notes(app, &names, theme), inner.width);
        if shown.is_empty() && notes.is_empty() && !names.is_empty() {
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
            let view = tensors::Viewport {
                width: usize::from(inner.width),
                height: usize::from(inner.height),
                scroll: app.tensor_scroll,
                hscroll: app.tensor_hscroll,
            };
            // A title or series line wider than the pane ends in a dim `…`, as code does.
            let columns = usize::from(inner.width);
            let view = tensors::Viewport {
                height: view.height.saturating_sub(notes.len()),
                ..view
            };
            let (table, rows) = tensors::render(&shown, view, theme);
            app.tensor_rows.set(rows);
            let lines: Vec<Line> = notes
                .into_iter()
                .chain(table)
                .map(|l| text::cut(l, columns, Span::styled("…", theme.dim())))
                .collect();
            Paragraph::new(lines).render(inner, buf);
        }
    }
}

/// Why the PPO-Penalty values among `names` are empty in a run of another objective, and
/// how to see them: one dim line (none before the first update, or when they are there).
fn missing_notes(app: &App, names: &[&str], theme: Theme) -> Vec<Line<'static>> {
    let s = &app.run.snapshot;
    let missing: Vec<&str> = names
        .iter()
        .copied()
        .filter(|n| crate::lesson::live::PENALTY_ONLY.contains(n) && s.tensor(n).is_none())
        .collect();
    if missing.is_empty() || s.cartpole_update().is_none() {
        return Vec::new();
    }
    vec![Line::styled(
        tr!(
            "{}: PPO-Penalty's values, empty while the live agent runs another objective. To see them, press s, set objective to penalty, and Enter retrains.",
            "{}：PPO-惩罚的数值，实时运行的智能体用别的目标时为空。要看到它们，按 s，把 objective 设为 penalty，再按 Enter 重新训练。",
            missing.join(t(", ", "、"))
        ),
        theme.dim(),
    )]
}

fn draw_view(app: &App, theme: Theme, view: StepView, area: Rect, buf: &mut Buffer) {
    let s = &app.run.snapshot;
    let previous = app
        .run
        .previous
        .as_ref()
        .map(|p| (p.label(), p.values.as_slice()));
    match view {
        StepView::Plot => {
            // The seed's window (9) up to 549 episodes; a longer run (Pendulum's 2000) is
            // smoothed over more, or its average is as noisy as its returns.
            let window = crate::plot::window::window(app.run.config().num_episodes());
            let scaled = (window != crate::plot::SMOOTHING_WINDOW)
                .then(|| crate::ppo::moving_average(&s.returns, window).ok())
                .flatten();
            let average = scaled.as_deref().unwrap_or(&s.moving_average);
            let window = if scaled.is_some() {
                window
            } else {
                crate::plot::SMOOTHING_WINDOW
            };
            ReturnPlot {
                returns: &s.returns,
                average,
                window,
                previous: previous
                    .as_ref()
                    .map(|(label, values)| (label.as_str(), *values)),
                max_return: app.run.config().max_return(),
                min_return: app.run.agent.spec().plot_floor,
                block: panel(
                    &tr!(
                        "{} on {}",
                        "{} 训练 {}",
                        crate::plot::labels::algorithm(&app.run.config()),
                        app.run.config().env_id()
                    ),
                    theme,
                ),
                theme,
            }
            .render(area, buf);
        }
        StepView::CartPole => {
            let obs = s
                .observation(app.run.frame)
                .and_then(|o| <[f32; 4]>::try_from(o).ok())
                .unwrap_or([0.0; 4]);
            let title = tr!(
                "the latest episode, step {}/{}",
                "最近一个回合，时间步 {}/{}",
                app.run.frame,
                s.observation_count().saturating_sub(1)
            );
            CartPoleView {
                obs,
                block: panel(&title, theme),
                color: theme.color,
            }
            .render(area, buf);
        }
        StepView::Pendulum => {
            let (theta, torque) = s
                .pendulum_frame(app.run.frame)
                .unwrap_or((std::f64::consts::PI, 0.0));
            let title = tr!(
                "the latest episode, step {}/{}",
                "最近一个回合，时间步 {}/{}",
                app.run.frame,
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
        StepView::TrustRegion => draw_probe(app, theme, area, buf),
        StepView::Lab => {
            let Some(experiment) = app.current_step().and_then(|s| s.lab) else {
                return;
            };
            let guess = match app.current_step().and_then(|s| s.predict) {
                None => Guess::None,
                Some(o) if app.asking_prediction() => Guess::Asking(o),
                Some(o) => app
                    .prediction(experiment)
                    .map_or(Guess::Ahead(o), |c| Guess::Made(o, c)),
            };
            app.lab
                .render(experiment, &app.lab_base(), guess, theme, area, buf);
        }
        StepView::ClipChart => {
            let trace = s.cartpole_update().map(|c| &c.trace);
            ClipChart {
                eps: app.run.cartpole().eps,
                epoch: trace.and_then(|t| t.epochs.last()),
                advantage: trace.map_or(&[], |t| t.advantage.as_slice()),
                block: panel(t("L^CLIP against the ratio", "L^CLIP 随比率的变化"), theme),
                theme,
            }
            .render(area, buf);
        }
    }
}

/// The trust-region probe of the latest batch as its table: step length, KL, the surrogate's
/// predicted change of J_γ against the measured one, and the score change.
fn draw_probe(app: &App, theme: Theme, area: Rect, buf: &mut Buffer) {
    use crate::tui::app::Probe;
    let block = panel(
        t(
            "trust region: the surrogate's prediction against the truth",
            "信任区域：替代目标的预测与真实变化",
        ),
        theme,
    );
    let inner = block.inner(area);
    block.render(area, buf);
    let lines: Vec<Line> = match &app.probe {
        Probe::Done(episodes, Ok(probe)) => {
            let mut lines = vec![Line::styled(
                tr!(
                    "the batch after episode {episodes}, stepped along its surrogate gradient; {} fresh episodes per row",
                    "第 {episodes} 个回合之后的这批数据，沿替代目标的梯度迈步；每行用 {} 个新回合",
                    probe.episodes
                ),
                theme.dim(),
            )];
            lines.extend(
                crate::notebook::trust_region_table(probe)
                    .into_iter()
                    .map(Line::raw),
            );
            lines
        }
        Probe::Done(_, Err(e)) => vec![Line::styled(e.clone(), theme.dim())],
        Probe::Measuring(episodes) => vec![Line::styled(
            tr!(
                "measuring the batch after episode {episodes} …",
                "正在测量第 {episodes} 个回合之后的这批数据……"
            ),
            theme.dim(),
        )],
        Probe::None => vec![Line::styled(
            t(
                "appears after the first episode: press e (one episode) or t (train).",
                "在第一个回合之后出现：按 e 训练一个回合，或按 t 连续训练。",
            ),
            theme.dim(),
        )],
    };
    let columns = usize::from(inner.width);
    let lines: Vec<Line> = lines
        .into_iter()
        .map(|l| text::cut(l, columns, Span::styled("…", theme.dim())))
        .collect();
    Paragraph::new(lines).render(inner, buf);
}

fn draw_footer(theme: Theme, status: &[String], area: Rect, buf: &mut Buffer) {
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
    // stepping, training, help and quit always show (at 80×24 in Chinese `q 退出` was once
    // cut to `q`).
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
    let mut lines = vec![Line::from(spans)];
    lines.extend(status.iter().map(|l| Line::styled(l.clone(), theme.dim())));
    Paragraph::new(lines).render(area, buf);
}

/// The status rows under the key bar, `width` columns wide: the latest message first (what
/// the learner just did, or a warning), whole, on two rows when it needs them; then the open
/// exercise and the counts, as many as fit on the row.
#[must_use]
pub fn status_lines(app: &App, width: usize) -> Vec<String> {
    let mut parts = Vec::new();
    let exercise = app.exercise_names();
    if !exercise.is_empty() {
        let state = if app.exercise_done() {
            t("done", "已完成")
        } else {
            t("pending", "未完成")
        };
        parts.push(tr!(
            "exercise {}: {state} (g grade, h hint)",
            "练习 {}：{state}（g 评分，h 提示）",
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
    let message = app.status.text();
    let room = width.saturating_sub(1).max(1);
    let mut rows: Vec<String> = if message.is_empty() {
        vec![String::new()]
    } else {
        let wrapped = text::wrap(
            [Line::raw(message.to_string())],
            u16::try_from(room).unwrap_or(u16::MAX),
        );
        let mut rows: Vec<String> = wrapped
            .iter()
            .map(|l| l.spans.iter().map(|s| s.content.as_ref()).collect())
            .collect();
        if rows.len() > 2 {
            // Two rows at most: the rest of a very long message ends in `…`.
            rows.truncate(2);
            let last = text::truncate(rows[1].trim_end(), room.saturating_sub(1));
            rows[1] = format!("{last}…");
        }
        rows
    };
    let sep = " · ";
    for part in parts {
        let Some(last) = rows.last_mut() else { break };
        let joined = if last.is_empty() {
            part
        } else {
            format!("{}{sep}{part}", last.trim_end())
        };
        if text::width(&joined) > room {
            continue;
        }
        *last = joined;
    }
    rows.into_iter().map(|r| format!(" {r}")).collect()
}
