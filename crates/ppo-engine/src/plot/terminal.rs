//! The return curve drawn with characters: `.` per-episode returns, `*` their moving average
//! (a connected line over the dots, so it reads as the curve); or, for several seeds, their
//! mean curve over the band they span.
//!
//! ```
//! use ppo_engine::plot::ascii_return_plot;
//!
//! let returns = [10.0, 20.0, 40.0, 80.0, 160.0];
//! let lines = ascii_return_plot(&returns, (&returns, 5), 30, 6);
//! assert!(lines.iter().any(|l| l.contains('*')));
//! assert!(lines[0].contains("moving average of 5"));
//! ```

use unicode_width::UnicodeWidthStr;

use super::labels;
use crate::ppo::seeds::Band;

/// Draws `returns` (`.`) and `smoothed`, their moving average over `window` episodes (`*`,
/// drawn over them as a connected line: each column from the previous episode's row to
/// this one's), in a `width` x `height` grid of cells, with a y axis from 0 to a round
/// maximum (from a round minimum to 0 for negative returns, as Pendulum's) and an x axis
/// of episode numbers; the legend says the window.
/// Returns the lines to print, without trailing newlines.
#[must_use]
pub fn ascii_return_plot(
    returns: &[f64],
    (smoothed, window): (&[f64], usize),
    width: usize,
    height: usize,
) -> Vec<String> {
    let mut grid = Grid::new(
        returns.iter().chain(smoothed).copied(),
        returns.len(),
        width,
        height,
    );
    for (i, &v) in returns.iter().enumerate() {
        grid.put(i, v, '.');
    }
    let mut previous = None;
    for (i, &v) in smoothed.iter().enumerate() {
        match previous {
            Some(p) if v.is_finite() => grid.fill(i, f64::min(p, v), f64::max(p, v), '*'),
            _ => grid.put(i, v, '*'),
        }
        previous = v.is_finite().then_some(v);
    }
    grid.lines(&labels::ascii_returns(window))
}

/// Draws several seeds' moving averages over `window` episodes as a band (`:` from the
/// lowest to the highest seed at each episode) with their mean (`*`) over it, on the same
/// axes as [`ascii_return_plot`]; the legend says the window.
#[must_use]
pub fn ascii_band_plot(
    (band, window): (&Band, usize),
    seeds: usize,
    width: usize,
    height: usize,
) -> Vec<String> {
    let mut grid = Grid::new(
        band.high.iter().chain(&band.mean).copied(),
        band.mean.len(),
        width,
        height,
    );
    for (i, (&lo, &hi)) in band.low.iter().zip(&band.high).enumerate() {
        grid.fill(i, lo, hi, ':');
    }
    for (i, &v) in band.mean.iter().enumerate() {
        grid.put(i, v, '*');
    }
    grid.lines(&labels::ascii_band(seeds, window))
}

/// Draws one arm of an experiment against the base arm on the same axes: the arm's band
/// (`:`), its mean (`*`) and the base arm's mean (`o`, drawn last so it stays visible).
#[must_use]
pub fn ascii_versus_plot(
    arm: (&str, &Band),
    base: (&str, &Band),
    seeds: usize,
    width: usize,
    height: usize,
) -> Vec<String> {
    let n = arm.1.mean.len().max(base.1.mean.len());
    let mut grid = Grid::new(
        arm.1.high.iter().chain(&base.1.mean).copied(),
        n,
        width,
        height,
    );
    for (i, (&lo, &hi)) in arm.1.low.iter().zip(&arm.1.high).enumerate() {
        grid.fill(i, lo, hi, ':');
    }
    for (i, &v) in arm.1.mean.iter().enumerate() {
        grid.put(i, v, '*');
    }
    for (i, &v) in base.1.mean.iter().enumerate() {
        grid.put(i, v, 'o');
    }
    grid.lines(&labels::ascii_versus(arm.0, base.0, seeds))
}

/// A character grid with a y axis from 0 to a round maximum (or from a round minimum, for
/// negative values) and `n` episodes across.
struct Grid {
    cells: Vec<Vec<char>>,
    top: f64,
    bottom: f64,
    n: usize,
    width: usize,
    height: usize,
}

