//! The characters a terminal draws itself rather than from its font, so that they fill the
//! cell edge to edge: box drawing (U+2500–U+257F: borders and axes join across cells),
//! block elements (U+2580–U+259F: the clip chart's markers, bars) and Braille patterns
//! (U+2800–U+28FF: the plots' dots, crisp on a 2×4 grid).

use super::canvas::{Canvas, Rgb};

/// A cell's rectangle in pixels.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct CellBox {
    /// Left edge.
    pub x: i64,
    /// Top edge.
    pub y: i64,
    /// Width.
    pub w: i64,
    /// Height.
    pub h: i64,
}

/// Draws `c` in `cell` with `fg` if it is one of the characters drawn here (`bold` makes
/// light lines heavy, as terminals do); false for any other character.
pub fn draw(canvas: &mut Canvas, c: char, cell: CellBox, fg: Rgb, bold: bool) -> bool {
    let code = u32::from(c);
    match code {
        0x2500..=0x257f => box_drawing(canvas, c, cell, fg, bold),
        0x2580..=0x259f => {
            block(canvas, code, cell, fg);
            true
        }
        0x2800..=0x28ff => {
            braille(canvas, code - 0x2800, cell, fg);
            true
        }
        _ => false,
    }
}

/// A line's weight toward one side of the cell.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum W {
    /// No line.
    N,
    /// Light.
    L,
    /// Heavy.
    H,
    /// Double.
    D,
}

/// The weights of a box-drawing character's lines toward up, right, down and left (None for
/// the dashed, rounded and diagonal ones, drawn apart).
fn arms(c: char) -> Option<[W; 4]> {
    use W::{D, H, L, N};
    Some(match c {
        '─' => [N, L, N, L],
        '━' => [N, H, N, H],
        '│' => [L, N, L, N],
        '┃' => [H, N, H, N],
        '┌' => [N, L, L, N],
        '┍' => [N, H, L, N],
        '┎' => [N, L, H, N],
        '┏' => [N, H, H, N],
        '┐' => [N, N, L, L],
        '┑' => [N, N, L, H],
        '┒' => [N, N, H, L],
        '┓' => [N, N, H, H],
        '└' => [L, L, N, N],
        '┕' => [L, H, N, N],
        '┖' => [H, L, N, N],
        '┗' => [H, H, N, N],
        '┘' => [L, N, N, L],
        '┙' => [L, N, N, H],
        '┚' => [H, N, N, L],
        '┛' => [H, N, N, H],
        '├' => [L, L, L, N],
        '┝' => [L, H, L, N],
        '┞' => [H, L, L, N],
        '┟' => [L, L, H, N],
        '┠' => [H, L, H, N],
        '┡' => [H, H, L, N],
        '┢' => [L, H, H, N],
        '┣' => [H, H, H, N],
        '┤' => [L, N, L, L],
        '┥' => [L, N, L, H],
        '┦' => [H, N, L, L],
        '┧' => [L, N, H, L],
        '┨' => [H, N, H, L],
        '┩' => [H, N, L, H],
        '┪' => [L, N, H, H],
        '┫' => [H, N, H, H],
        '┬' => [N, L, L, L],
        '┭' => [N, L, L, H],
        '┮' => [N, H, L, L],
        '┯' => [N, H, L, H],
        '┰' => [N, L, H, L],
        '┱' => [N, L, H, H],
        '┲' => [N, H, H, L],
        '┳' => [N, H, H, H],
        '┴' => [L, L, N, L],
        '┵' => [L, L, N, H],
        '┶' => [L, H, N, L],
        '┷' => [L, H, N, H],
        '┸' => [H, L, N, L],
        '┹' => [H, L, N, H],
        '┺' => [H, H, N, L],
        '┻' => [H, H, N, H],
        '┼' => [L, L, L, L],
        '┽' => [L, L, L, H],
        '┾' => [L, H, L, L],
        '┿' => [L, H, L, H],
        '╀' => [H, L, L, L],
        '╁' => [L, L, H, L],
        '╂' => [H, L, H, L],
        '╃' => [H, L, L, H],
        '╄' => [H, H, L, L],
        '╅' => [L, L, H, H],
        '╆' => [L, H, H, L],
        '╇' => [H, H, L, H],
        '╈' => [L, H, H, H],
        '╉' => [H, L, H, H],
        '╊' => [H, H, H, L],
        '╋' => [H, H, H, H],
        '═' => [N, D, N, D],
        '║' => [D, N, D, N],
        '╒' => [N, D, L, N],
        '╓' => [N, L, D, N],
        '╔' => [N, D, D, N],
        '╕' => [N, N, L, D],
        '╖' => [N, N, D, L],
        '╗' => [N, N, D, D],
        '╘' => [L, D, N, N],
        '╙' => [D, L, N, N],
        '╚' => [D, D, N, N],
        '╛' => [L, N, N, D],
        '╜' => [D, N, N, L],
        '╝' => [D, N, N, D],
        '╞' => [L, D, L, N],
        '╟' => [D, L, D, N],
        '╠' => [D, D, D, N],
        '╡' => [L, N, L, D],
        '╢' => [D, N, D, L],
        '╣' => [D, N, D, D],
        '╤' => [N, D, L, D],
        '╥' => [N, L, D, L],
        '╦' => [N, D, D, D],
        '╧' => [L, D, N, D],
        '╨' => [D, L, N, L],
        '╩' => [D, D, N, D],
        '╪' => [L, D, L, D],
        '╫' => [D, L, D, L],
        '╬' => [D, D, D, D],
        '╴' => [N, N, N, L],
        '╵' => [L, N, N, N],
        '╶' => [N, L, N, N],
        '╷' => [N, N, L, N],
        '╸' => [N, N, N, H],
        '╹' => [H, N, N, N],
        '╺' => [N, H, N, N],
        '╻' => [N, N, H, N],
        '╼' => [N, H, N, L],
        '╽' => [L, N, H, N],
        '╾' => [N, L, N, H],
        '╿' => [H, N, L, N],
        _ => return None,
    })
}

