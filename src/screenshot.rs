//! Pictures of the app made from its own screens, so that the README's pictures never go
//! stale: `ppo-tutor dev screenshots` draws each [`Scene`] as the terminal app draws it (on
//! an in-memory buffer of 160×50 cells, as `tests/tui.rs` does for its snapshots) and
//! paints the buffer to a PNG file with the bundled fonts; `tests/cli/screenshots.rs` draws
//! them again ([`draw_all`]) and fails when a committed picture differs from what the app
//! draws now ([`stale`]).
//!
//! - [`scenes`]: the app's states (a lesson with live tensors and the clip chart, the
//!   return plot after training, an exercise's grading report), in either language;
//! - [`paint`]: a buffer to pixels (colours, bold and the other modifiers, double-width
//!   glyphs), text from the bundled fonts;
//! - [`shapes`]: box drawing, block elements and Braille drawn procedurally, as terminals
//!   do, so that lines join across cells and plot dots are crisp;
//! - [`canvas`]: the pixels, the palette, PNG in and out.
//!
//! The fonts are read from the checkout (`assets/fonts/`), not compiled in: the command is
//! for the repository, like the other `dev` commands.

pub mod canvas;
pub mod paint;
pub mod scenes;
pub mod shapes;

use std::path::Path;

use anyhow::Context as _;

use crate::i18n::Lang;
use crate::tr;
use canvas::Canvas;
use paint::Fonts;
pub use scenes::Scene;

/// The command that regenerates the pictures.
pub const REGENERATE: &str = "cargo run --release -- dev screenshots";

/// The folder of the pictures, relative to the checkout's root.
pub const FOLDER: &str = "assets/screens";

/// One picture: a scene in a language.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Picture {
    /// What it shows.
    pub scene: Scene,
    /// The language of its screen.
    pub lang: Lang,
}

impl Picture {
    /// Every picture: each scene in English (README.md) and in Chinese (README.zh-CN.md).
    #[must_use]
    pub fn all() -> Vec<Picture> {
        [Lang::En, Lang::Zh]
            .into_iter()
            .flat_map(|lang| Scene::ALL.map(|scene| Picture { scene, lang }))
            .collect()
    }

    /// Its file, relative to the checkout's root: `assets/screens/en-lesson.png`.
    #[must_use]
    pub fn path(self) -> String {
        format!("{FOLDER}/{}-{}.png", self.lang.code(), self.scene.name())
    }
}

/// A picture as the app draws it now: its screen's cells and their pixels.
#[derive(Debug, Clone)]
pub struct Drawn {
    /// Which picture.
    pub picture: Picture,
    /// The screen, as the app rendered it.
    pub buffer: ratatui::buffer::Buffer,
    /// The screen painted.
    pub canvas: Canvas,
}

/// Draws every picture with the fonts under `root`, one thread each (a scene trains or
/// grades for a few seconds).
///
/// # Errors
/// The fonts cannot be read, or a scene cannot be built ([`Scene::buffer`]) or painted
/// ([`paint::paint`]).
pub fn draw_all(root: &Path) -> anyhow::Result<Vec<Drawn>> {
    let fonts = &Fonts::load(root)?;
    let pictures = Picture::all();
    std::thread::scope(|s| {
        let handles: Vec<_> = pictures
            .iter()
            .map(|&picture| {
                let draw = move || -> anyhow::Result<Drawn> {
                    let buffer = picture.scene.buffer(picture.lang)?;
                    let canvas = paint::paint(&buffer, fonts).with_context(|| picture.path())?;
                    Ok(Drawn {
                        picture,
                        buffer,
                        canvas,
                    })
                };
                (picture, s.spawn(draw))
            })
            .collect();
        handles
            .into_iter()
            .map(|(p, h)| {
                h.join().unwrap_or_else(|_| {
                    Err(anyhow::anyhow!(tr!(
                        "drawing {} panicked",
                        "绘制 {} 时程序崩溃（panic）",
                        p.path()
                    )))
                })
            })
            .collect()
    })
}

/// What [`write_all`] did to one file.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Written {
    /// The file, relative to the root.
    pub path: String,
    /// Whether its pixels changed (or it is new).
    pub changed: bool,
}

/// Draws every picture and writes it under `root`'s [`FOLDER`] (a file whose pixels are
/// already the same is left as it is).
///
/// # Errors
/// Drawing fails ([`draw_all`]) or a file cannot be written.
pub fn write_all(root: &Path) -> anyhow::Result<Vec<Written>> {
    let drawn = draw_all(root)?;
    let folder = root.join(FOLDER);
    std::fs::create_dir_all(&folder).with_context(|| folder.display().to_string())?;
    let mut written = Vec::new();
    for Drawn {
        picture, canvas, ..
    } in drawn
    {
        let path = picture.path();
        let file = root.join(&path);
        let same = std::fs::read(&file)
            .ok()
            .and_then(|bytes| Canvas::from_png(&bytes).ok())
            .is_some_and(|old| old.differing_pixels(&canvas) == 0);
        if !same {
            std::fs::write(&file, canvas.png()?).with_context(|| file.display().to_string())?;
        }
        written.push(Written {
            path,
            changed: !same,
        });
    }
    Ok(written)
}

/// Compares each of `drawn` with the committed file under `root`: one line per picture
/// that is missing or differs (empty when all are current).
#[must_use]
pub fn stale(root: &Path, drawn: &[Drawn]) -> Vec<String> {
    let mut problems = Vec::new();
    for Drawn {
        picture, canvas, ..
    } in drawn
    {
        let path = picture.path();
        let committed = std::fs::read(root.join(&path))
            .map_err(anyhow::Error::from)
            .and_then(|bytes| Canvas::from_png(&bytes));
        match committed {
            Err(e) => problems.push(tr!(
                "{path}: cannot be read ({e})",
                "{path}：无法读取（{e}）"
            )),
            Ok(old) => {
                let n = old.differing_pixels(canvas);
                if n > 0 {
                    let (w, h) = (canvas.width, canvas.height);
                    problems.push(tr!(
                        "{path}: {n} of its pixels differ from the {w}×{h} screen the app draws now",
                        "{path}：与应用现在画出的 {w}×{h} 屏幕相比，有 {n} 个像素不同"
                    ));
                }
            }
        }
    }
    problems
}
