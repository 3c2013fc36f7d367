//! The key map overlay (`?`).

use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::text::{Line, Span};
use ratatui::widgets::Widget;

use super::{Component, Ctx, Reply, Scroll, centered, clear, panel};
use crate::i18n::t;
use crate::tui::keys::{Action, help};
use crate::tui::theme::Theme;
use crate::tui::widgets::text;

/// The key map: every key, what it does; it scrolls when the terminal is too short for it.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Help {
    scroll: Scroll,
}

impl Component for Help {
    fn handle(&mut self, action: Action, _: &Ctx<'_>) -> Reply {
        if self.scroll.key(action) {
            return Reply::Stay;
        }
        match action {
            Action::Quit => Reply::Quit,
            Action::Help | Action::Back | Action::Enter => {
                self.scroll.top();
                Reply::Close
            }
            _ => Reply::Stay,
        }
    }

    fn render(&self, _: &Ctx<'_>, theme: Theme, area: Rect, buf: &mut Buffer) {
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
        let block = panel(t("keys (Esc closes)", "按键（Esc 关闭）"), theme);
        let inner = block.inner(rect);
        block.render(rect, buf);
        self.scroll.render(lines, theme, inner, buf);
    }
}
