//! The picture's pixels: an RGB canvas, the terminal palette a cell's colour is looked up
//! in, and PNG in and out.

use anyhow::Context as _;
use ratatui::style::Color;

/// A colour: red, green, blue.
pub type Rgb = [u8; 3];

/// The default background (a cell with [`Color::Reset`]): a dark terminal's.
pub const BACKGROUND: Rgb = [0x1e, 0x21, 0x27];
/// The default foreground.
pub const FOREGROUND: Rgb = [0xdc, 0xdf, 0xe4];

/// The 16 ANSI colours in ratatui's order (`Black` .. `White`): a dark theme in which
/// `Gray` (dim text) sits below the default foreground and `DarkGray` (borders) well below.
const ANSI: [Rgb; 16] = [
    [0x28, 0x2c, 0x34], // Black
    [0xe0, 0x6c, 0x75], // Red
    [0x98, 0xc3, 0x79], // Green
    [0xe5, 0xc0, 0x7b], // Yellow
    [0x61, 0xaf, 0xef], // Blue
    [0xc6, 0x78, 0xdd], // Magenta
    [0x56, 0xb6, 0xc2], // Cyan
    [0xab, 0xb2, 0xbf], // Gray
    [0x6b, 0x73, 0x81], // DarkGray
    [0xef, 0x88, 0x91], // LightRed
    [0xb5, 0xe0, 0x8f], // LightGreen
    [0xf3, 0xd5, 0x9a], // LightYellow
    [0x8c, 0xca, 0xf7], // LightBlue
    [0xd8, 0x9e, 0xeb], // LightMagenta
    [0x7f, 0xd1, 0xdb], // LightCyan
    [0xf5, 0xf6, 0xf7], // White
];

/// `color` as RGB; [`Color::Reset`] is `default` (the terminal's own foreground or
/// background). Indexed colours follow xterm's 256-colour table.
#[must_use]
pub fn rgb(color: Color, default: Rgb) -> Rgb {
    let ansi = |i: usize| ANSI[i];
    match color {
        Color::Reset => default,
        Color::Black => ansi(0),
        Color::Red => ansi(1),
        Color::Green => ansi(2),
        Color::Yellow => ansi(3),
        Color::Blue => ansi(4),
        Color::Magenta => ansi(5),
        Color::Cyan => ansi(6),
        Color::Gray => ansi(7),
        Color::DarkGray => ansi(8),
        Color::LightRed => ansi(9),
        Color::LightGreen => ansi(10),
        Color::LightYellow => ansi(11),
        Color::LightBlue => ansi(12),
        Color::LightMagenta => ansi(13),
        Color::LightCyan => ansi(14),
        Color::White => ansi(15),
        Color::Rgb(r, g, b) => [r, g, b],
        Color::Indexed(i) => indexed(i),
    }
}

/// xterm's colour `i`: the 16 ANSI colours, the 6×6×6 cube, then 24 greys.
fn indexed(i: u8) -> Rgb {
    match i {
        0..16 => ANSI[usize::from(i)],
        16..232 => {
            let level = |v: u8| if v == 0 { 0 } else { 55 + 40 * v };
            let v = i - 16;
            [level(v / 36), level(v / 6 % 6), level(v % 6)]
        }
        _ => {
            let grey = 8 + 10 * (i - 232);
            [grey; 3]
        }
    }
}

/// `fg` laid over `bg` with opacity `alpha` (0 to 1).
#[must_use]
pub fn mix(fg: Rgb, bg: Rgb, alpha: f32) -> Rgb {
    let a = alpha.clamp(0.0, 1.0);
    let channel = |f: u8, b: u8| {
        let v = f32::from(b) + (f32::from(f) - f32::from(b)) * a;
        // In 0..=255 by the clamp above: the cast cannot wrap.
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let v = v.round() as u8;
        v
    };
    [
        channel(fg[0], bg[0]),
        channel(fg[1], bg[1]),
        channel(fg[2], bg[2]),
    ]
}

/// An RGB image, row after row.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Canvas {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    pixels: Vec<Rgb>,
}

impl Canvas {
    /// A `width`×`height` canvas filled with `colour`.
    #[must_use]
    pub fn new(width: u32, height: u32, colour: Rgb) -> Self {
        let n = usize::try_from(u64::from(width) * u64::from(height)).unwrap_or(0);
        Self {
            width,
            height,
            pixels: vec![colour; n],
        }
    }

    fn index(&self, x: i64, y: i64) -> Option<usize> {
        let (w, h) = (i64::from(self.width), i64::from(self.height));
        ((0..w).contains(&x) && (0..h).contains(&y))
            .then(|| usize::try_from(y * w + x).ok())
            .flatten()
    }

    /// The colour at (`x`, `y`), if inside.
    #[must_use]
    pub fn pixel(&self, x: u32, y: u32) -> Option<Rgb> {
        self.index(i64::from(x), i64::from(y))
            .map(|i| self.pixels[i])
    }