/// Line thicknesses and positions across one axis of a cell `size` pixels long.
#[derive(Debug, Clone, Copy)]
struct Axis {
    size: i64,
    light: i64,
    heavy: i64,
    /// Half the distance between a double line's two strokes.
    gap: i64,
}

impl Axis {
    fn new(size: i64, light: i64, heavy: i64, gap: i64) -> Self {
        Self {
            size,
            light,
            heavy,
            gap,
        }
    }

    /// Where a light stroke on the middle starts.
    fn middle(self) -> i64 {
        (self.size - self.light) / 2
    }

    /// The pixels a line of weight `w` covers across this axis: `[start, end)`.
    fn span(self, w: W) -> Option<(i64, i64)> {
        let band = |t: i64| ((self.size - t) / 2, (self.size - t) / 2 + t);
        match w {
            W::N => None,
            W::L => Some(band(self.light)),
            W::H => Some(band(self.heavy)),
            W::D => Some((
                self.middle() - self.gap,
                self.middle() + self.gap + self.light,
            )),
        }
    }
}

/// The union of the spans of `ws` (None when none has a line).
fn union(axis: Axis, ws: &[W]) -> Option<(i64, i64)> {
    ws.iter()
        .filter_map(|w| axis.span(*w))
        .reduce(|(a, b), (c, d)| (a.min(c), b.max(d)))
}

/// One arm: a line from the cell's middle toward one side, in a frame where the arm runs
/// along `along` toward its end (`toward_end`: right or down) and `across` is the other
/// axis; `side` are the perpendicular arms (before, after) across it.
struct Arm {
    weight: W,
    toward_end: bool,
    side: (W, W),
    /// Whether the arm on the opposite side of the cell has a line.
    opposite: bool,
}

