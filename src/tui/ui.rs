//! Drawing only: the app's state to a frame. Nothing here changes state.

use ratatui::buffer::Buffer;
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, Borders, Clear, Gauge, Paragraph, Widget, Wrap};

use super::app::{App, Overlay, TrainState};
use super::keys::HELP;
use super::sandbox::Field;
use super::theme::Theme;
use super::widgets::{
    cartpole::CartPoleView, clip::ClipChart, lab::LabPanel, pendulum::PendulumView,
    plot::ReturnPlot, tensors, text,
};
use crate::lesson::{Environment, TensorView, VIEWS};

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
            let msg = format!(
                "The terminal is {}×{}; ppo-tutor needs at least {}×{}. Enlarge it, or press q to quit.",
                area.width, area.height, MIN_SIZE.0, MIN_SIZE.1
            );
            Paragraph::new(msg)
                .wrap(Wrap { trim: true })
                .render(area, buf);
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
    let title = app.current_lesson().map_or(String::new(), |l| {
        format!(
            " {:02}/{:02} {} · step {}/{}",
            l.order,
            app.course.lessons.len(),
            l.title,
            app.step + 1,
            l.steps.len()
        )
    });
    let train = match app.train {
        TrainState::Running => "training",
        TrainState::Paused => "paused",
        TrainState::Finished => "finished",
    };
    let last = app.snapshot.returns.last().map_or(String::new(), |r| {
        format!(" · last return {}", super::app::return_text(*r))
    });
    let right = format!(
        "episode {}{last} · {train} · {pos}/{total} ",
        app.snapshot.episodes
    );
    let pad = (area.width as usize).saturating_sub(title.chars().count() + right.chars().count());
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
    Paragraph::new(text::markdown(&body, theme))
        .block(panel(&step.title, theme))
        .wrap(Wrap { trim: false })
        .scroll((app.text_scroll, 0))
        .render(left, buf);
    let env = app
        .current_lesson()
        .map_or_else(Default::default, |l| l.env);
    let code = code_lines(step, env, theme);
    let code_height = (code.len() as u16 + 2).min(right.height / 3).max(5);
    let [code_area, live] =
        Layout::vertical([Constraint::Length(code_height), Constraint::Min(0)]).areas(right);
    Paragraph::new(code)
        .block(panel("the code that runs", theme))
        .render(code_area, buf);
    draw_live(app, theme, step, live, buf);
}

fn code_lines(
    step: &crate::lesson::Step,
    env: crate::lesson::Environment,
    theme: Theme,
) -> Vec<Line<'static>> {
    let mut lines = Vec::new();
    if !step.python.is_empty() {
        lines.push(Line::styled(
            format!("# the {} (PyTorch)", env.python_source()),
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
        lines.push(Line::styled("(no code in this step)", theme.dim()));
    }
    lines
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
        let block = panel("live values", theme);
        let inner = block.inner(tensor_area);
        block.render(tensor_area, buf);
        let lines = if shown.is_empty() && !names.is_empty() {
            vec![Line::styled(
                format!(
                    "{} appear after the first episode: press e (one episode) or t (train).",
                    names.join(", ")
                ),
                theme.dim(),
            )]
        } else {
            tensors::lines(&shown, app.tensor_scroll, inner.height as usize, theme)
        };
        Paragraph::new(lines).render(inner, buf);
    }
}

fn draw_view(app: &App, theme: Theme, view: &str, area: Rect, buf: &mut Buffer) {
    let s = &app.snapshot;
    match view {
        "plot" => ReturnPlot {
            returns: &s.returns,
            average: &s.moving_average,
            previous: app
                .previous
                .as_ref()
                .map(|p| (p.label.as_str(), p.values.as_slice())),
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
                    Environment::CartPole => format!("PPO on {}", app.config.env_id),
                    Environment::Pendulum => format!("PPO on {}", Environment::Pendulum.as_str()),
                },
                theme,
            ),
            theme,
        }
        .render(area, buf),
        "cartpole" => {
            let obs = s.observation(app.frame).unwrap_or([0.0; 4]);
            let title = format!(
                "the latest episode, step {}/{}",
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
            let title = format!(
                "the latest episode, step {}/{}",
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
                block: panel(&format!("clip lab: {}", experiment.name()), theme),
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
                block: panel("L^CLIP against the ratio", theme),
                theme,
            }
            .render(area, buf);
        }
    }
}

fn draw_footer(app: &App, theme: Theme, area: Rect, buf: &mut Buffer) {
    let keys = [
        ("←/→", "step"),
        ("l", "lessons"),
        ("t", "train/pause"),
        ("e", "one episode"),
        ("r", "reset"),
        ("s", "sandbox"),
        ("?", "help"),
        ("q", "quit"),
    ];
    let mut spans = Vec::new();
    for (k, what) in keys {
        spans.push(Span::styled(format!(" {k}"), theme.key()));
        spans.push(Span::raw(format!(" {what} ")));
    }
    // What stays first (the open exercise, the counts), the latest message last: a long
    // message is cut at the right edge, the counts never are.
    let mut parts = Vec::new();
    let exercise = app.exercise_names();
    if !exercise.is_empty() {
        let state = if app.exercise_done() {
            "done"
        } else {
            "pending"
        };
        parts.push(format!(
            "exercise {}: {state} (g grade, h hint)",
            exercise.join(", ")
        ));
    }
    let (answered, right, questions) = app.quiz_score();
    parts.push(format!(
        "lessons done {}/{}",
        app.progress.lessons_done.len(),
        app.course.lessons.len()
    ));
    parts.push(format!(
        "exercises done {}/{}",
        app.progress.exercises_done.len(),
        crate::grade::exercise_names().len()
    ));
    parts.push(format!(
        "quiz {right}/{questions} right ({answered} answered)"
    ));
    if !app.status.is_empty() {
        parts.push(app.status.clone());
    }
    let status = format!(" {}", parts.join(" · "));
    Paragraph::new(vec![Line::from(spans), Line::styled(status, theme.dim())]).render(area, buf);
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
    let rect = centered(area, 72, HELP.len() as u16 + 4);
    Clear.render(rect, buf);
    let lines: Vec<Line> = HELP
        .iter()
        .map(|(k, what)| {
            Line::from(vec![
                Span::styled(format!(" {k:<16}"), theme.key()),
                Span::raw(*what),
            ])
        })
        .collect();
    Paragraph::new(lines)
        .block(panel("keys (Esc closes)", theme))
        .render(rect, buf);
}

