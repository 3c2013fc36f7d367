//! The return curve drawn with characters: `.` per-episode returns, `*` their moving average.
//!
//! ```
//! use ppo_tutor::plot::ascii_return_plot;
//!
//! let returns = [10.0, 20.0, 40.0, 80.0, 160.0];
//! let lines = ascii_return_plot(&returns, &returns, 30, 6);
//! assert!(lines.iter().any(|l| l.contains('*')));
//! ```

/// Draws `returns` (`.`) and `smoothed` (`*`, drawn over) in a `width` x `height` grid of
/// cells, with a y axis from 0 to a round maximum and an x axis of episode numbers.
/// Returns the lines to print, without trailing newlines.
#[must_use]
pub fn ascii_return_plot(
    returns: &[f64],
    smoothed: &[f64],
    width: usize,
    height: usize,
) -> Vec<String> {
    let (width, height) = (width.max(10), height.max(3));
    let top = nice_ceiling(returns.iter().chain(smoothed).copied().fold(0.0, f64::max));
    let mut grid = vec![vec![' '; width]; height];
    let n = returns.len();
    let col = |i: usize| if n > 1 { i * (width - 1) / (n - 1) } else { 0 };
    let row = |v: f64| {
        let frac = (v / top).clamp(0.0, 1.0);
        ((1.0 - frac) * (height - 1) as f64).round() as usize
    };
    for (series, mark) in [(returns, '.'), (smoothed, '*')] {
        for (i, &v) in series.iter().enumerate().filter(|(_, v)| v.is_finite()) {
            grid[row(v)][col(i)] = mark;
        }
    }
    let label_width = format!("{top}").len().max(1);
    let mut lines = Vec::with_capacity(height + 3);
    lines.push(format!(
        "{:>label_width$}  Returns  (. per episode, * moving average)",
        ""
    ));
    for (r, cells) in grid.into_iter().enumerate() {
        let label = if r == 0 {
            format!("{top}")
        } else if r == (height - 1) / 2 && height > 4 {
            format!("{}", top / 2.0)
        } else if r == height - 1 {
            "0".to_string()
        } else {
            String::new()
        };
        let axis = if label.is_empty() { '|' } else { '+' };
        let line: String = cells.into_iter().collect();
        lines.push(format!("{label:>label_width$} {axis}{}", line.trim_end()));
    }
    lines.push(format!("{:>label_width$} +{}", "", "-".repeat(width)));
    let last = format!("{}", n.saturating_sub(1));
    let middle = "Episodes";
    let gap = width.saturating_sub(1 + last.len() + middle.len());
    let (left, right) = (gap / 2, gap - gap / 2);
    lines.push(format!(
        "{:>label_width$}  0{}{middle}{}{last}",
        "",
        " ".repeat(left),
        " ".repeat(right)
    ));
    lines
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
    fn axis_tops_are_round() {
        assert_eq!(nice_ceiling(491.0), 500.0);
        assert_eq!(nice_ceiling(500.0), 500.0);
        assert_eq!(nice_ceiling(23.0), 50.0);
        assert_eq!(nice_ceiling(0.0), 1.0);
    }

    #[test]
    fn a_full_curve_fits_its_box() {
        let returns: Vec<f64> = (0..500).map(f64::from).collect();
        let lines = ascii_return_plot(&returns, &returns, 60, 12);
        assert_eq!(lines.len(), 12 + 3);
        assert!(
            lines.iter().all(|l| l.chars().count() <= 60 + 6),
            "{lines:#?}"
        );
        assert!(lines[1].starts_with("500 +"), "{}", lines[1]);
        assert!(lines.last().is_some_and(|l| l.ends_with("499")));
    }

    #[test]
    fn empty_and_single_episode_runs_draw() {
        assert_eq!(ascii_return_plot(&[], &[], 20, 5).len(), 8);
        assert_eq!(ascii_return_plot(&[9.0], &[9.0], 20, 5).len(), 8);
    }
}
