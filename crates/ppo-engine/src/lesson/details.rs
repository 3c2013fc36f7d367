//! Collapsible details inside a step: niche material (float32 promotion, the CartPole
//! equations, prefix sums) that the main path can skip.
//!
//! In `lesson.md` a block is written as HTML, which Jupyter folds as it is:
//!
//! ```text
//! <details><summary>The equations of motion</summary>
//!
//! ...markdown...
//!
//! </details>
//! ```
//!
//! The terminal app shows one line per folded block and opens them all with `d`.

const OPEN: &str = "<details><summary>";
const SUMMARY_END: &str = "</summary>";
const CLOSE: &str = "</details>";

/// Why a step's details blocks cannot be read.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum DetailsError {
    /// A block opens inside another one.
    Nested,
    /// The opening line is not `<details><summary>TITLE</summary>`.
    BadOpening(String),
    /// A `</details>` closes no block.
    StrayClose,
    /// The step ends inside a block.
    Unclosed,
}

impl std::fmt::Display for DetailsError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Nested => write!(f, "a <details> block opens inside another; close the first"),
            Self::BadOpening(line) => write!(
                f,
                "'{line}': write the opening as one line, <details><summary>TITLE</summary>"
            ),
            Self::StrayClose => write!(f, "a </details> line closes no block"),
            Self::Unclosed => write!(f, "a <details> block is not closed; end it with </details>"),
        }
    }
}

/// One piece of a step body: main text, or a details block with its summary.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Part<'a> {
    /// Text on the main path.
    Main(Vec<&'a str>),
    /// A folded block: its summary and its lines.
    Details(&'a str, Vec<&'a str>),
}

/// Splits a body into main text and details blocks.
///
/// # Errors
/// A [`DetailsError`] for nested, unclosed or malformed blocks.
pub fn parts(body: &str) -> Result<Vec<Part<'_>>, DetailsError> {
    let mut out: Vec<Part<'_>> = vec![Part::Main(Vec::new())];
    let mut inside = false;
    for line in body.lines() {
        let trimmed = line.trim();
        if trimmed.starts_with("<details") {
            if inside {
                return Err(DetailsError::Nested);
            }
            let summary = trimmed
                .strip_prefix(OPEN)
                .and_then(|s| s.strip_suffix(SUMMARY_END))
                .ok_or_else(|| DetailsError::BadOpening(trimmed.to_string()))?;
            out.push(Part::Details(summary.trim(), Vec::new()));
            inside = true;
        } else if trimmed == CLOSE {
            if !inside {
                return Err(DetailsError::StrayClose);
            }
            out.push(Part::Main(Vec::new()));
            inside = false;
        } else {
            match out.last_mut() {
                Some(Part::Main(lines) | Part::Details(_, lines)) => lines.push(line),
                None => {}
            }
        }
    }
    if inside {
        return Err(DetailsError::Unclosed);
    }
    Ok(out)
}

/// The body for a terminal: each block folded to one line, or opened under a marker.
/// A body whose blocks cannot be read (the loader rejects those) is returned as is.
#[must_use]
pub fn fold(body: &str, open: bool) -> String {
    fold_first(body, if open { usize::MAX } else { 0 })
}

/// The body for a terminal with its first `opened` details blocks open and the rest folded:
/// the app opens a step's blocks one at a time, in order, with `d` (so that opening one
/// block never opens another, such as one to read only after a prediction), and folds them
/// all with `d` once every one is open. The folded block `d` opens next says so; once all
/// are open, the first says that `d` folds them.
#[must_use]
pub fn fold_first(body: &str, opened: usize) -> String {
    let Ok(parts) = parts(body) else {
        return body.to_string();
    };
    let total = parts
        .iter()
        .filter(|p| matches!(p, Part::Details(..)))
        .count();
    let mut out: Vec<String> = Vec::new();
    let mut index = 0;
    for part in parts {
        match part {
            Part::Main(lines) => out.extend(lines.iter().map(|l| (*l).to_string())),
            Part::Details(summary, lines) => {
                let (open, first) = (index < opened, index == 0);
                index += 1;
                if open {
                    out.push(if first && opened >= total {
                        crate::tr!(
                            "▾ **Details: {summary}** (d folds)",
                            "▾ **细节：{summary}**——按 d 收起"
                        )
                    } else {
                        crate::tr!("▾ **Details: {summary}**", "▾ **细节：{summary}**")
                    });
                    out.extend(lines.iter().map(|l| (*l).to_string()));
                    out.push(crate::i18n::t("▴ end of details", "▴ 细节结束").to_string());
                } else if index - 1 == opened {
                    out.push(crate::tr!(
                        "▸ **Details: {summary}** (d opens)",
                        "▸ **细节：{summary}**——按 d 展开"
                    ));
                } else {
                    out.push(crate::tr!(
                        "▸ **Details: {summary}** (d opens it after the one above)",
                        "▸ **细节：{summary}**——先展开上面那段，再按 d 展开"
                    ));
                }
            }
        }
    }
    out.join("\n").trim().to_string()
}