fn draw_lessons(app: &App, theme: Theme, selected: usize, area: Rect, buf: &mut Buffer) {
    let rect = centered(area, 76, app.course.lessons.len() as u16 + 4);
    Clear.render(rect, buf);
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
            if i == selected {
                Line::styled(text, theme.highlight())
            } else {
                Line::raw(text)
            }
        })
        .collect();
    Paragraph::new(lines)
        .block(panel("lessons (↑↓, Enter opens, Esc closes)", theme))
        .render(rect, buf);
}

fn draw_sandbox(app: &App, theme: Theme, area: Rect, buf: &mut Buffer) {
    let rect = centered(area, 64, Field::ALL.len() as u16 + 7);
    Clear.render(rect, buf);
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
        " ↑↓ choose · +/− or ←/→ change · Enter retrains",
        theme.dim(),
    ));
    lines.push(Line::styled(
        " (the current curve stays on the plot for comparison)",
        theme.dim(),
    ));
    Paragraph::new(lines)
        .block(panel("sandbox", theme))
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
    Clear.render(rect, buf);
    let names = app.exercise_names();
    let file_of = |name: &str| crate::grade::starter(name).map_or(String::new(), |(path, _)| path);
    let mut files: Vec<String> = names.iter().map(|n| file_of(n)).collect();
    files.dedup();
    let heading = match files.as_slice() {
        [file] => format!(" Write the function(s) in {file}"),
        _ => " Write each function in its file".to_string(),
    };
    let mut lines = vec![
        Line::styled(heading, theme.title()),
        Line::styled(
            " g grade (saving the file regrades too) · h next hint · ↑↓ scroll · Esc close",
            theme.dim(),
        ),
        Line::raw(""),
    ];
    for name in &names {
        let done = app.progress.exercises_done.contains(name);
        let mark = if done { "✓ done" } else { "· pending" };
        let mut line = vec![
            Span::styled(format!(" {mark:<10}"), theme.key()),
            Span::raw(name.clone()),
        ];
        if files.len() > 1 {
            let width = names.iter().map(String::len).max().unwrap_or(0);
            let pad = " ".repeat(width - name.len() + 2);
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
            format!(" Hints ({}/{})", app.exercise.hints_shown, hints.len()),
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
                " grading… (the first time compiles, a few seconds; for the candle exercise, \
                 a few minutes)"
            } else {
                " grading… (the first time compiles, a few seconds)"
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
            lines.push(Line::styled(" The reference solution", theme.title()));
            lines.extend(code.lines().map(|l| Line::raw(format!(" {l}"))));
        }
    }
    let [text, gauge] = Layout::vertical([Constraint::Min(0), Constraint::Length(1)])
        .areas(rect.inner(ratatui::layout::Margin::new(1, 1)));
    panel("exercise", theme).render(rect, buf);
    Paragraph::new(lines)
        .wrap(Wrap { trim: false })
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
        .label(format!("exercises done {done}/{total}"))
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
            format!(
                " Check your understanding: question {}/{}",
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
            format!(" a–{} answer", letter_of(choices.len().saturating_sub(1)))
        }
        QuestionKind::Predict { tolerance, .. } => {
            lines.push(Line::from(vec![
                Span::styled(" your prediction: ", theme.key()),
                Span::raw(format!("{}▏", app.quiz.input)),
                Span::styled(format!("  (within ±{tolerance} counts)"), theme.dim()),
            ]));
            if app.snapshot.trace.is_none() {
                lines.push(Line::styled(
                    " the live value comes from the agent: train an episode first (e or t)",
                    theme.dim(),
                ));
            }
            " type a number, Enter reveals the live value".to_string()
        }
    };
    if let Some(verdict) = &app.quiz.verdict {
        lines.push(Line::raw(""));
        lines.extend(verdict.text.lines().map(|l| Line::raw(format!(" {l}"))));
    }
    lines.push(Line::raw(""));
    lines.push(Line::styled(
        format!("{keys} · n next · p previous · Esc back to the lesson"),
        theme.dim(),
    ));
    // As tall as the wrapped text needs, at most the screen.
    let inner = usize::from(width.saturating_sub(2)).max(1);
    let rows: usize = lines.iter().map(|l| l.width().max(1).div_ceil(inner)).sum();
    // (+ 3: word wrapping can take a row more than the estimate here and there)
    let height = u16::try_from(rows + 5).unwrap_or(u16::MAX);
    let rect = centered(area, width, height.min(area.height.saturating_sub(4)));
    Clear.render(rect, buf);
    panel("quiz", theme).render(rect, buf);
    Paragraph::new(lines)
        .wrap(Wrap { trim: false })
        .render(rect.inner(ratatui::layout::Margin::new(1, 1)), buf);
}
