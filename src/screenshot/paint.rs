//! A ratatui [`Buffer`] painted as a terminal shows it: each cell's background, then its
//! symbol in its foreground and modifiers (bold, italic, dim, reversed, underlined). Lines,
//! blocks and Braille are drawn procedurally ([`super::shapes`]); text comes from the
//! bundled fonts, DejaVu Sans Mono (regular and bold) and, for the glyphs it lacks (Chinese
//! above all), the screens' subset of Noto Sans CJK SC. A double-width glyph spans two
//! cells.

use std::path::Path;

use ab_glyph::{Font, FontVec, Glyph, PxScale, ScaleFont as _, point};
use anyhow::Context as _;
use ratatui::buffer::Buffer;
use ratatui::style::Modifier;

use super::canvas::{BACKGROUND, Canvas, FOREGROUND, Rgb, mix, rgb};
use super::shapes::{self, CellBox};
use crate::tr;

/// A cell's size in pixels: DejaVu Sans Mono's advance is 10 pixels at this height.
pub const CELL: (u32, u32) = (10, 20);

/// The fonts, relative to the checkout's root: regular, bold, Chinese.
pub const FONT_FILES: [&str; 3] = [
    "assets/fonts/DejaVuSansMono.ttf",
    "assets/fonts/DejaVuSansMono-Bold.ttf",
    "assets/fonts/PpoTutorSansSCScreens-Regular.otf",
];

/// The command that rebuilds the Chinese screens' font with more characters.
pub const SUBSET_COMMAND: &str =
    "python3 assets/fonts/make_subset.py NotoSansCJK-Regular.ttc screens";

/// The fonts a picture is drawn with.
#[derive(Debug)]
pub struct Fonts {
    regular: FontVec,
    bold: FontVec,
    cjk: FontVec,
}

impl Fonts {
    /// Reads the fonts of [`FONT_FILES`] under `root` (a checkout of ppo-tutor).
    ///
    /// # Errors
    /// A font file is missing or is not a font.
    pub fn load(root: &Path) -> anyhow::Result<Self> {
        let read = |file: &str| -> anyhow::Result<FontVec> {
            let path = root.join(file);
            let shown = path.display();
            let bytes = std::fs::read(&path).with_context(|| {
                tr!(
                    "reading the font {shown} (dev screenshots runs in a checkout of ppo-tutor)",
                    "读取字体 {shown}（dev screenshots 要在 ppo-tutor 的仓库副本中运行）"
                )
            })?;
            FontVec::try_from_vec(bytes).map_err(|_| {
                anyhow::anyhow!(tr!(
                    "{shown} is not a font file: restore it with `git checkout -- {file}`",
                    "{shown} 不是字体文件：请用 `git checkout -- {file}` 恢复"
                ))
            })
        };
        let [regular, bold, cjk] = FONT_FILES;
        Ok(Self {
            regular: read(regular)?,
            bold: read(bold)?,
            cjk: read(cjk)?,
        })
    }
}

/// How one font sits in a cell: its scale and where its baseline is below the cell's top.
struct Face<'a> {
    font: &'a FontVec,
    scale: PxScale,
    baseline: f32,
}

impl<'a> Face<'a> {
    /// A monospace font scaled so that its advance is the cell's width, centred on the
    /// cell's height.
    fn mono(font: &'a FontVec) -> Self {
        let (w, h) = (CELL.0 as f32, CELL.1 as f32);
        let advance = font.h_advance_unscaled(font.glyph_id('M')).max(1.0);
        let px = w * font.height_unscaled() / advance;
        let scaled = font.as_scaled(PxScale::from(px));
        Self {
            font,
            scale: PxScale::from(px),
            baseline: (h - scaled.height()) / 2.0 + scaled.ascent(),
        }
    }

