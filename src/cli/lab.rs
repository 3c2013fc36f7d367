//! `ppo-tutor lab [EXPERIMENT]`: the clip lab from the command line. Each experiment changes
//! one of PPO's knobs, trains every setting over the same seeds on every core, and prints
//! each setting's final score over the seeds, what its updates did, and its curve against
//! the seed's settings.

use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

use anyhow::Context;
use clap::Args;

use super::args::{SeedList, parse_seeds};
use crate::i18n::t;
use crate::plot::{ascii_versus_plot, labels, save_lab_plot};
use crate::ppo::PpoConfig;
use crate::ppo::lab::{self, Experiment};
use crate::tr;

/// Arguments of `ppo-tutor lab`.
#[derive(Debug, Args)]
pub struct LabArgs {
    /// The experiment: eps, epochs, actor-lr, target-kl, reinforce, critic-lr, hidden-dim,
    /// gamma, lmbda or proximal (omit to list them).
    #[arg(value_parser = parse_experiment)]
    pub experiment: Option<Experiment>,
    /// The seeds every setting runs: numbers and ranges, e.g. 0-4 or 0,3,7.
    #[arg(long, default_value = "0-4", value_parser = parse_seeds, value_name = "LIST")]
    pub seeds: SeedList,
    /// Episodes per run.
    #[arg(long, value_parser = super::args::parse_count, allow_hyphen_values = true, default_value_t = 500)]
    pub episodes: usize,
    /// Write every run's returns, the bands and the statistics as JSON.
    #[arg(long, value_name = "FILE")]
    pub json: Option<PathBuf>,
    /// Draw the settings' bands to FILE.png or FILE.svg.
    #[arg(long, value_name = "FILE")]
    pub plot: Option<PathBuf>,
    /// Print only the table (no progress bar, no plot).
    #[arg(long, short)]
    pub quiet: bool,
}

fn parse_experiment(s: &str) -> Result<Experiment, String> {
    Experiment::from_name(s).ok_or_else(|| {
        let names: Vec<&str> = Experiment::ALL.iter().map(|e| e.name()).collect();
        let names = names.join(", ");
        tr!(
            "unknown experiment '{s}': choose one of {names}",
            "未知的实验 '{s}'：请从 {names} 中选一个"
        )
    })
}

