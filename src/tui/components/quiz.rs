//! The quiz overlay, after a lesson's last step: one question at a time, a choice (a–d) or
//! a prediction of a live value, its verdict and each choice's explanation.
//!
//! A question that shows numbers of the run, or is graded against it, keeps the snapshot it
//! first had them all in: the run may train on while the learner works the answer out, and
//! the numbers on screen and the answer they lead to stay the ones of that snapshot.

use ratatui::buffer::Buffer;
use ratatui::layout::{Constraint, Layout, Margin, Rect};
use ratatui::text::{Line, Span};
use ratatui::widgets::{Paragraph, Widget};

use super::{Component, Ctx, Reply, Scroll, centered, clear, panel};
use crate::i18n::t;
use crate::lesson::quiz::{Answer, Question, QuestionKind, Verdict, letter_index, letter_of};
use crate::lesson::{Progress, Snapshot};
use crate::tr;
use crate::tui::keys::Action;
use crate::tui::theme::Theme;
use crate::tui::widgets::text;

/// The open question, the answer being typed, and the verdict once given.
#[derive(Debug, Clone, Default)]
pub struct Quiz {
    question: usize,
    /// The prediction typed so far (digits, `.`, `-`).
    pub input: String,
    /// The verdict on the latest answer (or why it could not be graded yet).
    pub verdict: Option<Verdict>,
    /// The score already held the first answer to this question when this one was given:
    /// whether that first answer was right (this one does not count).
    first: Option<bool>,
    scroll: Scroll,
    /// The snapshot the open question shows and grades against, once it had every number
    /// the question needs (`None` before, and for a question that does not use the run).
    pinned: Option<Box<Snapshot>>,
    /// The latest answer given before this question was opened (kept in the progress), and
    /// whether the first answer was right: shown until the learner answers again.
    earlier: Option<(String, Option<bool>)>,
}

impl Quiz {
    /// The open question (from 0).
    #[must_use]
    pub fn question(&self) -> usize {
        self.question
    }

    /// Opens question `i` of `ctx`'s lesson with nothing typed, and says how to answer it.
    /// A question answered before shows that answer: a fixed choice with its verdict and
    /// explanations, a prediction or a choice the run decides as a line (its verdict was
    /// about another run's numbers).
    pub fn open(&mut self, i: usize, ctx: &Ctx<'_>) -> String {
        *self = Self {
            question: i,
            ..Self::default()
        };
        let question = ctx.lesson.and_then(|l| l.quiz.get(i));
        self.offer(question, ctx.snapshot);
        if let (Some(lesson), Some(question)) = (ctx.lesson, question)
            && let Some(answer) = ctx.progress.answer(&lesson.id, i + 1)
        {
            let key = Progress::quiz_key(&lesson.id, i + 1);
            let first = ctx.progress.quiz.get(&key).copied();
            let letter = match &question.kind {
                QuestionKind::Choice {
                    choices,
                    answer: Answer::Letter(_),
                    ..
                } => choices.iter().position(|c| c == answer).map(letter_of),
                _ => None,
            };
            match letter {
                Some(letter) => {
                    self.verdict = Some(question.choose(letter, ctx.snapshot));
                    self.first = first;
                }
                None => self.earlier = Some((answer.to_string(), first)),
            }
        }
        let total = ctx.lesson.map_or(0, |l| l.quiz.len());
        let how = match ctx.lesson.and_then(|l| l.quiz.get(i)).map(|q| &q.kind) {
            Some(QuestionKind::Predict { .. }) => t("type a number, Enter", "输入一个数，按 Enter"),
            _ => t("a–d answers", "按 a–d 作答"),
        };
        tr!(
            "check your understanding: question {}/{total} ({how})",
            "检验一下：第 {}/{total} 题（{how}）",
            i + 1
        )
    }

    /// Forgets what was typed and the verdict shown (the language changed: they were
    /// written in the old one); the question keeps its snapshot.
    pub fn clear_answer(&mut self) {
        *self = Self {
            question: self.question,
            pinned: self.pinned.take(),
            ..Self::default()
        };
    }

    /// Keeps `snapshot` for the open `question` if it uses the run, has not kept one yet,
    /// and `snapshot` has every number it needs (the app offers each new snapshot).
    pub fn offer(&mut self, question: Option<&Question>, snapshot: &Snapshot) {
        if self.pinned.is_none()
            && question.is_some_and(|q| q.uses_the_run() && q.ready_in(snapshot))
        {
            self.pinned = Some(Box::new(snapshot.clone()));
        }
    }

    /// The snapshot the open question shows and grades against: the one it kept, else the
    /// run's latest.
    fn snapshot<'a>(&'a self, ctx: &Ctx<'a>) -> &'a Snapshot {
        self.pinned.as_deref().unwrap_or(ctx.snapshot)
    }