impl Grid {
    fn new(values: impl Iterator<Item = f64>, n: usize, width: usize, height: usize) -> Self {
        let (width, height) = (width.max(10), height.max(3));
        let (low, high) = values
            .filter(|v| v.is_finite())
            .fold((0.0, 0.0), |(lo, hi): (f64, f64), v| (lo.min(v), hi.max(v)));
        // Only negative values: the axis ends at 0 (at a round maximum otherwise).
        let top = if low < 0.0 && high <= 0.0 {
            0.0
        } else {
            nice_ceiling(high)
        };
        let bottom = if low < 0.0 { -nice_ceiling(-low) } else { 0.0 };
        Self {
            cells: vec![vec![' '; width]; height],
            top,
            bottom,
            n,
            width,
            height,
        }
    }

    fn col(&self, i: usize) -> usize {
        if self.n > 1 {
            i * (self.width - 1) / (self.n - 1)
        } else {
            0
        }
    }

    fn row(&self, v: f64) -> usize {
        let frac = ((v - self.bottom) / (self.top - self.bottom)).clamp(0.0, 1.0);
        ((1.0 - frac) * (self.height - 1) as f64).round() as usize
    }

    /// Marks episode `i`'s value `v` (nothing for a value that is not finite).
    fn put(&mut self, i: usize, v: f64, mark: char) {
        if v.is_finite() {
            let (r, c) = (self.row(v), self.col(i));
            self.cells[r][c] = mark;
        }
    }

    /// Marks episode `i`'s column from `lo` to `hi`.
    fn fill(&mut self, i: usize, lo: f64, hi: f64, mark: char) {
        if lo.is_finite() && hi.is_finite() {
            let c = self.col(i);
            for r in self.row(hi)..=self.row(lo) {
                self.cells[r][c] = mark;
            }
        }
    }

    /// The lines to print: `legend`, the rows with y labels, the x axis and its labels.
    fn lines(self, legend: &str) -> Vec<String> {
        let Self {
            cells,
            top,
            bottom,
            n,
            width,
            height,
        } = self;
        let label_width = format!("{top}").len().max(format!("{bottom}").len());
        let mut lines = Vec::with_capacity(height + 3);
        lines.push(format!("{:>label_width$}  {legend}", ""));
        for (r, row) in cells.into_iter().enumerate() {
            let label = if r == 0 {
                format!("{top}")
            } else if r == (height - 1) / 2 && height > 4 {
                format!("{}", f64::midpoint(top, bottom))
            } else if r == height - 1 {
                format!("{bottom}")
            } else {
                String::new()
            };
            let axis = if label.is_empty() { '|' } else { '+' };
            let line: String = row.into_iter().collect();
            lines.push(format!("{label:>label_width$} {axis}{}", line.trim_end()));
        }
        lines.push(format!("{:>label_width$} +{}", "", "-".repeat(width)));
        let last = format!("{}", n.saturating_sub(1));
        let middle = labels::episodes();
        // Display columns, not bytes: 回合 is two characters of two columns each.
        let gap = width.saturating_sub(1 + last.len() + display_width(middle));
        let (left, right) = (gap / 2, gap - gap / 2);
        lines.push(format!(
            "{:>label_width$}  0{}{middle}{}{last}",
            "",
            " ".repeat(left),
            " ".repeat(right)
        ));
        lines
    }
}

/// The columns `text` takes in a terminal (`unicode-width`): 2 for a CJK character, 1 for
/// ASCII.
#[must_use]
pub fn display_width(text: &str) -> usize {
    UnicodeWidthStr::width(text)
}

