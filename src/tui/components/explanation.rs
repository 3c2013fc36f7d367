//! The step's explanation (the left pane): its text, scrolled with ↑/↓ (or j/k), its
//! details blocks folded or opened with `d`.

use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::widgets::Widget;

use super::{Component, Ctx, Reply, Scroll, panel};
use crate::lesson::Step;
use crate::lesson::face::Face;
use crate::tui::keys::Action;
use crate::tui::theme::Theme;
use crate::tui::widgets::text;

/// The explanation's scroll and whether its details blocks are open.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Explanation {
    /// Whether the details blocks show opened (`d`), for every step until closed.
    pub details_open: bool,
    scroll: Scroll,
}

impl Explanation {
    /// The first line shown.
    #[must_use]
    pub fn scroll(&self) -> u16 {
        self.scroll.offset()
    }

    /// Another step opened: back to its top.
    pub fn top(&mut self) {
        self.scroll.top();
    }

    fn draw(&self, step: &Step, theme: Theme, area: Rect, buf: &mut Buffer) {
        let body = crate::lesson::details::fold(&step.text(Face::Terminal), self.details_open);
        let columns = usize::from(area.width.saturating_sub(2));
        let lines = text::wrap(
            text::markdown(&body, theme, columns),
            area.width.saturating_sub(2),
        );
        let block = panel(&step.title, theme);
        let inner = block.inner(area);
        block.render(area, buf);
        self.scroll.render(lines, theme, inner, buf);
    }
}

impl Component for Explanation {
    /// Scrolling and `d`; every other key is the lesson view's.
    fn handle(&mut self, action: Action, _: &Ctx<'_>) -> Reply {
        match action {
            Action::ScrollDown => self.scroll.down(),
            Action::ScrollUp => self.scroll.up(),
            Action::Details => self.details_open = !self.details_open,
            other => return Reply::Pass(other),
        }
        Reply::Stay
    }

    fn render(&self, ctx: &Ctx<'_>, theme: Theme, area: Rect, buf: &mut Buffer) {
        if let Some(step) = ctx.step {
            self.draw(step, theme, area, buf);
        }
    }
}
