//! The app's faces. Each overlay (help, lesson list, sandbox, exercise panel, quiz) and the
//! clip lab is one component that owns its state, its keys and its drawing, as in ratatui's
//! component examples. [`App`](super::app::App) routes each action to the one open, applies
//! the [`Reply`] it gets back, and owns what they share: the course, the live run, the
//! progress and the status line.
//!
//! A status message remembers which face set it ([`Owner`]) and goes when that face closes,
//! so "question 4/4" does not follow the learner through the next lessons.

pub mod exercise;
pub mod explanation;
pub mod help;
pub mod lab;
pub mod lessons;
pub mod quiz;
pub mod sandbox;

use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::text::Span;
use ratatui::widgets::{Block, Borders, Clear, Widget};

use super::keys::Action;
use super::theme::Theme;
use super::widgets::text;
use crate::i18n::t;
use crate::lesson::{Course, Lesson, Progress, Snapshot, Step};

/// Something a face has to say on the status line: news, or a warning that stays until
/// it is read (episode updates do not replace it).
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Message {
    /// News: replaced by the next message.
    Info(String),
    /// A warning (without its `warning: ` prefix, which the status line adds).
    Warning(String),
}

/// Which face set a status message.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Owner {
    /// The lesson view, the run, the app itself: stays until replaced.
    #[default]
    App,
    /// The lesson list.
    Lessons,
    /// The sandbox.
    Sandbox,
    /// The exercise panel (grading, hints).
    Exercise,
    /// The quiz.
    Quiz,
}

/// The one-line status message and the face that set it.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Status {
    text: String,
    owner: Owner,
    warning: bool,
}

impl Status {
    /// The message (empty when there is none).
    #[must_use]
    pub fn text(&self) -> &str {
        &self.text
    }

    /// Who set it.
    #[must_use]
    pub fn owner(&self) -> Owner {
        self.owner
    }

    /// Whether the message is a warning, which stays until the learner reads it.
    #[must_use]
    pub fn is_warning(&self) -> bool {
        self.warning
    }

    /// Sets the message on behalf of `owner`.
    pub fn set(&mut self, owner: Owner, text: impl Into<String>) {
        self.text = text.into();
        self.owner = owner;
        self.warning = false;
    }

    /// Sets a warning on behalf of `owner`: `warning: ` (`警告：`) and `text`.
    pub fn warn(&mut self, owner: Owner, text: &str) {
        self.set(owner, format!("{}{text}", t("warning: ", "警告：")));
        self.warning = true;
    }

    /// Says `message` on behalf of `owner`.
    pub fn say(&mut self, owner: Owner, message: Message) {
        match message {
            Message::Info(text) => self.set(owner, text),
            Message::Warning(text) => self.warn(owner, &text),
        }
    }

    /// Clears the message if the face `owner` set it and it is not a warning (the face
    /// closed). The lesson view's messages ([`Owner::App`]) stay.
    pub fn close(&mut self, owner: Owner) {
        if owner != Owner::App && self.owner == owner && !self.is_warning() {
            self.clear();
        }
    }

    /// Clears the message unless it is a warning (the learner moved to another lesson).
    pub fn clear_unless_warning(&mut self) {
        if !self.is_warning() {
            self.clear();
        }
    }

    /// Clears the message.
    pub fn clear(&mut self) {
        self.text.clear();
        self.owner = Owner::App;
        self.warning = false;
    }
}

impl std::fmt::Display for Status {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.text)
    }
}

/// What a face reads of the app to answer a key or to draw itself.
#[derive(Debug, Clone, Copy)]
pub struct Ctx<'a> {
    /// The course, in the current language.
    pub course: &'a Course,
    /// The open lesson.
    pub lesson: Option<&'a Lesson>,
    /// The open step.
    pub step: Option<&'a Step>,
    /// The saved progress.
    pub progress: &'a Progress,
    /// The live run's latest values.
    pub snapshot: &'a Snapshot,
    /// Whether the open step shows what its experiment found (false while it waits for
    /// the learner's prediction).
    pub results_open: bool,
}