    /// Whether the open question has been answered (its verdict is shown).
    #[must_use]
    pub fn answered(&self) -> bool {
        self.verdict.as_ref().is_some_and(|v| v.answered)
    }

    /// Shows `verdict` on `answer` (the choice's text, or the number typed); a real answer
    /// goes to the app to be recorded (the first counts toward the score).
    fn give(&mut self, verdict: Verdict, answer: String, ctx: &Ctx<'_>) -> Reply {
        self.scroll.top();
        self.earlier = None;
        let reply = if verdict.answered {
            let id = ctx.lesson.map_or("", |l| l.id.as_str());
            let key = Progress::quiz_key(id, self.question + 1);
            self.first = ctx.progress.quiz.get(&key).copied();
            Reply::Answered(self.question, verdict.clone(), answer)
        } else {
            self.first = None;
            Reply::Say(verdict.text.lines().next().unwrap_or_default().to_string())
        };
        self.verdict = Some(verdict);
        reply
    }

    /// The question's lines wrapped to `columns`, each paragraph's later lines indented
    /// under its first line's text (a choice's under its words, not under its letter).
    fn lines(
        &self,
        ctx: &Ctx<'_>,
        question: &Question,
        theme: Theme,
        columns: u16,
    ) -> Vec<Line<'static>> {
        let total = ctx.lesson.map_or(0, |l| l.quiz.len());
        let mut lines = hanging(
            Span::raw(" "),
            Line::styled(
                tr!(
                    "Check your understanding: question {}/{}",
                    "检验一下：第 {}/{} 题",
                    self.question + 1,
                    total
                ),
                theme.title(),
            ),
            columns,
        );
        lines.push(Line::raw(""));
        lines.extend(hanging(
            Span::raw(" "),
            Line::raw(question.prompt_in(self.snapshot(ctx))),
            columns,
        ));
        lines.push(Line::raw(""));
        match &question.kind {
            QuestionKind::Choice { choices, .. } => {
                for (k, choice) in choices.iter().enumerate() {
                    lines.extend(hanging(
                        Span::styled(format!(" {}) ", letter_of(k)), theme.key()),
                        Line::raw(choice.clone()),
                        columns,
                    ));
                }
            }
            QuestionKind::Predict { tolerance, .. } => {
                let within = if *tolerance == 0.0 {
                    t(
                        "  (only the exact value counts)",
                        "  （只有完全相等才算对）",
                    )
                    .to_string()
                } else {
                    tr!(
                        "  (within ±{tolerance} counts)",
                        "  （误差在 ±{tolerance} 以内算对）"
                    )
                };
                lines.extend(text::wrap(
                    [Line::from(vec![
                        Span::styled(t(" your prediction: ", " 你的预测："), theme.key()),
                        Span::raw(format!("{}▏", self.input)),
                        Span::styled(within, theme.dim()),
                    ])],
                    columns,
                ));
            }
        }
        if question.uses_the_run() && !question.ready_in(self.snapshot(ctx)) {
            lines.extend(hanging(
                Span::raw(" "),
                Line::styled(
                    t(
                        "the live value comes from the agent: train an episode first (e or t)",
                        "实时数值来自智能体：先训练一个回合（e 或 t）",
                    ),
                    theme.dim(),
                ),
                columns,
            ));
        }
        if let Some((answer, first)) = &self.earlier {
            let score = match first {
                Some(true) => t(" (your first answer was right)", "（第一次作答答对了）"),
                Some(false) => t(" (your first answer was not right)", "（第一次作答没答对）"),
                None => "",
            };
            lines.push(Line::raw(""));
            lines.extend(hanging(
                Span::raw(" "),
                Line::styled(
                    tr!(
                        "Your answer last time: {answer}{score}. Answer again to see the verdict on this run's numbers.",
                        "你上次的回答：{answer}{score}。再答一次，看按这次运行的数字给出的判定。"
                    ),
                    theme.dim(),
                ),
                columns,
            ));
        }
        if let Some(verdict) = &self.verdict {
            lines.push(Line::raw(""));
            if let Some(first) = self.first {
                lines.extend(hanging(Span::raw(" "), Line::styled(
                    if first {
                        t(
                            "Only your first answer counts toward the score (it was right).",
                            "只有第一次作答计入成绩（第一次答对了）。",
                        )
                    } else {
                        t(
                            "Only your first answer counts toward the score (it was not right).",
                            "只有第一次作答计入成绩（第一次没答对）。",
                        )
                    },
                    theme.dim(),
                ), columns));
            }
            for l in verdict.text.lines() {
                lines.extend(hanging(Span::raw(" "), Line::raw(l.to_string()), columns));
            }
        }
        lines
    }
}