    /// A CJK font whose ideographic em square (0.88 em above the baseline, 0.12 below) is
    /// nine tenths of a double-width cell, centred in it.
    fn cjk(font: &'a FontVec) -> Self {
        let (w, h) = (CELL.0 as f32, CELL.1 as f32);
        let em = (2.0 * w).min(h) * 0.9;
        let units = font.units_per_em().unwrap_or(1000.0);
        let px = em * font.height_unscaled() / units;
        Self {
            font,
            scale: PxScale::from(px),
            baseline: (h - em) / 2.0 + 0.88 * em,
        }
    }

    fn has(&self, c: char) -> bool {
        self.font.glyph_id(c).0 != 0
    }
}

/// How a glyph is drawn beside its colour.
#[derive(Debug, Clone, Copy)]
struct Ink {
    fg: Rgb,
    bold: bool,
    italic: bool,
}

/// Characters that change how their neighbour looks but draw nothing themselves.
fn invisible(c: char) -> bool {
    matches!(u32::from(c), 0x200b..=0x200d | 0x2060 | 0xfe00..=0xfe0f)
}

/// Paints `buffer` as a terminal with the [`CELL`] size and the bundled `fonts` shows it.
///
/// # Errors
/// A character on the screen has a glyph in none of the fonts: the message lists them and
/// says how to add them to the Chinese screens' font.
pub fn paint(buffer: &Buffer, fonts: &Fonts) -> anyhow::Result<Canvas> {
    let area = buffer.area;
    let ch = i64::from(CELL.1);
    let mut canvas = Canvas::new(
        u32::from(area.width) * CELL.0,
        u32::from(area.height) * CELL.1,
        BACKGROUND,
    );
    let (regular, bold, cjk) = (
        Face::mono(&fonts.regular),
        Face::mono(&fonts.bold),
        Face::cjk(&fonts.cjk),
    );
    // Every background first, then every glyph: a glyph may reach into the cell below (an
    // underscore) or beside it, as in a terminal.
    let cells = layout(buffer);
    for cell in &cells {
        let b = cell.px;
        canvas.fill((b.x, b.y), (b.x + b.w, b.y + b.h), cell.bg);
    }
    let mut missing: Vec<char> = Vec::new();
    for cell in &cells {
        let (px, fg, modifier) = (cell.px, cell.fg, cell.modifier);
        if modifier.contains(Modifier::HIDDEN) {
            continue;
        }
        let ink = Ink {
            fg,
            bold: modifier.contains(Modifier::BOLD),
            italic: modifier.contains(Modifier::ITALIC),
        };
        let symbol = cell.symbol.as_str();
        let mut pen = px.x as f32;
        for c in symbol.chars().filter(|&c| c != ' ' && !invisible(c)) {
            if symbol.chars().count() == 1 && shapes::draw(&mut canvas, c, px, fg, ink.bold) {
                continue;
            }
            let mono = if ink.bold { &bold } else { &regular };
            let face = match (cell.columns, mono.has(c), cjk.has(c)) {
                (2, _, true) | (_, false, true) => &cjk,
                (_, true, _) => mono,
                _ => {
                    if !missing.contains(&c) {
                        missing.push(c);
                    }
                    continue;
                }
            };
            pen += glyph(&mut canvas, face, c, (pen, px), ink);
        }
        let line_at = |canvas: &mut Canvas, row: i64| {
            canvas.fill((px.x, px.y + row), (px.x + px.w, px.y + row + 1), fg);
        };
        if modifier.contains(Modifier::UNDERLINED) {
            // Two pixels under the baseline.
            #[allow(clippy::cast_possible_truncation)]
            let row = regular.baseline.round() as i64 + 2;
            line_at(&mut canvas, row.min(ch - 1));
        }
        if modifier.contains(Modifier::CROSSED_OUT) {
            line_at(&mut canvas, ch / 2);
        }
    }
    if missing.is_empty() {
        return Ok(canvas);
    }
    let listed: Vec<String> = missing
        .iter()
        .map(|c| format!("{c} (U+{:04X})", u32::from(*c)))
        .collect();
    let (listed, font, command) = (listed.join(", "), FONT_FILES[2], SUBSET_COMMAND);
    anyhow::bail!(tr!(
        "no glyph in the bundled fonts for {listed}; a Chinese character is added to {font} by \
         `{command}` (assets/fonts/README.md says where the source font comes from)",
        "内置字体中没有这些字符的字形：{listed}；中文字符可用 `{command}` 加入 {font}\
         （源字体从哪里来，见 assets/fonts/README.md）"
    ))
}

