//! A clip-lab experiment in the app: what it will run, its progress, then its table and one
//! chart per changed setting (its band and mean against the base setting's mean).

use ratatui::buffer::Buffer;
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::text::{Line, Span};
use ratatui::widgets::{Axis, Block, Chart, Dataset, GraphType, Paragraph, Widget};

use super::plot::{draw_chart, points};
use crate::i18n::t as t_;
use crate::ppo::lab::{ArmResult, Experiment, LabResult, Outcome, letters};
use crate::tr;
use crate::tui::theme::Theme;

/// Where an experiment stands in this app session.
#[derive(Debug, Clone, PartialEq)]
pub enum LabState {
    /// Running: episodes finished over all runs, and the total.
    Running {
        /// Episodes finished.
        done: usize,
        /// Episodes in all.
        total: usize,
    },
    /// Finished.
    Done(Box<LabResult>),
    /// Stopped with this message.
    Failed(String),
}

/// Where the learner's prediction of the experiment stands, on a step that asks for one.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Guess {
    /// The step asks for none.
    None,
    /// It asks for one; `x` will ask it.
    Ahead(Outcome),
    /// It is asking now.
    Asking(Outcome),
    /// Made: the chosen arm, or `None` where the learner ran without one.
    Made(Outcome, Option<usize>),
}

/// The panel of one experiment.
pub struct LabPanel<'a> {
    /// Which experiment the step runs.
    pub experiment: Experiment,
    /// Its settings' labels, base first (shown before it runs).
    pub arms: Vec<String>,
    /// Seeds and episodes per run.
    pub seeds: usize,
    /// Episodes per run.
    pub episodes: usize,
    /// Its state, `None` before the learner starts it.
    pub state: Option<&'a LabState>,
    /// The learner's prediction.
    pub guess: Guess,
    /// The surrounding block.
    pub block: Block<'a>,
    /// Styles.
    pub theme: Theme,
}

impl Widget for LabPanel<'_> {
    fn render(self, area: Rect, buf: &mut Buffer) {
        let inner = self.block.inner(area);
        self.block.clone().render(area, buf);
        let t = self.theme;
        let head = Line::styled(self.experiment.question().to_string(), t.title());
        match self.state {
            None | Some(LabState::Running { .. } | LabState::Failed(_)) => {
                let mut lines = vec![head, Line::raw("")];
                lines.push(Line::raw(tr!(
                    "Settings: {}. Each runs {} seeds x {} episodes, on every core.",
                    "设置：{}。每个设置跑 {} 个随机种子 × {} 个回合，用上所有 CPU 核心。",
                    self.arms.join(" | "),
                    self.seeds,
                    self.episodes
                )));
                lines.push(Line::raw(""));
                lines.extend(self.guess_lines_before());
                lines.push(match self.state {
                    Some(LabState::Running { done, total }) => Line::styled(
                        tr!(
                            "running: {done}/{total} episodes ({:.0}%); you can keep reading",
                            "运行中：{done}/{total} 个回合（{:.0}%），可以继续阅读",
                            100.0 * *done as f64 / (*total).max(1) as f64
                        ),
                        t.key(),
                    ),
                    Some(LabState::Failed(m)) => {
                        Line::styled(tr!("stopped: {m}", "已停止：{m}"), t.negative())
                    }
                    _ if matches!(self.guess, Guess::Asking(_)) => Line::from(vec![
                        Span::styled(
                            format!(
                                " a–{} ",
                                letters()
                                    .nth(self.arms.len().saturating_sub(1))
                                    .unwrap_or('a')
                            ),
                            t.key(),
                        ),
                        Span::raw(t_(
                            "your prediction; the run starts",
                            "你的预测；随后开始运行",
                        )),
                        Span::styled("  Esc ", t.key()),
                        Span::raw(t_("run without one", "不预测直接运行")),
                    ]),
                    _ if matches!(self.guess, Guess::Ahead(_)) => Line::from(vec![
                        Span::styled(" x ", t.key()),
                        Span::raw(tr!(
                            "asks your prediction, then runs the experiment (or: ppo-tutor lab {})",
                            "先请你预测，再运行实验（或在终端运行：ppo-tutor lab {}）",
                            self.experiment.name()
                        )),
                    ]),
                    _ => Line::from(vec![
                        Span::styled(" x ", t.key()),
                        Span::raw(tr!(
                            "runs the experiment (or: ppo-tutor lab {})",
                            "运行实验（或在终端运行：ppo-tutor lab {}）",
                            self.experiment.name()
                        )),
                    ]),
                });
                Paragraph::new(super::text::wrap(lines, inner.width)).render(inner, buf);
            }
            Some(LabState::Done(result)) => {
                let table = result.table();
                let comparisons = result.comparisons();
                let graded = super::text::wrap(self.guess_lines_after(result), inner.width);
                let rows = (table.len() + comparisons.len() + graded.len()) as u16 + 1;
                let [top, charts] =
                    Layout::vertical([Constraint::Length(rows), Constraint::Min(0)]).areas(inner);
                let mut lines: Vec<Line> = table
                    .into_iter()
                    .enumerate()
                    .map(|(i, l)| {
                        if i == 0 {
                            Line::styled(l, t.dim())
                        } else {
                            Line::raw(l)
                        }
                    })
                    .collect();
                lines.extend(comparisons.into_iter().enumerate().map(|(i, l)| {
                    if i == 0 {
                        Line::styled(l, t.dim())
                    } else {
                        Line::raw(l)
                    }
                }));
                lines.extend(graded);
                lines.push(Line::styled(
                    tr!(
                        "{} seeds, {} episodes; charts: band and mean of each setting (o: the first)",
                        "{} 个随机种子，{} 个回合；图：每个设置的范围带和平均曲线（o：第一个设置）",
                        result.seeds.len(),
                        result.episodes
                    ),
                    t.dim(),
                ));
                Paragraph::new(lines).render(top, buf);
                if let Some((base, others)) = result.arms.split_first() {
                    let n = others.len().max(1) as u32;
                    let areas = Layout::horizontal(vec![Constraint::Ratio(1, n); others.len()])
                        .split(charts);
                    for (arm, a) in others.iter().zip(areas.iter()) {
                        versus(arm, base, result.episodes, t, *a, buf);
                    }
                }
            }
        }
    }
}

