//! A step's markdown body to lines: paragraphs joined, bullets, headings, fenced code and
//! tables block by block, inline markup by [`inline`](super::inline::inline).

use ratatui::text::{Line, Span};

use super::inline::inline;
use super::table;
use crate::tui::theme::Theme;

/// Joins hard-wrapped source lines into paragraphs and list items, keeping code blocks,
/// tables and headings line by line. A line that starts with `|` is a table row only in a
/// table (a header row with the `|---|` rule under it); elsewhere, as in `|r − 1| is`, it
/// continues its paragraph.
#[must_use]
pub fn reflow(body: &str) -> Vec<String> {
    let source: Vec<&str> = body.lines().collect();
    let mut out: Vec<String> = Vec::new();
    let mut open = false; // whether the last pushed line may take a continuation
    let mut in_code = false;
    let mut i = 0;
    while i < source.len() {
        let raw = source[i];
        let t = raw.trim_start();
        i += 1;
        if t.starts_with("```") {
            in_code = !in_code;
            out.push(raw.to_string());
            open = false;
            continue;
        }
        let rows = if in_code {
            0
        } else {
            table::rows(&source[i - 1..])
        };
        if rows > 0 {
            out.extend(source[i - 1..i - 1 + rows].iter().map(|r| (*r).to_string()));
            i += rows - 1;
            open = false;
            continue;
        }
        let starts_block = in_code
            || t.is_empty()
            || t.starts_with("- ")
            || t.starts_with("* ")
            || t.starts_with('#')
            || t.split_once(". ")
                .is_some_and(|(n, _)| !n.is_empty() && n.chars().all(|c| c.is_ascii_digit()));
        if !starts_block
            && open
            && let Some(last) = out.last_mut()
        {
            last.push(' ');
            last.push_str(t);
            continue;
        }
        out.push(raw.to_string());
        open = !in_code && !t.is_empty() && !t.starts_with('#');
    }
    out
}

/// A heading's text without its `#` marks.
fn heading(line: &str) -> Option<&str> {
    let marks = line.chars().take_while(|&c| c == '#').count();
    (1..=6)
        .contains(&marks)
        .then(|| line[marks..].strip_prefix(' '))
        .flatten()
}

/// Converts a step's markdown body into lines for a pane `width` columns wide (wrap them
/// with [`wrap`](super::wrap)): emphasis and code spans styled without their markers,
/// tables as aligned columns that fit the width.
#[must_use]
pub fn markdown(body: &str, theme: Theme, width: usize) -> Vec<Line<'static>> {
    let source = reflow(body);
    let mut lines = Vec::new();
    let mut in_code = false;
    let mut i = 0;
    while i < source.len() {
        let raw = source[i].as_str();
        i += 1;
        if raw.trim_start().starts_with("```") {
            in_code = !in_code;
            continue;
        }
        if in_code {
            lines.push(Line::styled(format!("  {raw}"), theme.code()));
            continue;
        }
        let rows = table::rows(&source[i - 1..]);
        if rows > 0 {
            lines.extend(table::render(&source[i - 1..i - 1 + rows], theme, width));
            i += rows - 1;
            continue;
        }
        if let Some(h) = heading(raw) {
            let spans = inline(h, theme).into_iter();
            lines.push(Line::from(
                spans
                    .map(|s| s.patch_style(theme.title()))
                    .collect::<Vec<_>>(),
            ));
            continue;
        }
        let (prefix, rest) = match raw.strip_prefix("- ").or_else(|| raw.strip_prefix("* ")) {
            Some(rest) => ("• ", rest),
            None => ("", raw),
        };
        let mut spans = vec![Span::raw(prefix)];
        spans.extend(inline(rest, theme));
        lines.push(Line::from(spans));
    }
    lines
}

#[cfg(test)]
mod tests {
    use super::{markdown, reflow};
    use crate::tui::theme::Theme;
    use crate::tui::widgets::text::wrap;
    use ratatui::style::Modifier;

    #[test]
    fn paragraphs_join_and_blocks_stay() {
        let body = "one\ntwo\n\n- a\n  b\n- c\n\n| x |\n|---|\n| y |\n```\ncode\nmore\n```";
        assert_eq!(
            reflow(body),
            [
                "one two", "", "- a b", "- c", "", "| x |", "|---|", "| y |", "```", "code",
                "more", "```"
            ]
        );
        // A line that starts with `|` outside a table continues its paragraph.
        assert_eq!(
            reflow("the largest\n|r − 1| is 0.5.\n\n| a |\n| b |"),
            ["the largest |r − 1| is 0.5.", "", "| a | | b |"]
        );
    }

