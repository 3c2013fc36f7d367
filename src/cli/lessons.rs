//! `ppo-tutor lessons` and `ppo-tutor show`: the course as plain text, for scripts,
//! screen readers and logs.

use std::fmt::Write as _;
use std::io::Write;
use std::process::ExitCode;

use anyhow::Context;
use clap::Args;

use crate::i18n::t;
use crate::lesson::{Course, Progress, RunConfig, Session, Snapshot, reveal};
use crate::tr;

/// Arguments of `ppo-tutor show`.
#[derive(Debug, Args)]
pub struct ShowArgs {
    /// The lesson id, as `ppo-tutor lessons` lists it (e.g. td-target).
    pub id: String,
    /// The step to show, from 1; all steps when omitted.
    #[arg(long, value_parser = super::args::parse_count, allow_hyphen_values = true)]
    pub step: Option<usize>,
    /// Episodes to train before showing live values (the latest episode's update is shown).
    #[arg(long, value_parser = super::args::parse_count, allow_hyphen_values = true, default_value_t = 1)]
    pub episodes: usize,
    /// Seed of the agent and the environment.
    #[arg(long, default_value = "0", value_parser = super::args::parse_seed)]
    pub seed: u64,
}

/// Prints `id<TAB>title`, one lesson per line, in order.
///
/// # Errors
/// The embedded lessons are invalid (a build that passed its tests never is).
pub fn list() -> anyhow::Result<ExitCode> {
    let course = Course::embedded().context(t("loading the embedded lessons", "加载内置课程"))?;
    for l in &course.lessons {
        writeln!(std::io::stdout(), "{}\t{}", l.id, l.title)?;
    }
    Ok(ExitCode::SUCCESS)
}

/// The columns `show` wraps a step's text to (as the lessons' sources are wrapped).
const PLAIN_WIDTH: u16 = 100;

/// Renders one step as plain text with its live values; the code an exercise asks for is a
/// note until `passed` holds for it ([`crate::lesson::reveal`]).
#[must_use]
pub fn render_step(
    course: &Course,
    lesson: usize,
    step: usize,
    snapshot: &Snapshot,
    passed: &dyn Fn(&str) -> bool,
) -> String {
    let mut out = String::new();
    let Some(l) = course.lessons.get(lesson) else {
        return out;
    };
    let Some(s) = l.steps.get(step) else {
        return out;
    };
    let (title, n, of, step_title) = (&l.title, step + 1, l.steps.len(), &s.title);
    let _ = writeln!(
        out,
        "{}\n",
        tr!(
            "# {title} — step {n}/{of}: {step_title}",
            "# {title} — 第 {n}/{of} 节：{step_title}"
        )
    );
    // The terminal app's renderer, without styles: no emphasis markers, tables as columns.
    let body = crate::lesson::details::fold(&s.text(crate::lesson::face::Face::Terminal), true);
    let _ = writeln!(
        out,
        "{}\n",
        crate::tui::widgets::text::plain(&body, PLAIN_WIDTH)
    );
    if !s.python.is_empty() {
        let source = capitalised(l.env.source_name());
        let _ = writeln!(
            out,
            "## {source}{}\n{}\n",
            t(" (PyTorch)", "（PyTorch）"),
            s.python
        );
    }
    if let Some(listing) = (!s.code.is_empty())
        .then(|| reveal::listing(&s.code, passed))
        .flatten()
    {
        let (krate, path, code) = (listing.krate, &listing.path, listing.text());
        let _ = writeln!(out, "## {krate} (crates/{krate}/src/{path})");
        for gate in listing.shown.iter().filter(|g| g.lesson == l.order) {
            if let Ok(ex) = crate::grade::find(&gate.exercise) {
                let (name, folder, file) = (&gate.exercise, &gate.folder, ex.meta().starter);
                let _ = writeln!(
                    out,
                    "{}",
                    tr!(
                        "// your {name}: lessons/{folder}/{file}",
                        "// 你写的 {name}：lessons/{folder}/{file}"
                    )
                );
            }
        }
        let _ = writeln!(out, "{code}\n");
    }
    for name in &s.show {
        match snapshot.tensor(name) {
            Some(t) if !t.labels.is_empty() => {
                let _ = writeln!(out, "## {name}");
                for label in &t.labels {
                    let _ = writeln!(out, "  {label}");
                }
            }
            Some(t) => {
                let stats = t.stats().map_or(String::new(), |(lo, hi, mean)| {
                    tr!(
                        " min {lo:.6} max {hi:.6} mean {mean:.6}",
                        " 最小 {lo:.6} 最大 {hi:.6} 均值 {mean:.6}"
                    )
                });
                let _ = writeln!(out, "## {name} {}{stats}", t.shape_text());
                let cols = t.cols();
                for (row, chunk) in t.values.chunks(cols).enumerate().take(20) {
                    let vals: Vec<String> = chunk.iter().map(|v| format!("{v:.6}")).collect();
                    let _ = writeln!(out, "  [{row}] {}", vals.join(" "));
                }
                if t.values.len() / cols > 20 {
                    let rows = t.values.len() / cols;
                    let _ = writeln!(out, "  ... {}", tr!("({rows} rows)", "（共 {rows} 行）"));
                }
            }
            None if crate::lesson::VIEWS.contains(&name.as_str()) => {
                let _ = writeln!(
                    out,
                    "## {name}{}",
                    t(
                        ": a picture in the terminal app (ppo-tutor)",
                        "：终端应用（ppo-tutor）里的图"
                    )
                );
            }
            None => {
                let _ = writeln!(out, "## {name}{}", t(": not available yet", "：暂无数据"));
            }
        }
    }
    out
}

