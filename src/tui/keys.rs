//! The key map: every key the app understands, and the help text listing them.

use crossterm::event::{KeyCode, KeyEvent, KeyEventKind, KeyModifiers};

use crate::i18n::{Lang, t};

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
    /// Scroll the live tensors down one row (`J`).
    TensorDown,
    /// Scroll the live tensors up one row (`K`).
    TensorUp,
    /// Scroll the live tensors down a page (PgDn).
    TensorPageDown,
    /// Scroll the live tensors up a page (PgUp).
    TensorPageUp,
    /// The live tables' first rows (Home).
    TensorFirst,
    /// The live tables' last rows (End).
    TensorLast,
    /// Scroll the code pane down (`]`).
    CodeDown,
    /// Scroll the code pane up (`[`).
    CodeUp,
    /// Scroll the live tables right: the next column first (`>`).
    TensorRight,
    /// Scroll the live tables left: the previous column first (`<`).
    TensorLeft,
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
    /// Open the step's next details block, or fold them all once all are open (d).
    Details,
    /// Run the step's clip-lab experiment (x).
    RunLab,
    /// A character typed into a quiz answer: a choice letter, or part of a number.
    Type(char),
    /// Erase the last character typed (Backspace).
    Erase,
    /// Switch the language live, English ⇄ 中文 (L).
    Language,
    /// Leave the app.
    Quit,
}

/// The language key's label in the key bar and the help: the language it switches to
/// (`中文` while the app is in English, `English` while it is in Chinese).
#[must_use]
pub fn language_label() -> &'static str {
    Lang::current().other().name()
}

/// The help overlay's lines, in the current language: key, what it does.
#[must_use]
pub fn help() -> Vec<(&'static str, &'static str)> {
    vec![
        ("→ / n", t("next step", "下一节")),
        ("← / p", t("previous step", "上一节")),
        (
            t("j / k, wheel", "j / k、滚轮"),
            t("scroll the explanation", "滚动讲解"),
        ),
        (
            "J / K, < / >",
            t(
                "scroll the live values (a row, a column)",
                "滚动实时数值（一行、一列）",
            ),
        ),
        (
            "PgDn / PgUp",
            t("scroll the live values a page", "实时数值翻一页"),
        ),
        (
            "Home / End",
            t(
                "the live values' first / last rows",
                "实时数值的开头 / 最后几行",
            ),
        ),
        ("[ / ]", t("scroll the code pane", "滚动代码面板")),
        (
            "d",
            t(
                "open this step's next details block (▸); fold them once all are open",
                "展开本节的下一段细节（▸）；全部展开后再按则收起",
            ),
        ),
        (
            "x",
            t(
                "run the step's experiment (clip lab, 5 seeds)",
                "运行本节的实验（截断实验室，5 个随机种子）",
            ),
        ),
        (
            "l",
            t(
                "lesson list (↑↓ choose, Enter open)",
                "课程列表（↑↓ 选择，Enter 打开）",
            ),
        ),
        (
            "t",
            t(
                "train / pause (runs on a worker thread)",
                "训练 / 暂停（在后台线程运行）",
            ),
        ),
        ("e", t("train one episode", "训练一个回合")),
        (
            "r",
            t("reset the agent with the seed", "用随机种子重置智能体"),
        ),
        (
            "s",
            t(
                "sandbox: change ε, γ, λ, learning rates, seed",
                "沙盒：修改 ε、γ、λ、学习率、随机种子",
            ),
        ),
        (
            "  ↑↓ + − Enter",
            t(
                "  pick a value, change it, retrain (curves overlaid)",
                "  选一项，改它的值，重新训练（曲线叠加对比）",
            ),
        ),
        (
            "g",
            t(
                "grade this lesson's exercise (its exercise.rs)",
                "给本课的练习评分（它的 exercise.rs）",
            ),
        ),
        (
            "h",
            t("reveal the exercise's next hint", "显示练习的下一条提示"),
        ),
        (
            "a–d, 0–9 Enter",
            t(
                "answer the quiz after a lesson's last step",
                "回答每课最后一节之后的小测验",
            ),
        ),
        (
            "L",
            t(
                "switch the language to 中文 (Chinese)",
                "把界面语言切换为 English（英文）",
            ),
        ),
        ("?", t("this help", "本帮助")),
        ("Esc", t("close an overlay", "关闭弹出面板")),
        (
            "q / Ctrl-C",
            t("quit (progress is saved)", "退出（进度会保存）"),
        ),
        ("", ""),
        (
            t("Live values", "实时数值"),
            t(
                "magenta = clipped ratio, red = done flag",
                "品红 = 被截断的比率，红 = 回合结束标志",
            ),
        ),
        (
            "",
            t(
                "green / red = positive / negative advantage",
                "绿 / 红 = 正 / 负优势值",
            ),
        ),
    ]
}

/// Where a key press lands: what is open decides what some keys mean.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Context {
    /// An overlay with a list or fields is open (↑/↓ move in it).
    pub overlay_open: bool,
    /// The sandbox is open (←/→ and +/− change a value).
    pub sandbox_open: bool,
    /// A quiz question is open (a–d, digits, `.` and `-` are typed as an answer).
    pub quiz_open: bool,
    /// A lab step asks for a prediction (a–f, as many as an experiment has settings, are
    /// typed as its choice).
    pub prediction_open: bool,
}

/// Maps a key press to an action in the given context.
#[must_use]
pub fn map(key: KeyEvent, context: Context) -> Option<Action> {
    let Context {
        overlay_open,
        sandbox_open,
        quiz_open,
        prediction_open,
    } = context;
    if key.kind == KeyEventKind::Release {
        return None;
    }
    if key.modifiers.contains(KeyModifiers::CONTROL) && key.code == KeyCode::Char('c') {
        return Some(Action::Quit);
    }
    let action = match key.code {
        KeyCode::Char(c @ ('a'..='d' | '0'..='9' | '.' | '-')) if quiz_open => Action::Type(c),
        KeyCode::Char(c @ 'a'..='f') if prediction_open => Action::Type(c),
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
        KeyCode::Char('J') => Action::TensorDown,
        KeyCode::Char('K') => Action::TensorUp,
        KeyCode::PageDown => Action::TensorPageDown,
        KeyCode::PageUp => Action::TensorPageUp,
        KeyCode::Home => Action::TensorFirst,
        KeyCode::End => Action::TensorLast,
        KeyCode::Char(']') => Action::CodeDown,
        KeyCode::Char('[') => Action::CodeUp,
        KeyCode::Char('>') => Action::TensorRight,
        KeyCode::Char('<') => Action::TensorLeft,
        KeyCode::Char('l') => Action::Lessons,
        KeyCode::Char('s') => Action::Sandbox,
        KeyCode::Char('t') | KeyCode::Char(' ') => Action::TrainToggle,
        KeyCode::Char('e') => Action::OneEpisode,
        KeyCode::Char('r') => Action::ResetAgent,
        KeyCode::Char('g') => Action::Grade,
        KeyCode::Char('h') => Action::Hint,
        KeyCode::Char('d') => Action::Details,
        KeyCode::Char('x') => Action::RunLab,
        KeyCode::Char('L') => Action::Language,
        _ => return None,
    };
    Some(action)
}