/// What a face asks of the app after a key.
#[derive(Debug, Clone, PartialEq)]
pub enum Reply {
    /// Handled: the face stays open.
    Stay,
    /// Handled: the face stays open and says this in the status line.
    Say(String),
    /// The face closes (the messages it set go with it).
    Close,
    /// Not the face's key: the lesson view handles it, the face stays open.
    Pass(Action),
    /// Leave the app.
    Quit,
    /// The lesson list: open lesson `usize` at its first step.
    Open(usize),
    /// The sandbox: retrain with its settings.
    Retrain,
    /// The quiz: record a real answer to question `usize` (from 0): its verdict (the first
    /// counts toward the score) and the answer itself (the choice's text, or the number).
    Answered(usize, crate::lesson::quiz::Verdict, String),
    /// The quiz: past its last question, on to the next lesson.
    Finished,
}

/// One face of the app: its keys and its drawing (its state is the implementing type).
pub trait Component {
    /// Answers `action` while the face is open.
    fn handle(&mut self, action: Action, ctx: &Ctx<'_>) -> Reply;

    /// Draws the face over `area` (the whole screen, for an overlay).
    fn render(&self, ctx: &Ctx<'_>, theme: Theme, area: Rect, buf: &mut Buffer);
}

/// A bordered panel titled `title`.
#[must_use]
pub fn panel(title: &str, theme: Theme) -> Block<'static> {
    Block::default()
        .borders(Borders::ALL)
        .border_style(theme.border())
        .title(Span::styled(format!(" {title} "), theme.title()))
}

/// Clears `rect` for an overlay, and the wide glyph (a CJK character) of the text below
/// that straddles its left edge: the overlay's border would cut that glyph in half, and a
/// terminal would draw neither.
pub fn clear(rect: Rect, buf: &mut Buffer) {
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

/// A `width`×`height` rectangle in the middle of `area` (cut to it).
#[must_use]
pub fn centered(area: Rect, width: u16, height: u16) -> Rect {
    let w = width.min(area.width);
    let h = height.min(area.height);
    Rect {
        x: area.x + (area.width - w) / 2,
        y: area.y + (area.height - h) / 2,
        width: w,
        height: h,
    }
}

/// A scroll offset that the drawing keeps within the text: [`Scroll::down`] stops at the
/// last page, as the drawing last measured it.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Scroll {
    offset: u16,
    max: std::cell::Cell<u16>,
}

impl Scroll {
    /// The first line shown.
    #[must_use]
    pub fn offset(&self) -> u16 {
        self.offset.min(self.max.get())
    }

    /// One line up.
    pub fn up(&mut self) {
        self.offset = self.offset().saturating_sub(1);
    }

    /// One line down (not past the last page).
    pub fn down(&mut self) {
        self.offset = self.offset().saturating_add(1).min(self.max.get());
    }

    /// Scrolls for ↑/↓ (and `k`/`j`, the wheel); whether `action` was one of them.
    pub fn key(&mut self, action: Action) -> bool {
        match action {
            Action::Up | Action::ScrollUp => self.up(),
            Action::Down | Action::ScrollDown => self.down(),
            _ => return false,
        }
        true
    }

    /// Back to the top.
    pub fn top(&mut self) {
        self.offset = 0;
    }