/// How many details blocks the body has (0 when they cannot be read).
#[must_use]
pub fn count(body: &str) -> usize {
    parts(body).map_or(0, |p| {
        p.iter().filter(|p| matches!(p, Part::Details(..))).count()
    })
}

/// Whether the body has any details block.
#[must_use]
pub fn has_details(body: &str) -> bool {
    parts(body).is_ok_and(|p| p.iter().any(|p| matches!(p, Part::Details(..))))
}

#[cfg(test)]
mod tests {
    use super::*;

    const BODY: &str = "Main one.\n\n<details><summary>Why float32</summary>\n\nNiche line.\n\n</details>\n\nMain two.";

    #[test]
    fn folded_hides_the_block_and_names_it() {
        let folded = fold(BODY, false);
        assert!(folded.contains("Main one.") && folded.contains("Main two."));
        assert!(folded.contains("Details: Why float32"));
        assert!(!folded.contains("Niche line."));
        assert!(!folded.contains("<details>"));
    }

    #[test]
    fn opened_shows_the_block_between_markers() {
        let opened = fold(BODY, true);
        let marker = opened.find("Details: Why float32").unwrap_or(usize::MAX);
        let niche = opened.find("Niche line.").unwrap_or(0);
        assert!(marker < niche, "{opened}");
        assert!(opened.find("Main two.").unwrap_or(0) > niche);
    }

    #[test]
    fn malformed_blocks_are_errors() {
        assert_eq!(
            parts("<details>\nx\n</details>")
                .err()
                .map(|e| matches!(e, DetailsError::BadOpening(_))),
            Some(true)
        );
        assert_eq!(
            parts("<details><summary>a</summary>\nx").err(),
            Some(DetailsError::Unclosed)
        );
        assert_eq!(parts("x\n</details>").err(), Some(DetailsError::StrayClose));
        assert_eq!(
            parts("<details><summary>a</summary>\n<details><summary>b</summary>\n</details>\n</details>").err(),
            Some(DetailsError::Nested)
        );
        assert!(!has_details("plain"));
        assert!(has_details(BODY));
    }

    /// Two blocks: `d` opens the first only (the second stays folded and says how it
    /// opens), then the second; the first then says `d` folds them.
    #[test]
    fn blocks_open_one_at_a_time_in_order() {
        let _en = crate::i18n::Lang::En.scoped();
        let body = format!(
            "{BODY}\n\n<details><summary>The answer</summary>\n\nSecret line.\n\n</details>"
        );
        assert_eq!(count(&body), 2);
        let none = fold_first(&body, 0);
        assert!(none.contains("Why float32** (d opens)"), "{none}");
        assert!(none.contains("The answer** (d opens it after"), "{none}");
        let one = fold_first(&body, 1);
        assert!(
            one.contains("Niche line.") && !one.contains("Secret line."),
            "{one}"
        );
        assert!(one.contains("The answer** (d opens)"), "{one}");
        assert!(!one.contains("(d folds)"), "{one}");
        let both = fold_first(&body, 2);
        assert!(both.contains("Niche line.") && both.contains("Secret line."));
        assert!(both.contains("Why float32** (d folds)"), "{both}");
        assert_eq!(fold(&body, true), both);
        assert_eq!(fold(&body, false), none);
    }
}