/// The `[start, end)` along the arm's axis of each stroke of `arm`, with the stroke's
/// `[start, end)` across it.
fn strokes(arm: &Arm, along: Axis, across: Axis) -> Vec<((i64, i64), (i64, i64))> {
    // The extent along the arm: from the cell's edge to where it meets the perpendicular
    // lines (or the middle), for a stroke lying at `at` across.
    let reach = |meet: (i64, i64)| {
        if arm.toward_end {
            (meet.0, along.size)
        } else {
            (0, meet.1)
        }
    };
    let (before, after) = arm.side;
    if arm.weight != W::D {
        let Some(across_span) = across.span(arm.weight) else {
            return Vec::new();
        };
        let meet = union(along, &[before, after]).unwrap_or(
            along
                .span(arm.weight)
                .unwrap_or((along.middle(), along.middle())),
        );
        return vec![(reach(meet), across_span)];
    }
    // A double arm: two light strokes. Each stops at the near stroke of a double line on
    // its own side (an inner corner), at a single line there, or, with nothing on its side,
    // runs on to the far stroke of the other side's line (an outer corner).
    let m = along.middle();
    let stop = |own: W, other: W| -> (i64, i64) {
        let near_double = (m + along.gap, m - along.gap);
        match (own, other) {
            (W::D, _) => {
                if arm.toward_end {
                    (near_double.0, near_double.0 + along.light)
                } else {
                    (near_double.1, near_double.1 + along.light)
                }
            }
            (W::L | W::H, _) => along.span(own).unwrap_or((m, m + along.light)),
            (W::N, W::D) => {
                if arm.toward_end {
                    (m - along.gap, m - along.gap + along.light)
                } else {
                    (m + along.gap, m + along.gap + along.light)
                }
            }
            (W::N, o) => along.span(o).unwrap_or(if arm.opposite {
                (m, m + along.light)
            } else {
                (m - along.gap, m + along.gap + along.light)
            }),
        }
    };
    let a = across.middle();
    vec![
        (
            reach(stop(before, after)),
            (a - across.gap, a - across.gap + across.light),
        ),
        (
            reach(stop(after, before)),
            (a + across.gap, a + across.gap + across.light),
        ),
    ]
}

fn box_drawing(canvas: &mut Canvas, c: char, cell: CellBox, fg: Rgb, bold: bool) -> bool {
    let light = (cell.w / 8).max(1);
    let heavy = light * 2 + 1;
    let gap = (cell.w / 5).max(light + 1);
    let (xs, ys) = (
        Axis::new(cell.w, light, heavy, gap),
        Axis::new(cell.h, light, heavy, gap),
    );
    let Some(mut weights) = arms(c) else {
        return special_box(canvas, c, cell, fg, (xs, ys));
    };
    if bold {
        for w in &mut weights {
            if *w == W::L {
                *w = W::H;
            }
        }
    }
    let [up, right, down, left] = weights;
    let fill = |canvas: &mut Canvas, (x0, x1): (i64, i64), (y0, y1): (i64, i64)| {
        canvas.fill((cell.x + x0, cell.y + y0), (cell.x + x1, cell.y + y1), fg);
    };
    // Horizontal arms: along x, across y, their sides the vertical arms (up before down).
    for (weight, toward_end, opposite) in
        [(right, true, left != W::N), (left, false, right != W::N)]
    {
        let arm = Arm {
            weight,
            toward_end,
            side: (up, down),
            opposite,
        };
        for (along, across) in strokes(&arm, xs, ys) {
            fill(canvas, along, across);
        }
    }
    // Vertical arms: along y, across x, their sides the horizontal arms (left before right).
    for (weight, toward_end, opposite) in [(down, true, up != W::N), (up, false, down != W::N)] {
        let arm = Arm {
            weight,
            toward_end,
            side: (left, right),
            opposite,
        };
        for (along, across) in strokes(&arm, ys, xs) {
            fill(canvas, across, along);
        }
    }
    true
}