/// Runs `ppo-tutor lab`.
///
/// # Errors
/// A run that diverged, or an output file that could not be written.
pub fn run(args: &LabArgs) -> anyhow::Result<ExitCode> {
    let mut out = std::io::stdout().lock();
    let Some(experiment) = args.experiment else {
        writeln!(
            out,
            "{}",
            t(
                "The clip lab's experiments (run one with ppo-tutor lab NAME):",
                "截断实验室的实验（用 ppo-tutor lab <实验> 运行其中一个）："
            )
        )?;
        for e in Experiment::ALL {
            let arms: Vec<String> = e
                .arms(&PpoConfig::default())
                .into_iter()
                .map(|a| a.label)
                .collect();
            writeln!(
                out,
                "  {:<10} {}  [{}]",
                e.name(),
                e.question(),
                arms.join(" | ")
            )?;
        }
        return Ok(ExitCode::SUCCESS);
    };
    // Every output path is checked before the runs, not found bad after them.
    let outputs = [
        ("--json", args.json.as_deref(), None),
        ("--plot", args.plot.as_deref(), Some(&["png", "svg"][..])),
    ];
    for (flag, path, exts) in outputs {
        if let Some(path) = path
            && let Err(err) = super::args::check_output(flag, path, exts)
        {
            eprintln!("{}{err}", super::error_prefix());
            return Ok(ExitCode::from(super::EXIT_USAGE));
        }
    }
    let not_written: Vec<String> = outputs
        .iter()
        .filter_map(|(flag, path, _)| path.map(|p| format!("{flag} {}", p.display())))
        .collect();
    let interrupt = super::interrupt::Interrupt::install();
    let base = PpoConfig {
        num_episodes: args.episodes,
        ..PpoConfig::default()
    };
    let seeds = &args.seeds.0;
    let runs = experiment.arms(&base).len() * seeds.len();
    let threads = std::thread::available_parallelism()
        .map_or(1, usize::from)
        .min(runs);
    let bar = super::episodes_bar(args.quiet, runs * args.episodes, t("lab", "实验"));
    let started = Instant::now();
    let total = runs * args.episodes;
    let stopping = std::sync::atomic::AtomicBool::new(false);
    let result = lab::run(experiment, &base, seeds, threads, |done, _| {
        // The runs train on worker threads: at Ctrl-C, say how far they got and end the
        // process (nothing is written before the end).
        if interrupt.pressed() && !stopping.swap(true, std::sync::atomic::Ordering::Relaxed) {
            if let Some(bar) = &bar {
                bar.abandon();
            }
            let line = super::interrupt::stopped_line(done, total, &[], &not_written);
            eprintln!("{line}");
            std::process::exit(i32::from(super::interrupt::EXIT_INTERRUPTED));
        }
        if let Some(bar) = &bar {
            bar.set_position(done as u64);
        }
    })
    .context(t("the experiment stopped", "实验中止"))?;
    if let Some(bar) = &bar {
        bar.finish_and_clear();
    }
    let wall_s = started.elapsed().as_secs_f64();
    let (name, question) = (experiment.name(), experiment.question());
    let (arms, n_seeds, episodes) = (result.arms.len(), seeds.len(), args.episodes);
    writeln!(
        out,
        "{}\n",
        tr!(
            "lab {name}: {question}\n{arms} settings x {n_seeds} seeds, {episodes} episodes each, {threads} runs at a time, {wall_s:.1} s",
            "实验 {name}：{question}\n{arms} 种设置 × {n_seeds} 个随机种子，每次 {episodes} 个回合，同时跑 {threads} 次，用时 {wall_s:.1} 秒"
        )
    )?;
    for line in result.table() {
        writeln!(out, "{line}")?;
    }
    writeln!(out)?;
    for line in result.comparisons() {
        writeln!(out, "{line}")?;
    }
    if experiment == Experiment::Proximal {
        writeln!(out)?;
        for arm in &result.arms {
            writeln!(out, "{}", arm.kl_summary())?;
        }
    }
    if !args.quiet {
        let width = crossterm::terminal::size().map_or(80, |(w, _)| usize::from(w));
        if let Some((base_arm, others)) = result.arms.split_first() {
            for arm in others {
                writeln!(out)?;
                for line in ascii_versus_plot(
                    (&arm.label, &arm.band),
                    (&base_arm.label, &base_arm.band),
                    seeds.len(),
                    width.clamp(30, 120) - 8,
                    12,
                ) {
                    writeln!(out, "{line}")?;
                }
            }
        }
    }
    if let Some(path) = &args.json {
        // the result, and each arm after the first paired with it (null: fewer than 2 seeds)
        let mut value =
            serde_json::to_value(&result).context(t("encoding the results", "编码结果"))?;
        if let serde_json::Value::Object(map) = &mut value {
            let paired = serde_json::to_value(result.paired())
                .context(t("encoding the results", "编码结果"))?;
            map.insert("paired_with_first".into(), paired);
        }
        let text = value.to_string();
        super::train::write_output(path, format!("{text}\n").as_bytes())?;
    }
    if let Some(path) = &args.plot {
        let arms: Vec<(&str, &crate::ppo::seeds::Band)> = result
            .arms
            .iter()
            .map(|a| (a.label.as_str(), &a.band))
            .collect();
        let title = labels::lab_title(experiment.name(), seeds.len());
        save_lab_plot(path, &title, &arms, seeds.len())?;
        let shown = path.display();
        writeln!(
            out,
            "{}",
            tr!(
                "drew the settings' bands to {shown}",
                "已把各设置的曲线带画到 {shown}"
            )
        )?;
    }
    Ok(ExitCode::SUCCESS)
}
