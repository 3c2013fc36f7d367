//! The lesson list overlay (`l`).

use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::text::Line;
use ratatui::widgets::{Paragraph, Widget};

use super::{Component, Ctx, Reply, centered, clear, panel};
use crate::i18n::t;
use crate::tui::keys::Action;
use crate::tui::theme::Theme;
use crate::tui::widgets::text;

/// The lesson list, with the highlighted row.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct LessonList {
    /// The highlighted lesson (an index into the course).
    pub selected: usize,
}

impl LessonList {
    /// Opens the list on lesson `current`.
    pub fn open(&mut self, current: usize) {
        self.selected = current;
    }
}

impl Component for LessonList {
    fn handle(&mut self, action: Action, ctx: &Ctx<'_>) -> Reply {
        let n = ctx.course.lessons.len();
        match action {
            Action::Quit => return Reply::Quit,
            Action::Up | Action::ScrollUp => self.selected = self.selected.saturating_sub(1),
            Action::Down | Action::ScrollDown => {
                self.selected = (self.selected + 1).min(n.saturating_sub(1));
            }
            Action::Enter => return Reply::Open(self.selected),
            Action::Lessons | Action::Back => return Reply::Close,
            _ => {}
        }
        Reply::Stay
    }

    fn render(&self, ctx: &Ctx<'_>, theme: Theme, area: Rect, buf: &mut Buffer) {
        let lessons = &ctx.course.lessons;
        let rect = centered(
            area,
            76,
            u16::try_from(lessons.len() + 4).unwrap_or(u16::MAX),
        );
        clear(rect, buf);
        // A terminal too short for every lesson keeps the highlighted one in view.
        let rows = usize::from(rect.height.saturating_sub(2));
        let first = (self.selected + 1).saturating_sub(rows);
        let lines: Vec<Line> = lessons
            .iter()
            .enumerate()
            .skip(first)
            .take(rows)
            .map(|(i, l)| {
                let mark = if ctx.progress.lessons_done.contains(&l.id) {
                    "✓"
                } else {
                    " "
                };
                let text = format!(" {mark} {:02} {}", l.order, l.title);
                // Cut at the panel's edge by columns (a Chinese title is twice as wide).
                let text = text::truncate(&text, usize::from(rect.width.saturating_sub(2)));
                if i == self.selected {
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
}