impl Component for Quiz {
    fn handle(&mut self, action: Action, ctx: &Ctx<'_>) -> Reply {
        let i = self.question;
        let total = ctx.lesson.map_or(0, |l| l.quiz.len());
        let Some(question) = ctx.lesson.and_then(|l| l.quiz.get(i)) else {
            return Reply::Close;
        };
        self.offer(Some(question), ctx.snapshot);
        match action {
            Action::Type(c) => match &question.kind {
                QuestionKind::Choice { choices, .. } => {
                    let last = letter_of(choices.len().saturating_sub(1));
                    if c.is_ascii_lowercase() && c <= last {
                        let verdict = question.choose(c, self.snapshot(ctx));
                        let text = letter_index(&c.to_string())
                            .and_then(|k| choices.get(k))
                            .cloned()
                            .unwrap_or_default();
                        return self.give(verdict, text, ctx);
                    }
                    if c.is_ascii_lowercase() {
                        return Reply::Say(tr!(
                            "{c} is not one of the choices: answer with a–{last}",
                            "{c} 不是选项之一：请按 a–{last} 作答"
                        ));
                    }
                }
                QuestionKind::Predict { .. } => {
                    if !self.answered()
                        && (c.is_ascii_digit() || c == '.' || c == '-')
                        && self.input.len() < 16
                    {
                        self.input.push(c);
                    }
                }
            },
            Action::Erase => {
                if !self.answered() {
                    self.input.pop();
                }
            }
            Action::Enter => {
                if matches!(question.kind, QuestionKind::Predict { .. }) && !self.answered() {
                    return match self.input.parse::<f64>() {
                        Ok(v) => {
                            let verdict = question.predict(v, self.snapshot(ctx));
                            let typed = self.input.clone();
                            self.give(verdict, typed, ctx)
                        }
                        Err(_) => Reply::Say(
                            t(
                                "type a number first (digits, '.', '-')",
                                "先输入一个数（数字、'.'、'-'）",
                            )
                            .into(),
                        ),
                    };
                }
            }
            Action::Next => {
                return if i + 1 < total {
                    Reply::Say(self.open(i + 1, ctx))
                } else {
                    Reply::Finished
                };
            }
            Action::Prev => {
                return if i > 0 {
                    Reply::Say(self.open(i - 1, ctx))
                } else {
                    Reply::Close
                };
            }
            Action::Back => return Reply::Close,
            other if self.scroll.key(other) => {}
            other => return Reply::Pass(other),
        }
        Reply::Stay
    }

    fn render(&self, ctx: &Ctx<'_>, theme: Theme, area: Rect, buf: &mut Buffer) {
        let Some(question) = ctx.lesson.and_then(|l| l.quiz.get(self.question)) else {
            return;
        };
        let width = area.width.saturating_sub(8).min(100);
        let columns = width.saturating_sub(2);
        let answer = match &question.kind {
            QuestionKind::Choice { choices, .. } => tr!(
                " a–{} answer",
                " a–{} 作答",
                letter_of(choices.len().saturating_sub(1))
            ),
            QuestionKind::Predict { .. } => t(
                " type a number, Enter reveals the live value",
                " 输入一个数，按 Enter 揭晓实时数值",
            )
            .to_string(),
        };
        // The keys stay on the panel's last rows; the question, its choices and the
        // verdict scroll above them, saying when more follows.
        let keys = text::wrap(
            [Line::styled(
                tr!(
                    "{answer} · n next · p previous · Esc back to the lesson",
                    "{answer} · n 下一题 · p 上一题 · Esc 回到课文"
                ),
                theme.dim(),
            )],
            columns,
        );
        let body = self.lines(ctx, question, theme, columns);
        // As tall as the wrapped text needs, at most the screen less two rows each side.
        let height = u16::try_from(body.len() + 1 + keys.len() + 2).unwrap_or(u16::MAX);
        let rect = centered(area, width, height.min(area.height.saturating_sub(4)));
        clear(rect, buf);
        panel(t("quiz", "小测验"), theme).render(rect, buf);
        let inner = rect.inner(Margin::new(1, 1));
        let keys_height = u16::try_from(keys.len()).unwrap_or(u16::MAX);
        let [text_area, _, keys_area] = Layout::vertical([
            Constraint::Min(0),
            Constraint::Length(1),
            Constraint::Length(keys_height),
        ])
        .areas(inner);
        self.scroll.render(body, theme, text_area, buf);
        Paragraph::new(keys).render(keys_area, buf);
    }
}

/// `line` wrapped after `prefix` ([`text::hanging`]).
fn hanging(prefix: Span<'static>, line: Line<'static>, columns: u16) -> Vec<Line<'static>> {
    text::hanging(vec![prefix], line, columns)
}
