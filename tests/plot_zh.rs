//! Plots in Chinese: every label a figure shows has a glyph in the bundled font
//! (`assets/fonts/PpoTutorSansSC-Regular.otf`), a Chinese `--plot` PNG draws its labels,
//! English figures keep their words and font, and the character plots stay aligned with
//! CJK characters two columns wide.

use std::path::Path;

use ab_glyph::{Font, FontRef};
use ppo_tutor::i18n::Lang;
use ppo_tutor::plot::file::FONT_ZH;
use ppo_tutor::plot::{
    ascii_band_plot, ascii_return_plot, ascii_versus_plot, display_width, labels, return_plot_svg,
    save_band_plot, save_lab_plot, save_return_plot,
};
use ppo_tutor::ppo::PpoConfig;
use ppo_tutor::ppo::lab::Experiment;
use ppo_tutor::ppo::seeds::Band;
use ratatui::text::Line;

type TestResult = Result<(), Box<dyn std::error::Error>>;

fn is_cjk(c: char) -> bool {
    matches!(u32::from(c), 0x3000..=0x303f | 0x4e00..=0x9fff | 0xff00..=0xffef)
}

/// The arms of every lab experiment, labelled in `lang`: a figure's legend shows them.
fn arm_labels(lang: Lang) -> Vec<String> {
    let _lang = lang.scoped();
    Experiment::ALL
        .iter()
        .flat_map(|e| e.arms(&PpoConfig::default()))
        .map(|a| a.label)
        .collect()
}

/// The characters of `text` the font has no glyph for.
fn missing(font: &FontRef<'_>, text: &str) -> Vec<char> {
    text.chars().filter(|&c| font.glyph_id(c).0 == 0).collect()
}

#[test]
fn every_chinese_label_has_a_glyph_in_the_bundled_font() -> TestResult {
    let font = FontRef::try_from_slice(FONT_ZH)?;
    let mut shown = labels::all(Lang::Zh);
    shown.extend(arm_labels(Lang::Zh));
    for label in &shown {
        let lacking = missing(&font, label);
        assert!(
            lacking.is_empty(),
            "{label:?}: no glyph for {lacking:?} in assets/fonts/PpoTutorSansSC-Regular.otf; \
             add them (assets/fonts/README.md says how)"
        );
    }
    // The check can fail: the font is a subset, without most of Chinese.
    assert_eq!(missing(&font, "回合龘"), vec!['龘']);
    Ok(())
}

#[test]
fn the_labels_are_translated_and_the_font_stays_small() {
    let (en, zh) = (labels::all(Lang::En), labels::all(Lang::Zh));
    assert_eq!(en.len(), zh.len());
    for (e, z) in en.iter().zip(&zh) {
        // Formulas and numbers are the same in both languages; words are not.
        let names = [
            "CLIP",
            "surr",
            "min",
            "old",
            "PPO",
            "CartPole",
            "Pendulum",
            "target",
            "kl",
            "REINFORCE",
        ];
        let has_words = e
            .split(|c: char| !c.is_ascii_alphabetic())
            .any(|w| w.len() >= 2 && !names.contains(&w));
        if has_words {
            assert!(z.chars().any(is_cjk), "untranslated: {e:?} -> {z:?}");
            assert_ne!(e, z);
        } else {
            assert_eq!(e, z, "a formula changed between languages");
        }
    }
    // The moving average's window, the titles of every algorithm.
    for label in [
        "移动平均（41 回合）",
        "* 为 9 回合移动平均",
        "CartPole-v1 上的 REINFORCE",
        "CartPole-v1 上的 PPO-惩罚",
        "CartPole-v1 上的 KL 线搜索",
        "CartPole-v1 上的 不截断的 PPO",
    ] {
        assert!(zh.iter().any(|l| l.contains(label)), "{label}: {zh:#?}");
    }
    for label in [
        "moving average (41 episodes)",
        "REINFORCE on CartPole-v1",
        "PPO-Penalty on CartPole-v1",
    ] {
        assert!(en.iter().any(|l| l.contains(label)), "{label}: {en:#?}");
    }
    // A subset of some 300 characters, not the 16 MB collection it comes from.
    assert!(
        (20_000..100_000).contains(&FONT_ZH.len()),
        "{} bytes",
        FONT_ZH.len()
    );
    for file in ["OFL.txt", "README.md", "make_subset.py", "extra-chars.txt"] {
        let path = Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("assets/fonts")
            .join(file);
        assert!(path.is_file(), "{} is missing", path.display());
    }
}

/// A PNG's pixels as grey levels, row after row.
struct Grey {
    width: usize,
    pixels: Vec<u8>,
}