/// A cell as it is painted: where, in which colours, what.
struct Placed {
    px: CellBox,
    columns: usize,
    fg: Rgb,
    bg: Rgb,
    modifier: Modifier,
    symbol: String,
}

/// Every cell of `buffer` that is drawn (not the right half of a double-width glyph), with
/// its pixels and its colours after `REVERSED` and `DIM`.
fn layout(buffer: &Buffer) -> Vec<Placed> {
    let area = buffer.area;
    let (cw, ch) = (i64::from(CELL.0), i64::from(CELL.1));
    let mut placed = Vec::new();
    for y in 0..area.height {
        let mut covered = 0_usize;
        for x in 0..area.width {
            if covered > 0 {
                covered -= 1;
                continue;
            }
            let cell = &buffer[(area.x + x, area.y + y)];
            let symbol = cell.symbol();
            let columns = ratatui::text::Span::raw(symbol).width().clamp(1, 2);
            covered = columns - 1;
            let modifier = cell.modifier;
            let (mut fg, mut bg) = (rgb(cell.fg, FOREGROUND), rgb(cell.bg, BACKGROUND));
            if modifier.contains(Modifier::REVERSED) {
                std::mem::swap(&mut fg, &mut bg);
            }
            if modifier.contains(Modifier::DIM) {
                fg = mix(fg, bg, 0.55);
            }
            placed.push(Placed {
                px: CellBox {
                    x: i64::from(x) * cw,
                    y: i64::from(y) * ch,
                    w: cw * i64::try_from(columns).unwrap_or(1),
                    h: ch,
                },
                columns,
                fg,
                bg,
                modifier,
                symbol: symbol.to_string(),
            });
        }
    }
    placed
}

/// Draws `c` from `face` with its pen at `pen` in the cell `px` (centred in the cell when
/// it is the cell's only glyph and narrower or wider than it); returns its advance.
fn glyph(
    canvas: &mut Canvas,
    face: &Face<'_>,
    c: char,
    (pen, px): (f32, CellBox),
    ink: Ink,
) -> f32 {
    let scaled = face.font.as_scaled(face.scale);
    let id = face.font.glyph_id(c);
    let advance = scaled.h_advance(id);
    // A glyph as wide as its cells starts at the pen; others are centred on them.
    let start = if pen == px.x as f32 && (advance - px.w as f32).abs() > 0.5 {
        pen + (px.w as f32 - advance) / 2.0
    } else {
        pen
    };
    let baseline = px.y as f32 + face.baseline;
    let strokes: &[f32] = if ink.bold && face.font.glyph_id('M').0 == 0 {
        // No bold face (the Chinese font): strike twice, a little apart.
        &[0.0, 0.6]
    } else {
        &[0.0]
    };
    for dx in strokes {
        let g: Glyph = id.with_scale_and_position(face.scale, point(start + dx, baseline));
        let Some(outline) = face.font.outline_glyph(g) else {
            continue;
        };
        let bounds = outline.px_bounds();
        outline.draw(|x, y, coverage| {
            let gx = bounds.min.x + x as f32;
            let gy = bounds.min.y + y as f32;
            // Italic: lean right by a fifth of the height above the baseline.
            let lean = if ink.italic {
                (baseline - gy) * 0.2
            } else {
                0.0
            };
            #[allow(clippy::cast_possible_truncation)]
            let (tx, ty) = ((gx + lean).round() as i64, gy.round() as i64);
            canvas.blend(tx, ty, ink.fg, coverage);
        });
    }
    advance
}