/// The smallest of 1, 2, 5 times a power of ten that is at least `x` (at least 1).
fn nice_ceiling(x: f64) -> f64 {
    if !(x.is_finite() && x > 1.0) {
        return 1.0;
    }
    let base = 10f64.powf(x.log10().floor());
    [1.0, 2.0, 5.0, 10.0]
        .into_iter()
        .map(|m| m * base)
        .find(|&c| c >= x)
        .unwrap_or(10.0 * base)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_band_spans_the_seeds_and_the_mean_is_drawn_over_it() {
        let band = Band::of(&[vec![0.0, 100.0, 200.0], vec![100.0, 300.0, 500.0]]);
        let lines = ascii_band_plot((&band, 9), 2, 21, 11);
        assert!(lines[0].contains("over 2 seeds"), "{}", lines[0]);
        assert!(lines[0].contains("(9 episodes)"), "{}", lines[0]);
        let column = |c: usize| -> String {
            lines[1..12]
                .iter()
                .map(|l| l.chars().nth(5 + c).unwrap_or(' '))
                .collect()
        };
        // The last episode: lowest 200, highest 500 (the top), mean 350, on a 0..500 axis.
        assert_eq!(column(20).trim_end(), ":::*:::", "{lines:#?}");
        assert_eq!(column(0).trim(), ":*:", "{lines:#?}");
    }

    /// The average is a connected line: between two episodes' rows every row of the column
    /// is marked, where the dots of the returns are scattered.
    #[test]
    fn the_average_is_drawn_as_a_connected_line() {
        // A jump from 0 to 100 between episodes 1 and 2, on a 0..100 axis of 11 rows and 10
        // columns (episode i in column 3i).
        let returns = [0.0, 0.0, 100.0, 100.0];
        let lines = ascii_return_plot(&returns, (&returns, 9), 10, 11);
        assert!(lines[0].contains("moving average of 9"), "{}", lines[0]);
        let column = |c: usize| -> String {
            lines[1..12]
                .iter()
                .map(|l| l.chars().nth(5 + c).unwrap_or(' '))
                .collect()
        };
        // Episode 2's column runs from episode 1's row (the bottom) to its own (the top).
        assert_eq!(column(6), "*".repeat(11), "{lines:#?}");
        assert_eq!(column(3).trim(), "*", "{lines:#?}");
        // The returns alone are one dot there.
        let dots = ascii_return_plot(&returns, (&[], 9), 10, 11);
        let dots: String = dots[1..12]
            .iter()
            .map(|l| l.chars().nth(5 + 6).unwrap_or(' '))
            .collect();
        assert_eq!(dots.trim(), ".", "{dots:?}");
    }

    #[test]
    fn axis_tops_are_round() {
        assert_eq!(nice_ceiling(491.0), 500.0);
        assert_eq!(nice_ceiling(500.0), 500.0);
        assert_eq!(nice_ceiling(23.0), 50.0);
        assert_eq!(nice_ceiling(0.0), 1.0);
    }

    #[test]
    fn a_full_curve_fits_its_box() {
        let returns: Vec<f64> = (0..500).map(f64::from).collect();
        let lines = ascii_return_plot(&returns, (&returns, 9), 60, 12);
        assert_eq!(lines.len(), 12 + 3);
        assert!(
            lines.iter().all(|l| l.chars().count() <= 60 + 6),
            "{lines:#?}"
        );
        assert!(lines[1].starts_with("500 +"), "{}", lines[1]);
        assert!(lines.last().is_some_and(|l| l.ends_with("499")));
    }

    /// Pendulum's returns are negative: the axis runs from a round minimum to 0.
    #[test]
    fn negative_returns_hang_below_zero() {
        let returns = [-1200.0, -800.0, -250.0];
        let lines = ascii_return_plot(&returns, (&returns, 9), 21, 11);
        assert!(lines[1].starts_with("    0 +"), "{lines:#?}");
        assert!(lines[6].starts_with("-1000 +"), "{lines:#?}");
        assert!(lines[11].starts_with("-2000 +"), "{lines:#?}");
        // -1200 is row 6 of 0..=10 on a -2000..0 axis; -250 is row 1.
        assert_eq!(lines[7].chars().nth(7), Some('*'), "{lines:#?}");
        assert_eq!(lines[2].chars().nth(7 + 20), Some('*'), "{lines:#?}");
    }

    #[test]
    fn empty_and_single_episode_runs_draw() {
        assert_eq!(ascii_return_plot(&[], (&[], 1), 20, 5).len(), 8);
        assert_eq!(ascii_return_plot(&[9.0], (&[9.0], 1), 20, 5).len(), 8);
    }
}