/// Runs `ppo-tutor show`.
///
/// # Errors
/// Training failed; unknown ids and steps are reported with exit code 2.
pub fn show(args: &ShowArgs) -> anyhow::Result<ExitCode> {
    let course = Course::embedded().context(t("loading the embedded lessons", "加载内置课程"))?;
    let Some(index) = course.index_of(&args.id) else {
        let ids: Vec<&str> = course.lessons.iter().map(|l| l.id.as_str()).collect();
        let (id, ids) = (&args.id, ids.join(", "));
        eprintln!(
            "{}{}",
            super::error_prefix(),
            tr!(
                "unknown lesson '{id}' for <ID>: expected one of {ids}",
                "<ID> 没有名为 '{id}' 的课；可选：{ids}"
            )
        );
        return Ok(ExitCode::from(super::EXIT_USAGE));
    };
    let steps = course.lessons[index].steps.len();
    let range = match args.step {
        Some(n) if n == 0 || n > steps => {
            let id = &args.id;
            eprintln!(
                "{}{}",
                super::error_prefix(),
                tr!(
                    "--step {n} is out of range: lesson '{id}' has steps 1 to {steps}",
                    "--step {n} 超出范围：课 '{id}' 只有第 1 到 {steps} 节"
                )
            );
            return Ok(ExitCode::from(super::EXIT_USAGE));
        }
        Some(n) => n - 1..n,
        None => 0..steps,
    };
    // The lesson's environment: CartPole with the seed's PPO, or Pendulum with the book's
    // PPOContinuous.
    let run = RunConfig::default_for(course.lessons[index].env);
    let snapshot = Session::run(run, args.seed, args.episodes.max(1))?;
    // The app's progress file says which exercises are passed (only read: a missing or
    // corrupt file counts as none passed).
    let progress: Progress = std::fs::read_to_string(Progress::default_path())
        .ok()
        .and_then(|text| serde_json::from_str(&text).ok())
        .unwrap_or_default();
    let passed = |e: &str| progress.exercises_done.contains(e);
    let mut out = std::io::stdout();
    for step in range {
        write!(
            out,
            "{}",
            render_step(&course, index, step, &snapshot, &passed)
        )?;
    }
    Ok(ExitCode::SUCCESS)
}

/// `text` with its first letter upper-case ("The seed"; Chinese is unchanged).
fn capitalised(text: &str) -> String {
    let mut chars = text.chars();
    chars.next().map_or_else(String::new, |first| {
        first.to_uppercase().chain(chars).collect()
    })
}

#[cfg(test)]
mod tests {
    use super::render_step;
    use crate::lesson::{Course, Snapshot};

    /// `show` prints a step as the app shows it, without markdown's
    /// stars and pipes.
    #[test]
    fn a_step_prints_without_markdown_markers() -> Result<(), Box<dyn std::error::Error>> {
        let course = Course::embedded()?;
        let lesson = course.index_of("cartpole").ok_or("no cartpole lesson")?;
        let steps = course.lessons[lesson].steps.len();
        let text: String = (0..steps)
            .map(|k| render_step(&course, lesson, k, &Snapshot::default(), &|_| false))
            .collect();
        assert!(!text.contains("**") && !text.contains("|---"), "{text}");
        assert!(text.contains("\nCartPole-v1  500 steps   475\n"), "{text}");
        assert!(text.contains("Termination (terminated = True)"), "{text}");
        Ok(())
    }
}
