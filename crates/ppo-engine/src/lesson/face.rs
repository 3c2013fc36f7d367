//! Passages for one face of the course: the terminal (the app and `ppo-tutor show`) or a
//! notebook.
//!
//! Most of a step's text reads the same everywhere. Where it cannot (the app has panels,
//! keys and a sandbox; a notebook has cells to run and edit), `lesson.md` gives each face
//! its own words:
//!
//! ```text
//! Run it<app> with `x`</app><notebook> in the next cell</notebook>.
//!
//! <app>
//! Open the sandbox (`s`) and retrain.
//! </app>
//! <notebook>
//! Change `config` in the first cells and run them again.
//! </notebook>
//! ```
//!
//! A tag inside a line marks an inline passage; a tag alone on its line marks a passage of
//! whole lines (paragraphs, lists, `<details>` blocks) and takes its line with it. The
//! terminal keeps `<app>` passages and drops `<notebook>` ones, a notebook the reverse;
//! the tags themselves are removed, and text outside them is shared. Put the space that
//! separates an inline passage from the shared text inside the passage (`word<app> more</app>.`),
//! so that dropping it leaves no stray space. Passages do not nest.
//!
//! ```
//! use ppo_engine::lesson::face::{Face, select};
//!
//! let body = "Run it<app> with `x`</app><notebook> in the next cell</notebook>.";
//! assert_eq!(select(body, Face::Terminal).as_deref(), Ok("Run it with `x`."));
//! assert_eq!(select(body, Face::Notebook).as_deref(), Ok("Run it in the next cell."));
//! ```

/// Where a step's text is read.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Face {
    /// The terminal app and the headless `ppo-tutor show`: keeps `<app>` passages.
    Terminal,
    /// The generated Jupyter notebooks: keeps `<notebook>` passages.
    Notebook,
}

impl Face {
    /// Both faces.
    pub const ALL: [Self; 2] = [Self::Terminal, Self::Notebook];

    /// The tag of this face's own passages: `app` or `notebook`.
    #[must_use]
    pub const fn tag(self) -> &'static str {
        match self {
            Self::Terminal => "app",
            Self::Notebook => "notebook",
        }
    }
}

/// Why a step's face passages cannot be read.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum FaceError {
    /// A passage opens inside another one (`inner` inside `outer`).
    Nested {
        /// The tag of the passage already open.
        outer: &'static str,
        /// The tag that opens inside it.
        inner: &'static str,
    },
    /// A closing tag closes no open passage of its kind.
    StrayClose(&'static str),
    /// The step ends inside a passage.
    Unclosed(&'static str),
}

impl std::fmt::Display for FaceError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Nested { outer, inner } => write!(
                f,
                "a <{inner}> passage opens inside a <{outer}> one; close </{outer}> first \
                 (passages do not nest)"
            ),
            Self::StrayClose(tag) => write!(f, "a </{tag}> closes no open <{tag}> passage"),
            Self::Unclosed(tag) => {
                write!(f, "a <{tag}> passage is not closed; end it with </{tag}>")
            }
        }
    }
}

/// One tag in a body.
#[derive(Debug, Clone, Copy)]
struct Tag {
    face: Face,
    open: bool,
    /// Byte range of the tag itself.
    start: usize,
    end: usize,
}

/// The next tag at or after byte `from`.
fn next_tag(body: &str, from: usize) -> Option<Tag> {
    let mut at = from;
    while let Some(i) = body.get(at..)?.find('<') {
        let start = at + i;
        let rest = &body[start..];
        for face in Face::ALL {
            for open in [true, false] {
                let tag = if open {
                    format!("<{}>", face.tag())
                } else {
                    format!("</{}>", face.tag())
                };
                if rest.starts_with(&tag) {
                    return Some(Tag {
                        face,
                        open,
                        start,
                        end: start + tag.len(),
                    });
                }
            }
        }
        at = start + 1;
    }
    None
}

/// The byte range a tag takes: the whole line (with its newline) when the tag stands alone
/// on it, else the tag itself. (A tag alone on its line has no other tag before it there,
/// so its line starts at or after `from`, where the previous tag ended.)
fn span(body: &str, tag: Tag, from: usize) -> (usize, usize) {
    let line_start = body[..tag.start].rfind('\n').map_or(0, |p| p + 1);
    let line_end = body[tag.end..]
        .find('\n')
        .map_or(body.len(), |p| tag.end + p);
    let alone = line_start >= from
        && body[line_start..tag.start].trim().is_empty()
        && body[tag.end..line_end].trim().is_empty();
    if alone {
        (line_start, (line_end + 1).min(body.len()))
    } else {
        (tag.start, tag.end)
    }
}

/// Keeps at most one blank line in a row outside code fences: a dropped block passage
/// leaves the blank lines around it.
fn collapse_blank_lines(text: &str) -> String {
    let mut out: Vec<&str> = Vec::new();
    let mut fence = false;
    let mut blank_before = false;
    for line in text.lines() {
        if line.trim_start().starts_with("```") {
            fence = !fence;
        }
        let blank = line.trim().is_empty();
        if blank && blank_before && !fence {
            continue;
        }
        blank_before = blank;
        out.push(line);
    }
    out.join("\n").trim().to_string()
}

/// Appends shared or kept `text`; after an inline passage was dropped between two spaces,
/// one of them goes with it.
fn push(out: &mut String, text: &str, dropped_inline: &mut bool) {
    let text = if *dropped_inline && out.ends_with(' ') {
        text.strip_prefix(' ').unwrap_or(text)
    } else {
        text
    };
    out.push_str(text);
    *dropped_inline = false;
}