#[cfg(test)]
mod tests {
    use super::*;
    use ratatui::layout::Rect;
    use ratatui::style::{Color, Style};

    fn fonts() -> anyhow::Result<Fonts> {
        Fonts::load(Path::new(env!("CARGO_MANIFEST_DIR")))
    }

    /// How many pixels of the cell at column `x`, row `y` differ from `colour`.
    fn not(canvas: &Canvas, (x, y): (u32, u32), colour: Rgb) -> usize {
        let mut n = 0;
        for py in y * CELL.1..(y + 1) * CELL.1 {
            for px in x * CELL.0..(x + 1) * CELL.0 {
                n += usize::from(canvas.pixel(px, py) != Some(colour));
            }
        }
        n
    }

    #[test]
    fn cells_get_their_colours_text_its_glyphs_and_wide_glyphs_two_cells() -> anyhow::Result<()> {
        let fonts = fonts()?;
        let mut buffer = Buffer::empty(Rect::new(0, 0, 8, 2));
        buffer.set_string(0, 0, "a", Style::new().fg(Color::Red).bg(Color::Blue));
        buffer.set_string(2, 0, "回合", Style::new().fg(Color::Green));
        buffer.set_string(0, 1, "─┐", Style::new());
        let canvas = paint(&buffer, &fonts)?;
        assert_eq!((canvas.width, canvas.height), (80, 40));
        let blue = rgb(Color::Blue, BACKGROUND);
        let red = rgb(Color::Red, FOREGROUND);
        // The letter's cell: blue behind, some red ink.
        assert!(not(&canvas, (0, 0), blue) > 5);
        assert!((0..CELL.1).any(|y| (0..CELL.0).any(|x| canvas.pixel(x, y) == Some(red))));
        assert_eq!(
            not(&canvas, (1, 0), BACKGROUND),
            0,
            "an empty cell stays empty"
        );
        // 回 spans columns 2 and 3 (ink in both), 合 columns 4 and 5.
        for column in 2..6 {
            assert!(
                not(&canvas, (column, 0), BACKGROUND) > 10,
                "column {column}"
            );
        }
        assert_eq!(not(&canvas, (6, 0), BACKGROUND), 0);
        // The line (second row) runs on into the corner at the cell's edge.
        let row = CELL.1 + CELL.1 / 2 - 1;
        assert_ne!(canvas.pixel(CELL.0 - 1, row), Some(BACKGROUND));
        assert_ne!(canvas.pixel(CELL.0, row), Some(BACKGROUND));
        Ok(())
    }

    #[test]
    fn bold_reversed_and_missing_glyphs() -> anyhow::Result<()> {
        let fonts = fonts()?;
        let mut buffer = Buffer::empty(Rect::new(0, 0, 3, 1));
        buffer.set_string(0, 0, "l", Style::new());
        buffer.set_string(1, 0, "l", Style::new().add_modifier(Modifier::BOLD));
        buffer.set_string(2, 0, "x", Style::new().add_modifier(Modifier::REVERSED));
        let canvas = paint(&buffer, &fonts)?;
        assert!(not(&canvas, (1, 0), BACKGROUND) > not(&canvas, (0, 0), BACKGROUND));
        // Reversed: the foreground fills the cell, the glyph is cut out of it.
        let cut_out = not(&canvas, (2, 0), FOREGROUND);
        assert!((5..120).contains(&cut_out), "{cut_out}");
        let mut buffer = Buffer::empty(Rect::new(0, 0, 2, 1));
        // A rare character, written as an escape so that the subset (which keeps the
        // characters of the source) never holds it.
        buffer.set_string(0, 0, "\u{9F98}", Style::new());
        let err = paint(&buffer, &fonts)
            .map(|_| ())
            .map_err(|e| e.to_string());
        assert!(
            err.as_ref()
                .is_err_and(|e| e.contains("U+9F98") && e.contains("make_subset.py")),
            "{err:?}"
        );
        Ok(())
    }
}
