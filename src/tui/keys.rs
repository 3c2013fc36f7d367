//! The key map: every key the app understands, and the help text listing them.

use crossterm::event::{KeyCode, KeyEvent, KeyEventKind, KeyModifiers};

/// What the learner asked for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Action {
    /// Next step (→, n).
    Next,
    /// Previous step (←, p).
    Prev,
    /// Scroll the explanation down / up.
    ScrollDown,
    /// Scroll the explanation up.
    ScrollUp,
    /// Scroll the live tensors down.
    TensorDown,
    /// Scroll the live tensors up.
    TensorUp,
    /// Open or close the lesson list.
    Lessons,
    /// Open or close the help overlay.
    Help,
    /// Open or close the sandbox.
    Sandbox,
    /// Start or pause training.
    TrainToggle,
    /// Train exactly one episode.
    OneEpisode,
    /// Reset the agent (new weights from the seed).
    ResetAgent,
    /// Confirm (open the selected lesson, retrain in the sandbox).
    Enter,
    /// Up in a list or field.
    Up,
    /// Down in a list or field.
    Down,
    /// Increase the selected sandbox value.
    Increase,
    /// Decrease the selected sandbox value.
    Decrease,
    /// Close an overlay.
    Back,
    /// Grade the lesson's exercise (g).
    Grade,
    /// Reveal the exercise's next hint (h).
    Hint,
    /// Open or fold the steps' details blocks (d).
    Details,
    /// Run the step's clip-lab experiment (x).
    RunLab,
    /// A character typed into a quiz answer: a choice letter, or part of a number.
    Type(char),
    /// Erase the last character typed (Backspace).
    Erase,
    /// Leave the app.
    Quit,
}

/// The help overlay's lines: key, what it does.
pub const HELP: [(&str, &str); 21] = [
    ("→ / n", "next step"),
    ("← / p", "previous step"),
    ("j / k, wheel", "scroll the explanation"),
    ("J / K", "scroll the live tensors"),
    ("d", "open / fold the details (▸) in the explanation"),
    ("x", "run the step's experiment (clip lab, 5 seeds)"),
    ("l", "lesson list (↑↓ choose, Enter open)"),
    ("t", "train / pause (runs on a worker thread)"),
    ("e", "train one episode"),
    ("r", "reset the agent with the seed"),
    ("s", "sandbox: change ε, γ, λ, learning rates, seed"),
    (
        "  ↑↓ + − Enter",
        "  pick a value, change it, retrain (curves overlaid)",
    ),
    ("g", "grade this lesson's exercise (its exercise.rs)"),
    ("h", "reveal the exercise's next hint"),
    (
        "a–d, 0–9 Enter",
        "answer the quiz after a lesson's last step",
    ),
    ("?", "this help"),
    ("Esc", "close an overlay"),
    ("q / Ctrl-C", "quit (progress is saved)"),
    ("", ""),
    ("Live values", "magenta = clipped ratio, red = done flag"),
    ("", "green / red = positive / negative advantage"),
];

/// Where a key press lands: what is open decides what some keys mean.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Context {
    /// An overlay with a list or fields is open (↑/↓ move in it).
    pub overlay_open: bool,
    /// The sandbox is open (←/→ and +/− change a value).
    pub sandbox_open: bool,
    /// A quiz question is open (a–d, digits, `.` and `-` are typed as an answer).
    pub quiz_open: bool,
}

/// Maps a key press to an action in the given context.
#[must_use]
pub fn map(key: KeyEvent, context: Context) -> Option<Action> {
    let Context {
        overlay_open,
        sandbox_open,
        quiz_open,
    } = context;
    if key.kind == KeyEventKind::Release {
        return None;
    }
    if key.modifiers.contains(KeyModifiers::CONTROL) && key.code == KeyCode::Char('c') {
        return Some(Action::Quit);
    }
    let action = match key.code {
        KeyCode::Char(c @ ('a'..='d' | '0'..='9' | '.' | '-')) if quiz_open => Action::Type(c),
        KeyCode::Backspace if quiz_open => Action::Erase,
        KeyCode::Char('q') => Action::Quit,
        KeyCode::Esc => Action::Back,
        KeyCode::Char('?') => Action::Help,
        KeyCode::Enter => Action::Enter,
        KeyCode::Up if overlay_open => Action::Up,
        KeyCode::Down if overlay_open => Action::Down,
        KeyCode::Char('+' | '=') | KeyCode::Right if sandbox_open => Action::Increase,
        KeyCode::Char('-') | KeyCode::Left if sandbox_open => Action::Decrease,
        KeyCode::Right | KeyCode::Char('n') => Action::Next,
        KeyCode::Left | KeyCode::Char('p') => Action::Prev,
        KeyCode::Down | KeyCode::Char('j') => Action::ScrollDown,
        KeyCode::Up | KeyCode::Char('k') => Action::ScrollUp,
        KeyCode::Char('J') | KeyCode::PageDown => Action::TensorDown,
        KeyCode::Char('K') | KeyCode::PageUp => Action::TensorUp,
        KeyCode::Char('l') => Action::Lessons,
        KeyCode::Char('s') => Action::Sandbox,
        KeyCode::Char('t') | KeyCode::Char(' ') => Action::TrainToggle,
        KeyCode::Char('e') => Action::OneEpisode,
        KeyCode::Char('r') => Action::ResetAgent,
        KeyCode::Char('g') => Action::Grade,
        KeyCode::Char('h') => Action::Hint,
        KeyCode::Char('d') => Action::Details,
        KeyCode::Char('x') => Action::RunLab,
        _ => return None,
    };
    Some(action)
}