/// The body as `face` reads it: its own passages without their tags, the other face's
/// passages dropped, the shared text as is.
///
/// # Errors
/// A [`FaceError`] for a passage that nests, is not closed, or a closing tag that closes
/// none.
pub fn select(body: &str, face: Face) -> Result<String, FaceError> {
    let mut out = String::with_capacity(body.len());
    let mut open: Option<Face> = None;
    let mut pos = 0;
    let mut dropped_inline = false;
    while let Some(tag) = next_tag(body, pos) {
        let (start, end) = span(body, tag, pos);
        let keep = open.is_none_or(|f| f == face);
        if keep {
            push(&mut out, &body[pos..start], &mut dropped_inline);
        }
        match (open, tag.open) {
            (None, true) => open = Some(tag.face),
            (Some(outer), true) => {
                return Err(FaceError::Nested {
                    outer: outer.tag(),
                    inner: tag.face.tag(),
                });
            }
            (Some(f), false) if f == tag.face => {
                if f != face && (start, end) == (tag.start, tag.end) {
                    dropped_inline = true;
                }
                open = None;
            }
            (_, false) => return Err(FaceError::StrayClose(tag.face.tag())),
        }
        pos = end;
    }
    if let Some(f) = open {
        return Err(FaceError::Unclosed(f.tag()));
    }
    push(&mut out, &body[pos..], &mut dropped_inline);
    Ok(collapse_blank_lines(&out))
}

/// Checks the body's passages: what the loader rejects.
///
/// # Errors
/// See [`select`].
pub fn check(body: &str) -> Result<(), FaceError> {
    select(body, Face::Terminal).map(drop)
}

/// The body as `face` reads it; a body whose passages cannot be read (the loader rejects
/// those) is returned as is.
#[must_use]
pub fn text(body: &str, face: Face) -> String {
    select(body, face).unwrap_or_else(|_| body.to_string())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn both(body: &str) -> (String, String) {
        (
            select(body, Face::Terminal).unwrap_or_else(|e| format!("error: {e}")),
            select(body, Face::Notebook).unwrap_or_else(|e| format!("error: {e}")),
        )
    }

    #[test]
    fn text_without_tags_is_the_same_for_both_faces() {
        let body = "One.\n\n- a\n- b\n\n```rust\nlet x = 1;\n```\n\nTwo <b>bold</b> a < b.";
        assert_eq!(both(body), (body.to_string(), body.to_string()));
    }

    #[test]
    fn inline_passages_pick_their_face() {
        let body = "Run it<app> with `x`</app><notebook> in the next cell</notebook>, then look.";
        assert_eq!(
            both(body),
            (
                "Run it with `x`, then look.".to_string(),
                "Run it in the next cell, then look.".to_string()
            )
        );
        // A passage that opens at the end of a line keeps its line break.
        let wrapped = "Shared.<app> App.</app><notebook>\nNotebook.</notebook>\nMore.";
        assert_eq!(
            both(wrapped),
            (
                "Shared. App.\nMore.".to_string(),
                "Shared.\nNotebook.\nMore.".to_string()
            )
        );
        // A passage written between spaces leaves one space where it is dropped.
        let spaced = "Look <app>beside this text</app> now.";
        assert_eq!(
            both(spaced),
            (
                "Look beside this text now.".to_string(),
                "Look now.".to_string()
            )
        );
    }

    #[test]
    fn block_passages_take_their_lines_and_keep_paragraphs() {
        let body = "Shared one.\n\n<app>\nPress `x`.\n\nAnd retrain.\n</app>\n<notebook>\nRun the next cell.\n</notebook>\n\nShared two.";
        assert_eq!(
            both(body),
            (
                "Shared one.\n\nPress `x`.\n\nAnd retrain.\n\nShared two.".to_string(),
                "Shared one.\n\nRun the next cell.\n\nShared two.".to_string()
            )
        );
        // A dropped paragraph between two others leaves one blank line, not three.
        let alone = "A.\n\n<notebook>\nOnly here.\n</notebook>\n\nB.";
        assert_eq!(both(alone).0, "A.\n\nB.");
        // Lines of a list stay one list.
        let list = "- one\n<app>\n- two\n</app>\n- three";
        assert_eq!(
            both(list),
            (
                "- one\n- two\n- three".to_string(),
                "- one\n- three".to_string()
            )
        );
    }

    #[test]
    fn a_passage_may_hold_a_details_block() {
        let body = "Main.\n\n<notebook>\n<details><summary>S</summary>\n\nMore.\n\n</details>\n</notebook>";
        let (terminal, notebook) = both(body);
        assert_eq!(terminal, "Main.");
        assert!(
            crate::lesson::details::parts(&notebook).is_ok() && notebook.contains("More."),
            "{notebook}"
        );
    }

    #[test]
    fn malformed_passages_are_errors() {
        assert_eq!(
            check("a <app>b"),
            Err(FaceError::Unclosed("app")),
            "an unclosed inline passage"
        );
        assert_eq!(
            check("<notebook>\nb\n"),
            Err(FaceError::Unclosed("notebook"))
        );
        assert_eq!(
            check("a <app>b <app>c</app></app>"),
            Err(FaceError::Nested {
                outer: "app",
                inner: "app"
            })
        );
        assert_eq!(
            check("<app>a <notebook>b</notebook></app>"),
            Err(FaceError::Nested {
                outer: "app",
                inner: "notebook"
            })
        );
        assert_eq!(check("a</app>"), Err(FaceError::StrayClose("app")));
        assert_eq!(
            check("<app>a</notebook>"),
            Err(FaceError::StrayClose("notebook"))
        );
        let message = FaceError::Unclosed("app").to_string();
        assert!(message.contains("</app>"), "{message}");
        // The lenient form used by the faces returns a malformed body untouched.
        assert_eq!(text("a <app>b", Face::Notebook), "a <app>b");
    }
}
