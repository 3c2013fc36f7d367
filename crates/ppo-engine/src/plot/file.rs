//! The seed's figure (`plt.plot(episodes_list, return_list)`, then the moving average,
//! xlabel "Episodes", ylabel "Returns", title "PPO on CartPole-v1") drawn with plotters.
//!
//! The format follows the file extension: `.svg` or `.png`. The labels come from
//! [`labels`] in the current language. English text is set in DejaVu Sans, Chinese text in
//! PPO Tutor Sans SC (a subset of Noto Sans CJK SC with the labels' characters, see
//! `assets/fonts/README.md`), both shipped in `assets/` and compiled in, so no system font
//! is needed.

use std::path::Path;
use std::sync::Once;

use plotters::prelude::*;
use plotters::style::FontStyle;

use super::labels;
use crate::i18n::Lang;
use crate::ppo::seeds::Band;

/// The font of English labels (DejaVu Sans, Bitstream Vera license: assets/DejaVuSans-LICENSE.txt).
static FONT: &[u8] = include_bytes!("../../../../assets/DejaVuSans.ttf");
/// The font of Chinese labels: PPO Tutor Sans SC, a subset of Noto Sans CJK SC with the
/// characters of the Chinese labels (SIL OFL 1.1: assets/fonts/OFL.txt).
pub static FONT_ZH: &[u8] = include_bytes!("../../../../assets/fonts/PpoTutorSansSC-Regular.otf");
/// The family Chinese figures name: the bundled font is registered under it for PNGs, and
/// in an SVG it is a CSS font list, so a browser picks a Chinese font the reader has.
const FAMILY_ZH: &str =
    "Noto Sans CJK SC, Source Han Sans SC, PingFang SC, Microsoft YaHei, sans-serif";
static REGISTER: Once = Once::new();

/// What can go wrong writing a figure.
#[derive(Debug, thiserror::Error)]
pub enum PlotError {
    /// The extension is neither `.png` nor `.svg`.
    #[error("{path}: cannot tell the format from the extension; use FILE.png or FILE.svg")]
    UnknownFormat {
        /// The path given.
        path: String,
    },
    /// plotters failed (usually: the file could not be written).
    #[error("{path}: could not draw the figure: {reason}")]
    Draw {
        /// The path given.
        path: String,
        /// plotters' message.
        reason: String,
    },
}

fn register_font() {
    REGISTER.call_once(|| {
        // The bytes are a valid TrueType file compiled in; a failure would only lose text.
        let _ = plotters::style::register_font("sans-serif", FontStyle::Normal, FONT);
        let _ = plotters::style::register_font(FAMILY_ZH, FontStyle::Normal, FONT_ZH);
    });
}

/// The font family of the current language's labels.
fn family() -> &'static str {
    Lang::current().pick("sans-serif", FAMILY_ZH)
}

/// Writes the return curve and its moving average over `window` episodes (the legend says
/// how many: [`super::window`]) to `path` (`.png`, 1000x600, or `.svg`).
///
/// # Errors
/// [`PlotError::UnknownFormat`] for another extension; [`PlotError::Draw`] when writing fails.
pub fn save_return_plot(
    path: &Path,
    title: &str,
    returns: &[f64],
    (smoothed, window): (&[f64], usize),
) -> Result<(), PlotError> {
    save_return_plot_over(path, title, returns, (smoothed, window), XAxis::Episodes)
}

/// What a return curve is drawn against.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum XAxis<'a> {
    /// The episode's number, 0 first.
    Episodes,
    /// The environment steps taken when each episode ended (a run's
    /// `TrainSummary::episode_end_steps`, one per return): the axis on which runs with
    /// different rollouts, or different episode lengths, compare.
    Steps(&'a [u64]),
}

