//! Inline markdown to styled spans: `code` spans, *emphasis* and _emphasis_, **strong** and
//! __strong__, without their markers.
//!
//! The delimiter rules are CommonMark's (flanking runs, the rule of three), so that `*` and
//! `_` mark emphasis only where a reader sees it: `num_episodes` and `π_θ_old` keep their
//! underscores (an `_` between two letters neither opens nor closes), `a * b` keeps its
//! star, and `是*玩*：` is emphasised without spaces around it (a `*` may open and close
//! inside a word, so Chinese text needs none). A code span's content is taken as written.

use ratatui::text::Span;

use crate::tui::theme::Theme;

/// What a character of the line is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Kind {
    /// Text, possibly emphasised.
    Text,
    /// A character escaped with a backslash: text that is never a marker.
    Literal,
    /// Inside a code span.
    Code,
    /// A marker (a backtick, a matched `*`/`_`, an escaping backslash): not drawn.
    Marker,
}

#[derive(Debug, Clone, Copy)]
struct Char {
    c: char,
    kind: Kind,
    strong: bool,
    em: bool,
}

/// A run of `*` or `_` that may open or close emphasis.
#[derive(Debug, Clone, Copy)]
struct Run {
    c: char,
    /// Index of the first character still unmatched.
    start: usize,
    /// Characters still unmatched.
    len: usize,
    /// The run's length as written (for the rule of three).
    written: usize,
    can_open: bool,
    can_close: bool,
}

/// `text`'s inline markdown as spans: code spans in the code style, strong text in the
/// title style, emphasis in italics; markers that match nothing stay as written.
#[must_use]
pub fn inline(text: &str, theme: Theme) -> Vec<Span<'static>> {
    let mut chars = code_spans(text);
    match_emphasis(&mut chars);
    let mut spans: Vec<Span<'static>> = Vec::new();
    let mut current: Option<(bool, bool, bool)> = None;
    for ch in chars.iter().filter(|c| c.kind != Kind::Marker) {
        let key = (ch.kind == Kind::Code, ch.strong, ch.em);
        if current == Some(key)
            && let Some(last) = spans.last_mut()
        {
            last.content.to_mut().push(ch.c);
            continue;
        }
        let style = match ch.kind {
            Kind::Code => theme.code(),
            _ if ch.strong && ch.em => theme.title().patch(theme.emphasis()),
            _ if ch.strong => theme.title(),
            _ if ch.em => theme.emphasis(),
            _ => ratatui::style::Style::default(),
        };
        spans.push(Span::styled(ch.c.to_string(), style));
        current = Some(key);
    }
    spans
}

/// The characters of `text`, code spans and backslash escapes marked: a run of n backticks
/// opens a span that the next run of exactly n closes (one space inside each end is
/// dropped, as CommonMark does); a backtick run without its match is text.
fn code_spans(text: &str) -> Vec<Char> {
    let src: Vec<char> = text.chars().collect();
    let plain = |c| Char {
        c,
        kind: Kind::Text,
        strong: false,
        em: false,
    };
    let mut out: Vec<Char> = Vec::with_capacity(src.len());
    let mut i = 0;
    while i < src.len() {
        let c = src[i];
        if c == '\\' && src.get(i + 1).is_some_and(char::is_ascii_punctuation) {
            out.push(Char {
                kind: Kind::Marker,
                ..plain(c)
            });
            out.push(Char {
                kind: Kind::Literal,
                ..plain(src[i + 1])
            });
            i += 2;
            continue;
        }
        if c != '`' {
            out.push(plain(c));
            i += 1;
            continue;
        }
        let n = src[i..].iter().take_while(|&&b| b == '`').count();
        let close = (i + n..src.len()).find(|&j| {
            src[j] == '`'
                && src[j - 1] != '`'
                && src[j..].iter().take_while(|&&b| b == '`').count() == n
        });
        let Some(close) = close else {
            out.extend(src[i..i + n].iter().map(|&b| plain(b)));
            i += n;
            continue;
        };
        let mut content = &src[i + n..close];
        if content.len() >= 2
            && content[0] == ' '
            && content[content.len() - 1] == ' '
            && content.iter().any(|&c| c != ' ')
        {
            content = &content[1..content.len() - 1];
        }
        let marker = |b| Char {
            kind: Kind::Marker,
            ..plain(b)
        };
        out.extend(src[i..i + n].iter().map(|&b| marker(b)));
        out.extend(content.iter().map(|&b| Char {
            kind: Kind::Code,
            ..plain(b)
        }));
        out.extend(src[close..close + n].iter().map(|&b| marker(b)));
        i = close + n;
    }
    out
}

/// Punctuation in CommonMark's sense, widened to symbols (`∇`, `·`) and CJK punctuation:
/// anything neither a letter, a digit nor white space.
fn is_punctuation(c: char) -> bool {
    !c.is_alphanumeric() && !c.is_whitespace()
}

/// Whether `c` next to a run lets punctuation on the run's other side open or close it:
/// white space and punctuation (CommonMark), and CJK characters, since Chinese puts no
/// space between words (so `。**时序差分目标（TD 目标）**把` closes after `）`). CJK
/// punctuation inside the markers needs nothing outside (`**小批量。**4 个`).
fn loose(c: char) -> bool {
    c.is_whitespace() || is_punctuation(c) || super::is_wide(c)
}

