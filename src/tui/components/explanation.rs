//! The step's explanation (the left pane): its text, scrolled with ↑/↓ (or j/k), its
//! details blocks opened one at a time with `d` (and folded again once all are open). Which
//! blocks are open is kept per step: opening one on a step opens nothing on another.

use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::widgets::Widget;

use super::{Component, Ctx, Reply, Scroll, panel};
use crate::lesson::Step;
use crate::lesson::face::Face;
use crate::tui::keys::Action;
use crate::tui::theme::Theme;
use crate::tui::widgets::text;

/// The explanation's scroll and which details blocks are open.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Explanation {
    /// How many of each step's details blocks are open (its first ones, in order), by
    /// lesson id and step index; a step not listed has them all folded.
    opened: std::collections::HashMap<(String, usize), usize>,
    scroll: Scroll,
}

/// A step's place in its lesson: the key of [`Explanation::opened`].
fn key(ctx: &Ctx<'_>) -> Option<(String, usize)> {
    let (lesson, step) = (ctx.lesson?, ctx.step?);
    let index = lesson.steps.iter().position(|s| std::ptr::eq(s, step))?;
    Some((lesson.id.clone(), index))
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

    /// How many of the open step's details blocks are open.
    #[must_use]
    pub fn opened(&self, ctx: &Ctx<'_>) -> usize {
        key(ctx)
            .and_then(|k| self.opened.get(&k).copied())
            .unwrap_or(0)
    }

    /// `d`: opens the step's next folded block, or folds them all once all are open.
    fn details(&mut self, ctx: &Ctx<'_>) -> Reply {
        let (Some(key), Some(step)) = (key(ctx), ctx.step) else {
            return Reply::Stay;
        };
        let total = crate::lesson::details::count(&step.text(Face::Terminal));
        if total == 0 {
            return Reply::Say(
                crate::i18n::t("this step has no details to open", "本节没有可展开的细节")
                    .to_string(),
            );
        }
        let opened = self.opened.get(&key).copied().unwrap_or(0);
        if opened >= total {
            self.opened.remove(&key);
        } else {
            self.opened.insert(key, opened + 1);
        }
        Reply::Stay
    }

    fn draw(
        &self,
        step: &Step,
        opened: usize,
        results_open: bool,
        theme: Theme,
        area: Rect,
        buf: &mut Buffer,
    ) {
        let text = match step.parts(Face::Terminal) {
            (before, Some(_)) if !results_open => format!(
                "{before}\n{}\n",
                crate::i18n::t(
                    "*What the seeds showed appears here once you have made your prediction: press x.*",
                    "*做出预测后，这里会显示随机种子的结果：按 x。*",
                )
            ),
            _ => step.text(Face::Terminal),
        };
        let body = crate::lesson::details::fold_first(&text, opened);
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
    fn handle(&mut self, action: Action, ctx: &Ctx<'_>) -> Reply {
        match action {
            Action::ScrollDown => self.scroll.down(),
            Action::ScrollUp => self.scroll.up(),
            Action::Details => return self.details(ctx),
            other => return Reply::Pass(other),
        }
        Reply::Stay
    }

    fn render(&self, ctx: &Ctx<'_>, theme: Theme, area: Rect, buf: &mut Buffer) {
        if let Some(step) = ctx.step {
            self.draw(step, self.opened(ctx), ctx.results_open, theme, area, buf);
        }
    }
}