    /// Draws `lines` (wrapped to `area`'s width) in `area` from the offset. When lines are
    /// hidden below, the last row says so (`↓ N more lines: ↓ scrolls`); when scrolled, the
    /// first row says lines are above.
    pub fn render(
        &self,
        lines: Vec<ratatui::text::Line<'static>>,
        theme: Theme,
        area: Rect,
        buf: &mut Buffer,
    ) {
        use ratatui::widgets::Paragraph;
        let marks = Marks {
            up: |n| {
                crate::tr!(
                    " ↑ {n} lines above: ↑ scrolls",
                    " ↑ 上面还有 {n} 行：按 ↑ 滚动"
                )
            },
            down: |n| {
                crate::tr!(
                    " ↓ {n} more lines: ↓ scrolls",
                    " ↓ 下面还有 {n} 行：按 ↓ 滚动"
                )
            },
        };
        let height = usize::from(area.height);
        let (shown, max) = window(lines, height, usize::from(self.offset), &marks, theme);
        self.max.set(u16::try_from(max).unwrap_or(u16::MAX));
        Paragraph::new(shown).render(area, buf);
    }
}

/// What a scrolled window says above and below its lines, given how many are hidden there
/// (and which key scrolls).
pub struct Marks {
    /// The first row, when lines are above.
    pub up: fn(usize) -> String,
    /// The last row, when lines are below.
    pub down: fn(usize) -> String,
}

/// The `height` rows of `lines` from `offset` (kept within the text): when lines are hidden,
/// the first row says how many are above and the last how many below ([`Marks`]); and the
/// largest useful offset. Text that fits (or a window under 3 rows) comes back whole.
#[must_use]
pub fn window(
    lines: Vec<ratatui::text::Line<'static>>,
    height: usize,
    offset: usize,
    marks: &Marks,
    theme: Theme,
) -> (Vec<ratatui::text::Line<'static>>, usize) {
    use ratatui::text::Line;
    let total = lines.len();
    if total <= height || height < 3 {
        return (lines, 0);
    }
    // With both marks shown, `height - 2` lines of text fit.
    let max = total.saturating_sub(height - 1);
    let offset = offset.min(max);
    let above = offset > 0;
    let room = height - usize::from(above);
    let below = total - offset > room;
    let room = room - usize::from(below);
    let mut shown: Vec<Line<'static>> = Vec::with_capacity(height);
    if above {
        shown.push(Line::styled((marks.up)(offset), theme.dim()));
    }
    shown.extend(lines.into_iter().skip(offset).take(room));
    if below {
        let more = total - offset - room;
        shown.push(Line::styled((marks.down)(more), theme.dim()));
    }
    (shown, max)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::i18n::Lang;
    use ratatui::text::Line;

    fn rows(scroll: &Scroll, total: usize, height: u16) -> Vec<String> {
        let lines = (0..total).map(|i| Line::raw(format!("line {i}"))).collect();
        let area = Rect::new(0, 0, 40, height);
        let mut buf = Buffer::empty(area);
        scroll.render(lines, Theme { color: false }, area, &mut buf);
        (0..height)
            .map(|y| {
                (0..40)
                    .map(|x| buf[(x, y)].symbol())
                    .collect::<String>()
                    .trim_end()
                    .to_string()
            })
            .collect()
    }

    #[test]
    fn a_scroll_says_what_is_hidden_and_stops_at_the_last_page() {
        let _en = Lang::En.scoped();
        let mut scroll = Scroll::default();
        let top = rows(&scroll, 10, 5);
        assert_eq!(top[0], "line 0");
        assert_eq!(top[4], " ↓ 6 more lines: ↓ scrolls");
        for _ in 0..100 {
            scroll.down();
        }
        let end = rows(&scroll, 10, 5);
        assert_eq!(scroll.offset(), 6, "the last page, not 100");
        assert_eq!(end[0], " ↑ 6 lines above: ↑ scrolls");
        assert_eq!(end[1..], ["line 6", "line 7", "line 8", "line 9"]);
        scroll.up();
        let middle = rows(&scroll, 10, 5);
        assert_eq!(middle[0], " ↑ 5 lines above: ↑ scrolls");
        assert_eq!(middle[4], " ↓ 2 more lines: ↓ scrolls");
        // Text that fits shows whole, without marks.
        assert_eq!(
            rows(&Scroll::default(), 3, 5)[..3],
            ["line 0", "line 1", "line 2"]
        );
    }

    #[test]
    fn a_face_s_message_goes_with_it_and_a_warning_stays() {
        let mut status = Status::default();
        status.set(Owner::Quiz, "question 1/4");
        status.close(Owner::Exercise);
        assert_eq!(
            status.text(),
            "question 1/4",
            "another face closing keeps it"
        );
        status.close(Owner::Quiz);
        assert_eq!(status.text(), "");
        status.set(Owner::Quiz, "warning: not one, only words");
        assert!(
            !status.is_warning(),
            "a warning is said as one, not recognised by its words"
        );
        status.warn(Owner::Quiz, "cannot save");
        status.close(Owner::Quiz);
        assert!(status.is_warning(), "a warning stays until read");
        assert!(status.text().ends_with("cannot save"));
        status.clear_unless_warning();
        assert!(status.is_warning());
        status.clear();
        assert!(!status.is_warning() && status.text().is_empty());
        status.set(Owner::App, "paused");
        status.close(Owner::App);
        assert_eq!(status.text(), "paused", "the lesson view's messages stay");
    }
}