/// The dashed lines, the rounded corners and the diagonals.
fn special_box(
    canvas: &mut Canvas,
    c: char,
    cell: CellBox,
    fg: Rgb,
    (xs, ys): (Axis, Axis),
) -> bool {
    // Dashed: (dashes, heavy, horizontal).
    let dashed = match c {
        '┄' => Some((3, false, true)),
        '┅' => Some((3, true, true)),
        '┆' => Some((3, false, false)),
        '┇' => Some((3, true, false)),
        '┈' => Some((4, false, true)),
        '┉' => Some((4, true, true)),
        '┊' => Some((4, false, false)),
        '┋' => Some((4, true, false)),
        '╌' => Some((2, false, true)),
        '╍' => Some((2, true, true)),
        '╎' => Some((2, false, false)),
        '╏' => Some((2, true, false)),
        _ => None,
    };
    if let Some((n, heavy, horizontal)) = dashed {
        let weight = if heavy { W::H } else { W::L };
        let (along, across) = if horizontal { (xs, ys) } else { (ys, xs) };
        let Some((a0, a1)) = across.span(weight) else {
            return false;
        };
        for i in 0..n {
            let (s, e) = (along.size * i / n, along.size * (i + 1) / n);
            let gap = ((e - s) / 4).max(1);
            let (s, e) = (s + gap / 2, e - (gap - gap / 2));
            let ((x0, x1), (y0, y1)) = if horizontal {
                ((s, e), (a0, a1))
            } else {
                ((a0, a1), (s, e))
            };
            canvas.fill((cell.x + x0, cell.y + y0), (cell.x + x1, cell.y + y1), fg);
        }
        return true;
    }
    let (w, h) = (cell.w as f32, cell.h as f32);
    let half = xs.light as f32 / 2.0;
    // The middle of a light line, across each axis.
    let (mx, my) = (xs.middle() as f32 + half, ys.middle() as f32 + half);
    match c {
        '╭' | '╮' | '╯' | '╰' => {
            // A quarter circle joining the middles of two sides, tangent to both lines.
            let r = (w / 2.0).min(h / 2.0);
            let (sx, sy) = match c {
                '╭' => (1.0, 1.0),
                '╮' => (-1.0, 1.0),
                '╯' => (-1.0, -1.0),
                _ => (1.0, -1.0),
            };
            let centre = (mx + sx * r, my + sy * r);
            cover(canvas, cell, fg, |x, y| {
                let (dx, dy) = (x - centre.0, y - centre.1);
                let in_quadrant = dx * sx <= 0.0 && dy * sy <= 0.0;
                let d = if in_quadrant {
                    ((dx * dx + dy * dy).sqrt() - r).abs()
                } else if dx * sx > 0.0 && dy * sy <= 0.0 {
                    // Beside the arc, along the horizontal line.
                    (y - my).abs()
                } else if dy * sy > 0.0 && dx * sx <= 0.0 {
                    (x - mx).abs()
                } else {
                    f32::INFINITY
                };
                d <= half
            });
            true
        }
        '╱' | '╲' | '╳' => {
            let rising = |x: f32, y: f32| segment_distance((x, y), (w, 0.0), (0.0, h)) <= half;
            let falling = |x: f32, y: f32| segment_distance((x, y), (0.0, 0.0), (w, h)) <= half;
            cover(canvas, cell, fg, |x, y| match c {
                '╱' => rising(x, y),
                '╲' => falling(x, y),
                _ => rising(x, y) || falling(x, y),
            });
            true
        }
        _ => false,
    }
}

/// The distance from `p` to the segment from `a` to `b`.
fn segment_distance(p: (f32, f32), a: (f32, f32), b: (f32, f32)) -> f32 {
    let (vx, vy) = (b.0 - a.0, b.1 - a.1);
    let t = (((p.0 - a.0) * vx + (p.1 - a.1) * vy) / (vx * vx + vy * vy)).clamp(0.0, 1.0);
    let (dx, dy) = (p.0 - a.0 - t * vx, p.1 - a.1 - t * vy);
    (dx * dx + dy * dy).sqrt()
}