impl Grey {
    fn read(path: &Path) -> Result<Self, Box<dyn std::error::Error>> {
        let mut decoder = png::Decoder::new(std::fs::File::open(path)?);
        decoder.set_transformations(png::Transformations::EXPAND | png::Transformations::STRIP_16);
        let mut reader = decoder.read_info()?;
        let mut buf = vec![0; reader.output_buffer_size()];
        let info = reader.next_frame(&mut buf)?;
        let channels = info.color_type.samples();
        let pixels = buf[..info.buffer_size()]
            .chunks(channels)
            .map(|p| {
                let rgb = &p[..channels.min(3)];
                (rgb.iter().map(|&v| u32::from(v)).sum::<u32>() / rgb.len() as u32) as u8
            })
            .collect();
        Ok(Self {
            width: info.width as usize,
            pixels,
        })
    }

    /// Dark pixels (text, lines) in the rectangle `[x0, x1) × [y0, y1)`.
    fn ink(&self, (x0, y0): (usize, usize), (x1, y1): (usize, usize)) -> usize {
        (y0..y1)
            .flat_map(|y| (x0..x1).map(move |x| (x, y)))
            .filter(|&(x, y)| self.pixels[y * self.width + x] < 128)
            .count()
    }

    /// Pixels that differ from `other`'s in the rectangle.
    fn differ(&self, other: &Self, (x0, y0): (usize, usize), (x1, y1): (usize, usize)) -> usize {
        (y0..y1)
            .flat_map(|y| (x0..x1).map(move |x| y * self.width + x))
            .filter(|&i| self.pixels[i].abs_diff(other.pixels[i]) > 64)
            .count()
    }
}

#[test]
fn a_chinese_png_draws_its_labels() -> TestResult {
    let dir = tempfile::tempdir()?;
    let returns: Vec<f64> = (0..60).map(|i| f64::from(i * 8)).collect();
    let smoothed = ppo_tutor::plot::smoothed_returns(&returns);
    let draw = |lang: Lang, name: &str, title: &str| -> Result<Grey, Box<dyn std::error::Error>> {
        let _lang = lang.scoped();
        let path = dir.path().join(name);
        save_return_plot(&path, title, &returns, (&smoothed, 9))?;
        Grey::read(&path)
    };
    let title = {
        let _zh = Lang::Zh.scoped();
        labels::return_title("PPO", "CartPole-v1")
    };
    let zh = draw(Lang::Zh, "zh.png", &title)?;
    let untitled = draw(Lang::Zh, "untitled.png", "")?;
    // The same number of characters, none of which the font has: boxes (.notdef).
    let boxes: String = title
        .chars()
        .map(|c| if is_cjk(c) { '龘' } else { c })
        .collect();
    let tofu = draw(Lang::Zh, "tofu.png", &boxes)?;
    let en = draw(Lang::En, "en.png", &title)?;

    // 1000x600, margin 20, caption 28 px on top; the x axis's title in the bottom 50 px
    // below the tick labels, the y axis's title in the left 70 px.
    let title_strip = ((200, 0), (800, 70));
    assert_eq!(untitled.ink(title_strip.0, title_strip.1), 0);
    assert!(
        zh.ink(title_strip.0, title_strip.1) > 150,
        "the title is drawn"
    );
    assert!(
        zh.differ(&tofu, title_strip.0, title_strip.1) > 100,
        "上的 are drawn as glyphs, not as the boxes of missing ones"
    );
    // The axes' titles: 回合 under the axis, 回报 left of it, where English has its words.
    let x_title = ((400, 560), (600, 600));
    let y_title = ((0, 150), (45, 450));
    for (what, (from, to)) in [("回合", x_title), ("回报", y_title)] {
        assert!(zh.ink(from, to) > 40, "{what} is drawn");
        assert!(
            en.ink(from, to) > 40,
            "the English title of {what}'s axis is drawn"
        );
        assert!(
            zh.differ(&en, from, to) > 40,
            "{what} is not the English word"
        );
    }
    // The legend, lower right: 回报 and 移动平均（9 回合） against returns, moving average (9).
    let legend = ((650, 380), (1000, 560));
    assert!(zh.ink(legend.0, legend.1) > 200);
    assert!(zh.differ(&en, legend.0, legend.1) > 100);
    Ok(())
}

#[test]
fn band_and_lab_figures_write_in_both_languages() -> TestResult {
    let dir = tempfile::tempdir()?;
    let band = Band::of(&[vec![10.0, 50.0, 90.0], vec![30.0, 70.0, 200.0]]);
    for lang in Lang::ALL {
        let _lang = lang.scoped();
        let arms = arm_labels(lang);
        let arm_refs = [(arms[0].as_str(), &band), (arms[2].as_str(), &band)];
        for ext in ["png", "svg"] {
            let band_path = dir.path().join(format!("band-{lang}.{ext}"));
            let title = labels::band_title("PPO", "CartPole-v1", 2);
            save_band_plot(&band_path, &title, &band, 2)?;
            let lab_path = dir.path().join(format!("lab-{lang}.{ext}"));
            save_lab_plot(&lab_path, &labels::lab_title("eps", 2), &arm_refs, 2)?;
            assert!(std::fs::metadata(&band_path)?.len() > 1000);
            assert!(std::fs::metadata(&lab_path)?.len() > 1000);
        }
        let svg = std::fs::read_to_string(dir.path().join(format!("band-{lang}.svg")))?;
        assert!(svg.contains(&labels::band(2)) && svg.contains(labels::mean_over_seeds()));
    }
    let zh = std::fs::read_to_string(dir.path().join("band-zh.svg"))?;
    assert!(zh.contains("2 个随机种子的最低到最高"), "{zh}");
    Ok(())
}