    /// Rows as text, and each row's italic part.
    fn rows(body: &str, columns: u16) -> Vec<(String, String)> {
        let theme = Theme { color: false };
        wrap(markdown(body, theme, usize::from(columns)), columns)
            .iter()
            .map(|l| {
                let text = l.spans.iter().map(|s| s.content.as_ref()).collect();
                let italic = l
                    .spans
                    .iter()
                    .filter(|s| s.style.add_modifier.contains(Modifier::ITALIC))
                    .map(|s| s.content.as_ref())
                    .collect();
                (text, italic)
            })
            .collect()
    }

    /// Emphasis that wraps keeps its style on both rows and shows no
    /// stars (as the hard-wrapped source and a narrow pane split it).
    #[test]
    fn emphasis_across_a_wrap_has_no_markers() {
        let body = "The gradient is a *distribution\nover actions* and a **single\nnumber**.";
        let rows = rows(body, 24);
        let text: Vec<&str> = rows.iter().map(|(t, _)| t.as_str()).collect();
        assert_eq!(
            text,
            [
                "The gradient is a",
                "distribution over",
                "actions and a single",
                "number."
            ]
        );
        assert_eq!(rows[1].1, "distribution over");
        assert_eq!(rows[2].1, "actions");
    }

    /// Chinese emphasis has no spaces around its stars, and a Chinese row may break inside
    /// the emphasised words.
    #[test]
    fn chinese_emphasis_wraps_without_stars() {
        let body = "训练在两个阶段之间交替进行。先是*玩*：智能体用当前策略玩一个回合。然后是*学会很多东西*。";
        let rows = rows(body, 20);
        assert_eq!(
            rows,
            [
                ("训练在两个阶段之间交".into(), String::new()),
                ("替进行。先是玩：智能".into(), "玩".into()),
                ("体用当前策略玩一个回".into(), String::new()),
                ("合。然后是学会很多东".into(), "学会很多东".into()),
                ("西。".into(), "西".into()),
            ]
        );
    }

    #[test]
    fn identifiers_with_underscores_are_untouched() {
        let body = "`num_episodes` is num_episodes, and transition_dict holds π_θ_old(a_t|s_t).";
        let rows = rows(body, 100);
        assert_eq!(
            rows[0].0,
            "num_episodes is num_episodes, and transition_dict holds π_θ_old(a_t|s_t)."
        );
        assert_eq!(rows[0].1, "");
    }

    /// The words of `text` that hold an underscore between letters (`num_episodes`).
    fn identifiers(text: &str) -> Vec<&str> {
        text.split(|c: char| !(c.is_alphanumeric() || c == '_'))
            .filter(|w| w.trim_matches('_').contains('_'))
            .map(|w| w.trim_matches('_'))
            .collect()
    }

    /// Every step of every lesson, in both languages, as the terminal app draws it (at
    /// 80×24's text width and 160×50's): no emphasis star or table pipe left in the prose,
    /// and every identifier with underscores whole.
    #[test]
    fn no_lesson_shows_markdown_markers() -> Result<(), Box<dyn std::error::Error>> {
        use crate::i18n::Lang;
        use crate::lesson::{Course, details, face::Face};
        let theme = Theme { color: true };
        for lang in [Lang::En, Lang::Zh] {
            let _lang = lang.scoped();
            for lesson in &Course::embedded()?.lessons {
                for step in &lesson.steps {
                    let body = details::fold(&step.text(Face::Terminal), true);
                    for columns in [34, 70, 500] {
                        let lines = markdown(&body, theme, columns);
                        for line in lines.iter().filter(|l| l.style != theme.code()) {
                            let text: String =
                                line.spans.iter().map(|s| s.content.as_ref()).collect();
                            let place =
                                format!("{} {:?} ({columns}): {text}", lesson.id, step.title);
                            assert!(!text.trim_start().starts_with('|'), "{place}");
                            for span in line.spans.iter().filter(|s| s.style != theme.code()) {
                                // A star between spaces is a product (`a * b`), not a marker.
                                let stars = span.content.replace(" * ", "");
                                assert!(!stars.contains('*'), "{place}");
                            }
                        }
                        // Wide enough that no table cell wraps: each identifier on one line.
                        if columns == 500 {
                            let all: Vec<String> = lines
                                .iter()
                                .map(|l| l.spans.iter().map(|s| s.content.as_ref()).collect())
                                .collect();
                            for word in identifiers(&body) {
                                assert!(
                                    all.iter().any(|l| l.contains(word)),
                                    "{} {:?}: {word} lost",
                                    lesson.id,
                                    step.title
                                );
                            }
                        }
                    }
                }
            }
        }
        Ok(())
    }
}