/// [`save_return_plot`] against `x`: episodes, or the environment steps at which each
/// episode ended.
///
/// # Errors
/// As [`save_return_plot`]; [`PlotError::Draw`] when `x` has another length than `returns`.
pub fn save_return_plot_over(
    path: &Path,
    title: &str,
    returns: &[f64],
    (smoothed, window): (&[f64], usize),
    x: XAxis<'_>,
) -> Result<(), PlotError> {
    if let XAxis::Steps(steps) = x
        && steps.len() != returns.len()
    {
        return Err(PlotError::Draw {
            path: path.display().to_string(),
            reason: crate::tr!(
                "{} step counts for {} returns: pass one per episode",
                "{} 个步数对应 {} 个回报：每个回合应有一个步数",
                steps.len(),
                returns.len()
            ),
        });
    }
    save(
        path,
        title,
        Figure::Curve {
            returns,
            smoothed,
            window,
            x,
        },
    )
}

/// Writes several seeds' curves to `path` (`.png` or `.svg`, as [`save_return_plot`]):
/// their mean as a line over the band from the lowest to the highest seed.
///
/// # Errors
/// As [`save_return_plot`].
pub fn save_band_plot(
    path: &Path,
    title: &str,
    band: &Band,
    seeds: usize,
) -> Result<(), PlotError> {
    save(path, title, Figure::Band { band, seeds })
}

/// Writes a lab experiment to `path` (`.png` or `.svg`, as [`save_return_plot`]): each
/// arm's mean curve over its min–max band, in its own colour, base arm first.
///
/// # Errors
/// As [`save_return_plot`].
pub fn save_lab_plot(
    path: &Path,
    title: &str,
    arms: &[(&str, &Band)],
    seeds: usize,
) -> Result<(), PlotError> {
    save(path, title, Figure::Arms { arms, seeds })
}

/// The figure of [`save_lab_plot`] as an SVG document in memory (800x480), for notebooks.
///
/// # Errors
/// [`PlotError::Draw`] if plotters fails.
pub fn lab_plot_svg(
    title: &str,
    arms: &[(&str, &Band)],
    seeds: usize,
) -> Result<String, PlotError> {
    svg_string((800, 480), |root| {
        draw(root, title, Figure::Arms { arms, seeds })
    })
}

/// What a return figure shows.
#[derive(Clone, Copy)]
enum Figure<'a> {
    /// One run: the returns and their moving average over `window` episodes.
    Curve {
        returns: &'a [f64],
        smoothed: &'a [f64],
        window: usize,
        x: XAxis<'a>,
    },
    /// Several seeds: the mean of their curves over the min–max band.
    Band { band: &'a Band, seeds: usize },
    /// Several settings, each over several seeds: a band and a mean per setting.
    Arms {
        arms: &'a [(&'a str, &'a Band)],
        seeds: usize,
    },
}

/// Draws `figure` into a temporary file beside `path` and renames it over `path` once it
/// is whole; on any failure the temporary file goes and `path` is left as it was.
fn save(path: &Path, title: &str, figure: Figure<'_>) -> Result<(), PlotError> {
    register_font();
    let shown = path.display().to_string();
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    let draw_err = |e: &dyn std::fmt::Display| PlotError::Draw {
        path: shown.clone(),
        reason: e.to_string(),
    };
    // The temporary file ends like `path`: the PNG encoder picks its format by the name.
    let tmp = crate::files::temporary_sibling(path);
    let drawn = match ext.as_deref() {
        Some("svg") => {
            let root = SVGBackend::new(&tmp, (1000, 600)).into_drawing_area();
            draw(&root, title, figure)
                .map_err(|e| draw_err(&e))
                .and_then(|()| root.present().map_err(|e| draw_err(&e)))
        }
        Some("png") => {
            let root = BitMapBackend::new(&tmp, (1000, 600)).into_drawing_area();
            draw(&root, title, figure)
                .map_err(|e| draw_err(&e))
                .and_then(|()| root.present().map_err(|e| draw_err(&e)))
        }
        _ => return Err(PlotError::UnknownFormat { path: shown }),
    };
    let saved = drawn.and_then(|()| std::fs::rename(&tmp, path).map_err(|e| draw_err(&e)));
    if saved.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    saved
}