impl LabPanel<'_> {
    /// Before the run: the question and its lettered choices while asking, the choice once
    /// made.
    fn guess_lines_before(&self) -> Vec<Line<'static>> {
        let t = self.theme;
        let letter = |i: usize| letters().nth(i).unwrap_or('?');
        match self.guess {
            Guess::None | Guess::Ahead(_) => Vec::new(),
            Guess::Asking(outcome) => {
                let mut lines = vec![Line::styled(outcome.question(self.seeds), t.title())];
                lines.extend(
                    self.arms
                        .iter()
                        .enumerate()
                        .map(|(i, a)| Line::raw(format!("  {}) {a}", letter(i)))),
                );
                lines.push(Line::raw(""));
                lines
            }
            Guess::Made(_, Some(i)) => vec![
                Line::raw(tr!(
                    "Your prediction: {}) {}; graded when the run ends.",
                    "你的预测：{}) {}；运行结束后评分。",
                    letter(i),
                    self.arms.get(i).map_or("", String::as_str)
                )),
                Line::raw(""),
            ],
            Guess::Made(_, None) => Vec::new(),
        }
    }

    /// After the run: the prediction graded against it.
    fn guess_lines_after(&self, result: &LabResult) -> Vec<Line<'static>> {
        let t = self.theme;
        match self.guess {
            Guess::Made(outcome, Some(i)) => outcome.grade(i, result).map_or_else(Vec::new, |g| {
                g.lines
                    .into_iter()
                    .enumerate()
                    .map(|(k, l)| match (k, g.right) {
                        (0, true) => Line::styled(l, t.positive()),
                        (0, false) => Line::styled(l, t.negative()),
                        _ => Line::styled(l, t.dim()),
                    })
                    .collect()
            }),
            _ => Vec::new(),
        }
    }
}

/// One changed setting against the base: its band (two dim lines), its mean, the base mean.
fn versus(
    arm: &ArmResult,
    base: &ArmResult,
    episodes: usize,
    t: Theme,
    area: Rect,
    buf: &mut Buffer,
) {
    let (low, high, mean, base_mean) = (
        points(&arm.band.low),
        points(&arm.band.high),
        points(&arm.band.mean),
        points(&base.band.mean),
    );
    let top = arm
        .band
        .high
        .iter()
        .chain(&base.band.mean)
        .copied()
        .fold(10.0, f64::max);
    let datasets = vec![
        Dataset::default()
            .marker(super::marker())
            .graph_type(GraphType::Line)
            .style(t.dim())
            .data(&low),
        Dataset::default()
            .marker(super::marker())
            .graph_type(GraphType::Line)
            .style(t.dim())
            .data(&high),
        Dataset::default()
            .marker(super::marker())
            .graph_type(GraphType::Line)
            .style(t.previous())
            .data(&base_mean),
        Dataset::default()
            .marker(super::marker())
            .graph_type(GraphType::Line)
            .style(t.average())
            .data(&mean),
    ];
    let x_top = episodes.max(10) as f64;
    let chart = Chart::new(datasets)
        .x_axis(
            Axis::default()
                .bounds([0.0, x_top])
                .labels([Span::raw("0"), Span::raw(format!("{x_top:.0}"))])
                .style(t.dim()),
        )
        .y_axis(
            Axis::default()
                .bounds([0.0, top])
                .labels([Span::raw("0"), Span::raw(format!("{top:.0}"))])
                .style(t.dim()),
        );
    let block = Block::bordered()
        .border_style(t.border())
        .title(Span::styled(
            tr!(" {} vs {} ", " {} 对比 {} ", arm.label, base.label),
            t.title(),
        ));
    let legend = [
        (base.label.clone(), t.previous()),
        (arm.label.clone(), t.average()),
    ];
    draw_chart(chart, block, &legend, (None, None), t, area, buf);
}