    /// Lays `colour` over the pixel at (`x`, `y`) with opacity `alpha`; outside, nothing.
    pub fn blend(&mut self, x: i64, y: i64, colour: Rgb, alpha: f32) {
        if let Some(i) = self.index(x, y) {
            self.pixels[i] = mix(colour, self.pixels[i], alpha);
        }
    }

    /// Fills the rectangle from (`x0`, `y0`) to (`x1`, `y1`), ends excluded, with `colour`.
    pub fn fill(&mut self, (x0, y0): (i64, i64), (x1, y1): (i64, i64), colour: Rgb) {
        for y in y0..y1 {
            for x in x0..x1 {
                if let Some(i) = self.index(x, y) {
                    self.pixels[i] = colour;
                }
            }
        }
    }

    /// How many pixels differ from `other`'s (every pixel when the sizes differ).
    #[must_use]
    pub fn differing_pixels(&self, other: &Canvas) -> usize {
        if (self.width, self.height) != (other.width, other.height) {
            return self.pixels.len().max(other.pixels.len());
        }
        self.pixels
            .iter()
            .zip(&other.pixels)
            .filter(|(a, b)| a != b)
            .count()
    }

    /// The image as a PNG file (8-bit RGB; the same pixels give the same bytes).
    ///
    /// # Errors
    /// The encoder failed (a bug: the canvas's size and data always agree).
    pub fn png(&self) -> anyhow::Result<Vec<u8>> {
        let mut out = Vec::new();
        let mut encoder = png::Encoder::new(&mut out, self.width, self.height);
        encoder.set_color(png::ColorType::Rgb);
        encoder.set_depth(png::BitDepth::Eight);
        encoder.set_compression(png::Compression::Best);
        encoder.set_filter(png::FilterType::Paeth);
        encoder.set_adaptive_filter(png::AdaptiveFilterType::Adaptive);
        let mut writer = encoder.write_header().context("encoding a PNG header")?;
        let data: Vec<u8> = self.pixels.iter().flatten().copied().collect();
        writer
            .write_image_data(&data)
            .context("encoding a PNG image")?;
        writer.finish().context("finishing a PNG image")?;
        Ok(out)
    }

    /// A PNG file's pixels (any colour type and depth, as 8-bit RGB).
    ///
    /// # Errors
    /// The bytes are not a PNG image.
    pub fn from_png(bytes: &[u8]) -> anyhow::Result<Self> {
        let mut decoder = png::Decoder::new(bytes);
        decoder.set_transformations(png::Transformations::EXPAND | png::Transformations::STRIP_16);
        let mut reader = decoder.read_info()?;
        let mut buf = vec![0; reader.output_buffer_size()];
        let info = reader.next_frame(&mut buf)?;
        let samples = info.color_type.samples();
        let pixels = buf[..info.buffer_size()]
            .chunks_exact(samples)
            .map(|p| match p {
                [g] | [g, _] => [*g; 3],
                [r, g, b, ..] => [*r, *g, *b],
                _ => [0; 3],
            })
            .collect();
        Ok(Self {
            width: info.width,
            height: info.height,
            pixels,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn named_and_indexed_colours_and_the_defaults() {
        assert_eq!(rgb(Color::Reset, BACKGROUND), BACKGROUND);
        assert_eq!(
            rgb(Color::Cyan, BACKGROUND),
            rgb(Color::Indexed(6), FOREGROUND)
        );
        assert_eq!(rgb(Color::Indexed(196), BACKGROUND), [255, 0, 0]);
        assert_eq!(rgb(Color::Indexed(232), BACKGROUND), [8, 8, 8]);
        assert_eq!(rgb(Color::Rgb(1, 2, 3), BACKGROUND), [1, 2, 3]);
        assert_eq!(mix([255, 255, 255], [0, 0, 0], 0.5), [128, 128, 128]);
    }

    #[test]
    fn a_canvas_survives_png_and_counts_its_differences() -> anyhow::Result<()> {
        let mut canvas = Canvas::new(7, 3, BACKGROUND);
        canvas.fill((1, 1), (3, 2), [200, 10, 30]);
        canvas.blend(6, 2, FOREGROUND, 0.25);
        canvas.blend(99, 99, FOREGROUND, 1.0);
        let back = Canvas::from_png(&canvas.png()?)?;
        assert_eq!(back, canvas);
        assert_eq!(back.pixel(2, 1), Some([200, 10, 30]));
        let mut changed = back.clone();
        changed.fill((0, 0), (1, 1), FOREGROUND);
        assert_eq!(changed.differing_pixels(&canvas), 1);
        assert_eq!(Canvas::new(1, 1, BACKGROUND).differing_pixels(&canvas), 21);
        Ok(())
    }
}