/// The same figure as [`save_return_plot`], as an SVG document in memory (800x480), for
/// notebooks and web pages: `smoothed` is the seed's moving average over
/// [`SMOOTHING_WINDOW`](super::SMOOTHING_WINDOW) episodes, a [`Snapshot`]'s.
///
/// [`Snapshot`]: crate::lesson::Snapshot
///
/// # Errors
/// [`PlotError::Draw`] if plotters fails.
pub fn return_plot_svg(
    title: &str,
    returns: &[f64],
    smoothed: &[f64],
) -> Result<String, PlotError> {
    let window = super::SMOOTHING_WINDOW;
    svg_string((800, 480), |root| {
        draw(
            root,
            title,
            Figure::Curve {
                returns,
                smoothed,
                window,
                x: XAxis::Episodes,
            },
        )
    })
}

/// The clip chart as an SVG document (640x400): `L^CLIP(r)` for a unit advantage of each
/// sign, the band `[1 − ε, 1 + ε]` shaded, and each `(ratio, advantage)` row of a batch at
/// `(r, min(surr1, surr2) / |A|)` (rows with a zero advantage are left out).
///
/// # Errors
/// [`PlotError::Draw`] if plotters fails.
pub fn clip_chart_svg(eps: f64, rows: &[(f64, f64)]) -> Result<String, PlotError> {
    svg_string((640, 400), |root| draw_clip(root, eps, rows))
}

/// Draws a figure of `size` with `paint` into an SVG document in memory.
fn svg_string<F>(size: (u32, u32), paint: F) -> Result<String, PlotError>
where
    F: FnOnce(
        &DrawingArea<SVGBackend<'_>, plotters::coord::Shift>,
    ) -> Result<(), DrawingAreaErrorKind<std::io::Error>>,
{
    register_font();
    let draw_err = |e: &dyn std::fmt::Display| PlotError::Draw {
        path: "(in memory)".into(),
        reason: e.to_string(),
    };
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, size).into_drawing_area();
        paint(&root).map_err(|e| draw_err(&e))?;
        root.present().map_err(|e| draw_err(&e))?;
    }
    Ok(svg)
}

fn draw_clip<DB: DrawingBackend>(
    root: &DrawingArea<DB, plotters::coord::Shift>,
    eps: f64,
    rows: &[(f64, f64)],
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    use super::l_clip;
    root.fill(&WHITE)?;
    let font = family();
    let shown = rows.iter().filter(|(_, a)| *a != 0.0).count();
    let mut chart = ChartBuilder::on(root)
        .caption(labels::clip_caption(eps, shown), (font, 18))
        .margin(15)
        .x_label_area_size(45)
        .y_label_area_size(55)
        .build_cartesian_2d(0.0..2.0, -2.0..2.0)?;
    chart.draw_series(std::iter::once(Rectangle::new(
        [(1.0 - eps, -2.0), (1.0 + eps, 2.0)],
        RGBColor(255, 236, 204).filled(),
    )))?;
    chart
        .configure_mesh()
        .x_desc(labels::ratio_axis())
        .y_desc(labels::clip_axis())
        .label_style((font, 14))
        .axis_desc_style((font, 15))
        .draw()?;
    let green = RGBColor(43, 138, 62);
    let red = RGBColor(201, 42, 42);
    for (a, colour, label) in [(1.0, green, "A > 0"), (-1.0, red, "A < 0")] {
        let curve = (0..=80).map(move |i| {
            let r = f64::from(i) / 40.0;
            (r, l_clip(r, a, eps))
        });
        chart
            .draw_series(LineSeries::new(curve, colour.stroke_width(2)))?
            .label(label)
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], colour));
    }
    chart.draw_series(rows.iter().filter(|(_, a)| *a != 0.0).map(|&(r, a)| {
        let r = r.clamp(0.0, 2.0);
        let colour = if a > 0.0 { green } else { red };
        Circle::new((r, l_clip(r, a.signum(), eps)), 3, colour.mix(0.6).filled())
    }))?;
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperLeft)
        .label_font((font, 14))
        .background_style(WHITE.mix(0.8))
        .border_style(BLACK)
        .draw()?;
    Ok(())
}