/// Paints the pixels of `cell` with `fg` in proportion to how much of each `inside` covers
/// (4×4 samples a pixel; coordinates relative to the cell).
fn cover(canvas: &mut Canvas, cell: CellBox, fg: Rgb, inside: impl Fn(f32, f32) -> bool) {
    const N: i64 = 4;
    for py in 0..cell.h {
        for px in 0..cell.w {
            let mut hits = 0_u8;
            for sy in 0..N {
                for sx in 0..N {
                    let x = px as f32 + (sx as f32 + 0.5) / N as f32;
                    let y = py as f32 + (sy as f32 + 0.5) / N as f32;
                    hits += u8::from(inside(x, y));
                }
            }
            if hits > 0 {
                canvas.blend(cell.x + px, cell.y + py, fg, f32::from(hits) / 16.0);
            }
        }
    }
}

/// Block elements: eighths from the bottom or the left, halves, quadrants and shades.
fn block(canvas: &mut Canvas, code: u32, cell: CellBox, fg: Rgb) {
    let (w, h) = (cell.w, cell.h);
    let mut rect = |(x0, y0): (i64, i64), (x1, y1): (i64, i64)| {
        canvas.fill((cell.x + x0, cell.y + y0), (cell.x + x1, cell.y + y1), fg);
    };
    let eighth = |n: i64, of: i64| (of * n + 4) / 8;
    // Quadrants: upper left, upper right, lower left, lower right.
    let quadrants = |bits: [bool; 4], rect: &mut dyn FnMut((i64, i64), (i64, i64))| {
        let (hw, hh) = (w / 2, h / 2);
        let boxes = [
            ((0, 0), (hw, hh)),
            ((hw, 0), (w, hh)),
            ((0, hh), (hw, h)),
            ((hw, hh), (w, h)),
        ];
        for (on, (a, b)) in bits.iter().zip(boxes) {
            if *on {
                rect(a, b);
            }
        }
    };
    match code {
        0x2580 => rect((0, 0), (w, h / 2)),
        // ▁ to █: n eighths from the bottom.
        0x2581..=0x2588 => {
            let n = i64::from(code - 0x2580);
            rect((0, h - eighth(n, h)), (w, h));
        }
        // ▉ to ▏: 7 to 1 eighths from the left.
        0x2589..=0x258f => {
            let n = 8 - i64::from(code - 0x2588);
            rect((0, 0), (eighth(n, w), h));
        }
        0x2590 => rect((w / 2, 0), (w, h)),
        0x2591..=0x2593 => {
            let alpha = f32::from(u8::try_from(code - 0x2590).unwrap_or(0)) / 4.0;
            for y in 0..h {
                for x in 0..w {
                    canvas.blend(cell.x + x, cell.y + y, fg, alpha);
                }
            }
        }
        0x2594 => rect((0, 0), (w, eighth(1, h))),
        0x2595 => rect((w - eighth(1, w), 0), (w, h)),
        _ => {
            let bits = match code {
                0x2596 => [false, false, true, false],
                0x2597 => [false, false, false, true],
                0x2598 => [true, false, false, false],
                0x2599 => [true, false, true, true],
                0x259a => [true, false, false, true],
                0x259b => [true, true, true, false],
                0x259c => [true, true, false, true],
                0x259d => [false, true, false, false],
                0x259e => [false, true, true, false],
                _ => [false, true, true, true],
            };
            quadrants(bits, &mut rect);
        }
    }
}