#[test]
fn english_figures_keep_their_words_and_font() -> TestResult {
    let returns: Vec<f64> = (0..30).map(f64::from).collect();
    let en = {
        let _en = Lang::En.scoped();
        return_plot_svg("PPO on CartPole-v1", &returns, &returns)?
    };
    for word in [
        "Episodes",
        "Returns",
        "moving average (9 episodes)",
        "returns",
    ] {
        assert!(en.contains(word), "{word} is missing");
    }
    assert!(en.contains("font-family=\"sans-serif\"") && !en.contains("Noto"));
    let zh = {
        let _zh = Lang::Zh.scoped();
        return_plot_svg(
            &labels::return_title("PPO", "CartPole-v1"),
            &returns,
            &returns,
        )?
    };
    for word in ["回合", "回报", "移动平均（9 回合）", "CartPole-v1 上的 PPO"] {
        assert!(zh.contains(word), "{word} is missing");
    }
    assert!(!zh.contains("Episodes") && !zh.contains("moving average"));
    // A browser picks a Chinese font the reader has for the SVG.
    assert!(zh.contains("Noto Sans CJK SC") && zh.contains("sans-serif"));
    Ok(())
}

fn width(line: &str) -> usize {
    Line::raw(line).width()
}

/// The character plot's rows line up: the axis, the x labels (0, 回合 in the middle, the
/// last episode at the axis's end) and the legend, measured in columns, not bytes.
fn assert_aligned(lines: &[String], plot_width: usize, terminal: usize) {
    let n = lines.len();
    let (axis, ticks) = (&lines[n - 2], &lines[n - 1]);
    assert_eq!(width(axis), width(ticks), "{lines:#?}");
    let gutter = width(axis) - plot_width;
    let middle = ticks.find("回合").unwrap_or(0);
    assert!(middle > 0, "{lines:#?}");
    let centre = width(&ticks[..middle]) + 2;
    let axis_centre = gutter + plot_width / 2;
    assert!(
        centre.abs_diff(axis_centre) <= 2,
        "{ticks:?} at {centre}, axis centre {axis_centre}"
    );
    for line in lines {
        assert_eq!(display_width(line), width(line), "{line:?}");
        assert!(
            width(line) <= terminal,
            "{line:?} overflows {terminal} columns"
        );
    }
    assert!(lines[0].chars().any(is_cjk), "{}", lines[0]);
}

#[test]
fn chinese_character_plots_stay_aligned_at_80_and_160_columns() {
    let _zh = Lang::Zh.scoped();
    let returns: Vec<f64> = (0..500).map(|i| f64::from(i % 200)).collect();
    let smoothed = ppo_tutor::plot::smoothed_returns(&returns);
    let band = Band::of(&[returns.clone(), smoothed.clone()]);
    // `ppo-tutor train` draws `width.clamp(30, 120) - 8` columns wide.
    for terminal in [80, 160] {
        let plot_width = terminal.min(120) - 8;
        assert_aligned(
            &ascii_return_plot(&returns, (&smoothed, 9), plot_width, 14),
            plot_width,
            terminal,
        );
        assert_aligned(
            &ascii_band_plot((&band, 9), 5, plot_width, 14),
            plot_width,
            terminal,
        );
        let arms = arm_labels(Lang::Zh);
        assert_aligned(
            &ascii_versus_plot((&arms[1], &band), (&arms[0], &band), 5, plot_width, 14),
            plot_width,
            terminal,
        );
    }
    let lines = ascii_return_plot(&returns, (&smoothed, 9), 72, 14);
    assert_eq!(
        lines[0].trim_start(),
        "回报（. 为每回合的值，* 为 9 回合移动平均）"
    );
    assert!(
        lines.last().is_some_and(|l| l.ends_with("499")),
        "{lines:#?}"
    );
}

#[test]
fn english_character_plots_are_unchanged() {
    let _en = Lang::En.scoped();
    let returns: Vec<f64> = (0..500).map(f64::from).collect();
    let lines = ascii_return_plot(&returns, (&returns, 9), 60, 12);
    assert_eq!(
        lines[0],
        "     Returns  (. per episode, * moving average of 9)"
    );
    let ticks = lines.last().map_or("", String::as_str);
    assert_eq!(
        ticks,
        format!("     0{}Episodes{}499", " ".repeat(24), " ".repeat(24))
    );
    let band = Band::of(&[vec![0.0, 100.0], vec![100.0, 300.0]]);
    assert!(ascii_band_plot((&band, 9), 2, 21, 11)[0].ends_with(
        "Moving average (9 episodes) of the returns over 2 seeds  (* mean, : lowest to highest seed)"
    ));
}
