//! Colours and styles in one place; `NO_COLOR` turns every colour off.

use ratatui::style::{Color, Modifier, Style};

/// The styles the app draws with.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Theme {
    /// Whether colours are used at all (false under `NO_COLOR`).
    pub color: bool,
}

impl Theme {
    /// Colours unless the `NO_COLOR` environment variable is set to anything non-empty.
    #[must_use]
    pub fn from_env() -> Self {
        let no_color = std::env::var_os("NO_COLOR").is_some_and(|v| !v.is_empty());
        Self { color: !no_color }
    }

    fn fg(self, c: Color) -> Style {
        if self.color {
            Style::new().fg(c)
        } else {
            Style::new()
        }
    }

    /// Panel borders and plain text.
    #[must_use]
    pub fn border(self) -> Style {
        self.fg(Color::DarkGray)
    }
    /// Titles and headings.
    #[must_use]
    pub fn title(self) -> Style {
        self.fg(Color::Cyan).add_modifier(Modifier::BOLD)
    }
    /// Emphasised words in lesson prose (`*word*`): italics, with or without colour.
    #[must_use]
    pub fn emphasis(self) -> Style {
        Style::new().add_modifier(Modifier::ITALIC)
    }
    /// Inline code and the Rust listing.
    #[must_use]
    pub fn code(self) -> Style {
        self.fg(Color::Yellow)
    }
    /// The seed's Python.
    #[must_use]
    pub fn python(self) -> Style {
        self.fg(Color::LightBlue)
    }
    /// De-emphasised text (shapes, hints).
    #[must_use]
    pub fn dim(self) -> Style {
        if self.color {
            Style::new().fg(Color::Gray)
        } else {
            Style::new().add_modifier(Modifier::DIM)
        }
    }
    /// A clipped ratio.
    #[must_use]
    pub fn clipped(self) -> Style {
        self.fg(Color::Magenta).add_modifier(Modifier::BOLD)
    }
    /// A done flag.
    #[must_use]
    pub fn done(self) -> Style {
        self.fg(Color::Red).add_modifier(Modifier::BOLD)
    }
    /// A positive value.
    #[must_use]
    pub fn positive(self) -> Style {
        self.fg(Color::Green)
    }
    /// A negative value.
    #[must_use]
    pub fn negative(self) -> Style {
        self.fg(Color::Red)
    }
    /// The raw return curve.
    #[must_use]
    pub fn curve(self) -> Style {
        self.fg(Color::Cyan)
    }
    /// The moving average.
    #[must_use]
    pub fn average(self) -> Style {
        self.fg(Color::Yellow)
    }
    /// The previous run's curve in the sandbox comparison.
    #[must_use]
    pub fn previous(self) -> Style {
        self.fg(Color::DarkGray)
    }
    /// Selected items and key names.
    #[must_use]
    pub fn highlight(self) -> Style {
        if self.color {
            Style::new().fg(Color::Black).bg(Color::Cyan)
        } else {
            Style::new().add_modifier(Modifier::REVERSED)
        }
    }
    /// Key names in hints.
    #[must_use]
    pub fn key(self) -> Style {
        self.fg(Color::Cyan).add_modifier(Modifier::BOLD)
    }
}