/// A Braille pattern: its eight dots (bit i of `bits` is dot i + 1) on a 2×4 grid, round.
fn braille(canvas: &mut Canvas, bits: u32, cell: CellBox, fg: Rgb) {
    // Dots 1-3 and 7 down the left column, 4-6 and 8 down the right.
    const DOTS: [(u8, u8); 8] = [
        (0, 0),
        (0, 1),
        (0, 2),
        (1, 0),
        (1, 1),
        (1, 2),
        (0, 3),
        (1, 3),
    ];
    let (w, h) = (cell.w as f32, cell.h as f32);
    let radius = (w / 4.0).min(h / 8.0) * 0.8;
    let centres: Vec<(f32, f32)> = DOTS
        .iter()
        .enumerate()
        .filter(|(i, _)| bits & (1 << i) != 0)
        .map(|(_, &(col, row))| {
            (
                w * (1.0 + 2.0 * f32::from(col)) / 4.0,
                h * (1.0 + 2.0 * f32::from(row)) / 8.0,
            )
        })
        .collect();
    if centres.is_empty() {
        return;
    }
    cover(canvas, cell, fg, |x, y| {
        centres
            .iter()
            .any(|(cx, cy)| (x - cx) * (x - cx) + (y - cy) * (y - cy) <= radius * radius)
    });
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::screenshot::canvas::BACKGROUND;

    const FG: Rgb = [255, 255, 255];
    const CELL: CellBox = CellBox {
        x: 0,
        y: 0,
        w: 10,
        h: 20,
    };

    /// One cell drawn with `c`: which pixels are lit (any of the foreground).
    fn lit(c: char) -> Vec<Vec<bool>> {
        let mut canvas = Canvas::new(10, 20, BACKGROUND);
        assert!(draw(&mut canvas, c, CELL, FG, false), "{c} not drawn");
        (0..20)
            .map(|y| {
                (0..10)
                    .map(|x| canvas.pixel(x, y) != Some(BACKGROUND))
                    .collect()
            })
            .collect()
    }

    fn edges(c: char) -> [bool; 4] {
        let p = lit(c);
        [
            p[0].iter().any(|&b| b),
            p.iter().any(|row| row[9]),
            p[19].iter().any(|&b| b),
            p.iter().any(|row| row[0]),
        ]
    }

    #[test]
    fn lines_reach_exactly_the_edges_they_name_so_neighbours_join() {
        for (c, expected) in [
            ('─', [false, true, false, true]),
            ('│', [true, false, true, false]),
            ('┌', [false, true, true, false]),
            ('┘', [true, false, false, true]),
            ('┼', [true, true, true, true]),
            ('╔', [false, true, true, false]),
            ('╭', [false, true, true, false]),
            ('╶', [false, true, false, false]),
        ] {
            assert_eq!(edges(c), expected, "{c}");
        }
        // A horizontal line and a vertical one meet a corner on the same row and column.
        let (h, v, corner) = (lit('─'), lit('│'), lit('┌'));
        let row = |p: &Vec<Vec<bool>>| p.iter().position(|r| r[9]);
        let col = |p: &Vec<Vec<bool>>| p[19].iter().position(|&b| b);
        assert_eq!(row(&h), row(&corner));
        assert_eq!(col(&v), col(&corner));
        // A light line is one pixel across, a heavy one more.
        assert_eq!(lit('─').iter().filter(|r| r[5]).count(), 1);
        assert!(lit('━').iter().filter(|r| r[5]).count() > 1);
        // Double lines: two strokes.
        let double = lit('═');
        assert_eq!(double.iter().filter(|r| r[5]).count(), 2);
    }

    #[test]
    fn blocks_fill_their_part_and_braille_its_dots() {
        let full = lit('█');
        assert!(full.iter().flatten().all(|&b| b));
        let lower = lit('▄');
        assert!(lower[..10].iter().flatten().all(|&b| !b));
        assert!(lower[10..].iter().flatten().all(|&b| b));
        // ⠁ is dot 1 (top left), ⢀ dot 8 (bottom right).
        let top_left = lit('⠁');
        assert!(top_left[2][2] && !top_left[17][7]);
        let bottom_right = lit('⢀');
        assert!(bottom_right[17][7] && !bottom_right[2][2]);
        let all = lit('⣿');
        assert_eq!(
            all.iter().flatten().filter(|&&b| b).count(),
            8 * top_left.iter().flatten().filter(|&&b| b).count()
        );
        let mut canvas = Canvas::new(10, 20, BACKGROUND);
        assert!(!draw(&mut canvas, 'a', CELL, FG, false));
    }
}