/// The runs of `*` and `_` in text (not in code spans), with whether each may open and
/// close emphasis (CommonMark's left- and right-flanking rules). A code span or the line's
/// ends count as punctuation and white space around a run.
fn delimiter_runs(chars: &[Char]) -> Vec<Run> {
    let around = |i: Option<usize>| match i.and_then(|i| chars.get(i)) {
        None => ' ',
        Some(ch) if matches!(ch.kind, Kind::Text | Kind::Literal) => ch.c,
        Some(_) => '`',
    };
    let mut runs = Vec::new();
    let mut i = 0;
    while i < chars.len() {
        let ch = chars[i];
        if ch.kind != Kind::Text || !matches!(ch.c, '*' | '_') {
            i += 1;
            continue;
        }
        let len = chars[i..]
            .iter()
            .take_while(|d| d.kind == Kind::Text && d.c == ch.c)
            .count();
        let before = around(i.checked_sub(1));
        let after = around(Some(i + len));
        let left = !after.is_whitespace()
            && (!is_punctuation(after) || loose(before) || super::is_wide(after));
        let right = !before.is_whitespace()
            && (!is_punctuation(before) || loose(after) || super::is_wide(before));
        let (can_open, can_close) = if ch.c == '*' {
            (left, right)
        } else {
            (
                left && (!right || is_punctuation(before)),
                right && (!left || is_punctuation(after)),
            )
        };
        runs.push(Run {
            c: ch.c,
            start: i,
            len,
            written: len,
            can_open,
            can_close,
        });
        i += len;
    }
    runs
}

/// Matches closing runs with the nearest opening run of the same character, innermost
/// first, marks the matched delimiters as markers and the text between as emphasised (one
/// delimiter each side) or strong (two).
fn match_emphasis(chars: &mut [Char]) {
    let mut openers: Vec<Run> = Vec::new();
    for mut run in delimiter_runs(chars) {
        while run.can_close && run.len > 0 {
            let Some(j) = openers.iter().rposition(|o| {
                o.c == run.c
                    && !((o.can_close || run.can_open)
                        && (o.written + run.written) % 3 == 0
                        && !(o.written % 3 == 0 && run.written % 3 == 0))
            }) else {
                break;
            };
            let opener = &mut openers[j];
            let n = if opener.len >= 2 && run.len >= 2 {
                2
            } else {
                1
            };
            let inner = opener.start + opener.len;
            for ch in &mut chars[inner - n..inner] {
                ch.kind = Kind::Marker;
            }
            for ch in &mut chars[run.start..run.start + n] {
                ch.kind = Kind::Marker;
            }
            for ch in &mut chars[inner..run.start] {
                if n == 2 {
                    ch.strong = true;
                } else {
                    ch.em = true;
                }
            }
            opener.len -= n;
            run.start += n;
            run.len -= n;
            // Openers between the pair can no longer match anything.
            let keep = if opener.len == 0 { j } else { j + 1 };
            openers.truncate(keep);
        }
        if run.can_open && run.len > 0 {
            openers.push(run);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::inline;
    use crate::tui::theme::Theme;
    use ratatui::style::Modifier;

    const THEME: Theme = Theme { color: true };

    /// The spans as `(text, marks)`: `*` italic, `!` bold, `c` code.
    fn parts(text: &str) -> Vec<(String, String)> {
        inline(text, THEME)
            .iter()
            .map(|s| {
                let mut marks = String::new();
                if s.style.add_modifier.contains(Modifier::ITALIC) {
                    marks.push('*');
                }
                if s.style.add_modifier.contains(Modifier::BOLD) {
                    marks.push('!');
                }
                if s.style == THEME.code() && !s.content.is_empty() {
                    marks.push('c');
                }
                (s.content.to_string(), marks)
            })
            .collect()
    }

    fn text(text: &str) -> String {
        inline(text, THEME)
            .iter()
            .map(|s| s.content.as_ref())
            .collect()
    }

    #[test]
    fn emphasis_and_strong_lose_their_markers() {
        assert_eq!(
            parts("the *actor* and **critic**, _both_ __nets__"),
            [
                ("the ".into(), String::new()),
                ("actor".into(), "*".into()),
                (" and ".into(), String::new()),
                ("critic".into(), "!".into()),
                (", ".into(), String::new()),
                ("both".into(), "*".into()),
                (" ".into(), String::new()),
                ("nets".into(), "!".into()),
            ]
        );
        assert_eq!(text("***both*** at once"), "both at once");
        assert_eq!(parts("***both***")[0].1, "*!");
    }

    #[test]
    fn chinese_emphasis_needs_no_spaces() {
        assert_eq!(
            parts("先是*玩*：然后是*学*。"),
            [
                ("先是".into(), String::new()),
                ("玩".into(), "*".into()),
                ("：然后是".into(), String::new()),
                ("学".into(), "*".into()),
                ("。".into(), String::new()),
            ]
        );
        assert_eq!(
            text("即**剩余回报**（return-to-go）"),
            "即剩余回报（return-to-go）"
        );
    }

    #[test]
    fn identifiers_maths_and_stars_between_spaces_are_text() {
        for s in [
            "num_episodes and transition_dict",
            "π_θ_old, a_t and s_{t+1}",
            "∇_θ J(θ) = E[ Σ_t ∇_θ log π_θ(a_t|s_t) · A(s_t, a_t) ]",
            "ratio * advantage * 2",
            "snake_case_name_",
            "an *unclosed star",
        ] {
            assert_eq!(text(s), s, "{s}");
        }
        assert_eq!(text(r"\*not emphasis\*"), "*not emphasis*");
    }

    #[test]
    fn code_spans_keep_their_content_and_style() {
        assert_eq!(
            parts("call `take_action(*s*)` **with `x`**"),
            [
                ("call ".into(), String::new()),
                ("take_action(*s*)".into(), "c".into()),
                (" ".into(), String::new()),
                ("with ".into(), "!".into()),
                ("x".into(), "c".into()),
            ]
        );
        assert_eq!(text("`` a`b ``"), "a`b");
        assert_eq!(text("a ` lone backtick"), "a ` lone backtick");
    }
}