fn draw<DB: DrawingBackend>(
    root: &DrawingArea<DB, plotters::coord::Shift>,
    title: &str,
    figure: Figure<'_>,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    root.fill(&WHITE)?;
    let font = family();
    let (len, values): (usize, Vec<f64>) = match figure {
        Figure::Curve {
            returns, smoothed, ..
        } => (
            returns.len(),
            returns.iter().chain(smoothed).copied().collect(),
        ),
        Figure::Band { band, .. } => (
            band.mean.len(),
            band.high.iter().chain(&band.low).copied().collect(),
        ),
        Figure::Arms { arms, .. } => (
            arms.iter().map(|(_, b)| b.mean.len()).max().unwrap_or(0),
            arms.iter()
                .flat_map(|(_, b)| b.high.iter().chain(&b.low).copied())
                .collect(),
        ),
    };
    let finite = || values.iter().copied().filter(|v| v.is_finite());
    let highest = finite().fold(1.0, f64::max);
    // Returns below 0 (Pendulum's) extend the axis down; CartPole's start at 0.
    let lowest = finite().fold(0.0, f64::min);
    let steps = match figure {
        Figure::Curve {
            x: XAxis::Steps(steps),
            ..
        } => Some(steps),
        _ => None,
    };
    let x_max = match steps {
        Some(steps) => steps.last().copied().unwrap_or(0).max(1) as f64,
        None => len.saturating_sub(1).max(1) as f64,
    };
    let y_max = highest * 1.05;
    let y_min = lowest * 1.05;
    let mut chart = ChartBuilder::on(root)
        .caption(title, (font, 28))
        .margin(20)
        .x_label_area_size(50)
        .y_label_area_size(70)
        .build_cartesian_2d(0.0..x_max, y_min..y_max)?;
    chart
        .configure_mesh()
        .x_desc(if steps.is_some() {
            labels::env_steps()
        } else {
            labels::episodes()
        })
        .x_label_formatter(&|x| format!("{x:.0}"))
        .y_label_formatter(&|y| format!("{y:.0}"))
        .y_desc(labels::returns_axis())
        .label_style((font, 16))
        .axis_desc_style((font, 20))
        .draw()?;
    let blue = RGBColor(31, 119, 180); // matplotlib's first colour
    let orange = RGBColor(255, 127, 14);
    let points = |ys: &[f64]| {
        ys.iter()
            .enumerate()
            .map(|(i, &y)| {
                let x = steps.map_or(i as f64, |s| s.get(i).map_or(f64::NAN, |&s| s as f64));
                (x, y)
            })
            .collect::<Vec<_>>()
    };
    match figure {
        Figure::Curve {
            returns,
            smoothed,
            window,
            ..
        } => {
            // The average is the curve to read: three times the raw returns' width, over
            // them, which are lighter.
            let raw = blue.mix(0.6);
            chart
                .draw_series(LineSeries::new(points(returns), raw.stroke_width(1)))?
                .label(labels::returns())
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], raw));
            chart
                .draw_series(LineSeries::new(points(smoothed), orange.stroke_width(3)))?
                .label(labels::moving_average(window))
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], orange.stroke_width(3))
                });
        }
        Figure::Band { band, seeds } => {
            // The band as one polygon: along the highest curve, back along the lowest.
            let mut outline = points(&band.high);
            outline.extend(points(&band.low).into_iter().rev());
            chart
                .draw_series(std::iter::once(Polygon::new(
                    outline,
                    blue.mix(0.2).filled(),
                )))?
                .label(labels::band(seeds))
                .legend(move |(x, y)| {
                    Rectangle::new([(x, y - 5), (x + 20, y + 5)], blue.mix(0.2).filled())
                });
            chart
                .draw_series(LineSeries::new(points(&band.mean), blue.stroke_width(2)))?
                .label(labels::mean_over_seeds())
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], blue));
        }
        Figure::Arms { arms, seeds } => {
            // matplotlib's first four colours: blue is the base arm.
            let colours = [blue, orange, RGBColor(44, 160, 44), RGBColor(214, 39, 40)];
            for (k, (label, band)) in arms.iter().enumerate() {
                let colour = colours[k % colours.len()];
                let mut outline = points(&band.high);
                outline.extend(points(&band.low).into_iter().rev());
                chart.draw_series(std::iter::once(Polygon::new(
                    outline,
                    colour.mix(0.15).filled(),
                )))?;
                chart
                    .draw_series(LineSeries::new(points(&band.mean), colour.stroke_width(2)))?
                    .label(labels::arm(label, seeds))
                    .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], colour));
            }
        }
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::LowerRight)
        .label_font((font, 16))
        .background_style(WHITE.mix(0.8))
        .border_style(BLACK)
        .draw()?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn writes_png_and_svg_and_rejects_others() -> Result<(), Box<dyn std::error::Error>> {
        let dir = tempfile::tempdir()?;
        let returns: Vec<f64> = (0..50).map(|i| f64::from(i * 10)).collect();
        for name in ["curve.png", "curve.svg"] {
            let path = dir.path().join(name);
            save_return_plot(&path, "PPO on CartPole-v1", &returns, (&returns, 9))?;
            assert!(
                std::fs::metadata(&path)?.len() > 1000,
                "{name} is too small"
            );
        }
        let svg = std::fs::read_to_string(dir.path().join("curve.svg"))?;
        assert!(
            svg.contains("Episodes")
                && svg.contains("Returns")
                && svg.contains("PPO on CartPole-v1")
        );
        let err = save_return_plot(&dir.path().join("curve.jpg"), "t", &returns, (&returns, 9));
        assert!(matches!(err, Err(PlotError::UnknownFormat { .. })));
        Ok(())
    }

    /// A long run's figure: the legend says the window the rule gives, the average is drawn
    /// three times as wide as the returns, and a figure that cannot be written leaves no
    /// temporary file.
    #[test]
    fn the_legend_says_the_window_and_the_average_is_thicker()
    -> Result<(), Box<dyn std::error::Error>> {
        let _en = Lang::En.scoped();
        let dir = tempfile::tempdir()?;
        let returns: Vec<f64> = (0..2000).map(|i| -f64::from(i % 97) * 10.0).collect();
        let (window, smoothed) = super::super::window::smoothed(&returns);
        let path = dir.path().join("long.svg");
        save_return_plot(&path, "PPO on Pendulum-v1", &returns, (&smoothed, window))?;
        let svg = std::fs::read_to_string(&path)?;
        assert!(svg.contains("moving average (39 episodes)"), "the legend");
        let width_of = |colour: &str| {
            svg.lines()
                .find(|l| l.contains("<polyline") && l.contains(colour))
                .and_then(|l| l.split("stroke-width=\"").nth(1))
                .and_then(|w| w.split('"').next())
                .and_then(|w| w.parse::<u32>().ok())
        };
        // matplotlib's orange (the average) and blue (the returns).
        assert_eq!(
            (width_of("#FF7F0E"), width_of("#1F77B4")),
            (Some(3), Some(1))
        );
        let folder = dir.path().join("a-folder.svg");
        std::fs::create_dir(&folder)?;
        assert!(save_return_plot(&folder, "t", &returns, (&smoothed, window)).is_err());
        let names: Vec<_> = std::fs::read_dir(dir.path())?.collect::<Result<_, _>>()?;
        assert_eq!(names.len(), 2, "{names:?}");
        Ok(())
    }

    #[test]
    fn a_band_figure_names_its_seeds() -> Result<(), Box<dyn std::error::Error>> {
        let dir = tempfile::tempdir()?;
        let band = Band::of(&[vec![10.0, 50.0, 90.0], vec![30.0, 70.0, 200.0]]);
        let path = dir.path().join("band.svg");
        save_band_plot(&path, "PPO on CartPole-v1, seeds 0-1", &band, 2)?;
        let svg = std::fs::read_to_string(&path)?;
        assert!(svg.contains("lowest to highest of 2 seeds") && svg.contains("mean over seeds"));
        assert!(svg.contains("<polygon"), "the band is drawn");
        let err = save_band_plot(&dir.path().join("band.txt"), "t", &band, 2);
        assert!(matches!(err, Err(PlotError::UnknownFormat { .. })));
        Ok(())
    }
}
