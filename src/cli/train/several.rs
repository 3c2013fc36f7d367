//! `ppo-tutor train --seeds LIST`: one configuration over several seeds at once, on every
//! core, summarised as each seed's mean of the last 50 returns (100 on Pendulum-v1), their
//! mean ± std, and the mean curve over the band the seeds span.

use std::io::Write;
use std::process::ExitCode;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::time::Instant;

use anyhow::Context;
use serde_json::json;

use super::{TrainArgs, Written, peak_rss_mb, write_output};
use crate::cli::interrupt::Interrupt;
use crate::i18n::t;
use crate::lesson::RunConfig;
use crate::plot::{ascii_band_plot, labels, save_band_plot};
use crate::ppo::knobs::Tunable;
use crate::ppo::seeds::ReportOf;
use crate::ppo::seeds::{Band, SeedError, SeedRun, mean_std, train_seeds};
use crate::run::RunVisitor;
use crate::tr;

/// Trains `setup` once per seed and reports as the module says. Ctrl-C ends the process
/// at the end of the episode under way, saying how far the seeds got and that nothing was
/// written ([`Interrupt`]).
///
/// # Errors
/// A run that diverged, or an output file that could not be written.
pub(super) fn run(
    args: &TrainArgs,
    setup: &RunConfig,
    seeds: &[u64],
    interrupt: &Interrupt,
) -> anyhow::Result<ExitCode> {
    let threads = std::thread::available_parallelism()
        .map_or(1, usize::from)
        .min(seeds.len());
    let episodes = setup.num_episodes();
    let bar = super::super::episodes_bar(
        args.quiet,
        seeds.len() * episodes,
        t("all seeds", "所有随机种子"),
    );
    let started = Instant::now();
    let trained = AtomicUsize::new(0);
    let stopping = AtomicBool::new(false);
    let on_episode = |seed: u64, episode: usize| {
        let done = trained.fetch_add(1, Ordering::Relaxed) + 1;
        // The seeds train on worker threads that cannot be stopped from here: the first to
        // see Ctrl-C says so and ends the process (nothing is written before the end).
        if interrupt.pressed() && !stopping.swap(true, Ordering::Relaxed) {
            if let Some(bar) = &bar {
                bar.abandon();
            }
            Written::new(args, seeds.len() * episodes, interrupt).stopped(done);
            std::process::exit(i32::from(crate::cli::interrupt::EXIT_INTERRUPTED));
        }
        if let Some(bar) = &bar {
            bar.inc(1);
        } else if !args.quiet && episode + 1 == episodes {
            eprintln!(
                "{}",
                tr!(
                    "seed {seed}: {episodes} episodes trained",
                    "随机种子 {seed}：已训练 {episodes} 个回合"
                )
            );
        }
    };
    let runs = setup
        .visit(Seeds {
            seeds,
            threads,
            on_episode: &on_episode,
        })
        .context(t("training stopped", "训练中止"))?;
    if let Some(bar) = &bar {
        bar.finish_and_clear();
    }
    let wall_s = started.elapsed().as_secs_f64();
    let window = crate::plot::window::window(episodes);
    let smoothed: Vec<Vec<f64>> = runs
        .iter()
        .map(|r| crate::plot::window::smoothed(&r.summary.returns).1)
        .collect();
    let band = Band::of(&smoothed);
    let last = setup.agent().spec().summary_window;
    let finals: Vec<f64> = runs.iter().map(|r| r.summary.mean_last(last)).collect();

    let mut out = std::io::stdout().lock();
    let steps: u64 = runs.iter().map(|r| r.summary.env_steps).sum();
    let n_runs = runs.len();
    let title = labels::band_title(labels::algorithm(setup), setup.env_id(), n_runs);
    writeln!(
        out,
        "{}",
        tr!(
            "{title}, {episodes} episodes each, {threads} at a time: {steps} env steps in {wall_s:.2} s",
            "{title}，每个 {episodes} 个回合，同时跑 {threads} 个：环境共 {steps} 步，用时 {wall_s:.2} 秒"
        )
    )?;
    for run in &runs {
        let (seed, n, mean) = (
            run.seed,
            run.summary.returns.len().min(last),
            run.summary.mean_last(last),
        );
        writeln!(
            out,
            "{}",
            tr!(
                "seed {seed:>3}: mean return of the last {n} episodes {mean:6.1}",
                "随机种子 {seed:>3}：最后 {n} 个回合的平均回报 {mean:6.1}"
            )
        )?;
    }
    let (mean, std) = mean_std(&finals);
    writeln!(
        out,
        "{}",
        tr!(
            "over {n_runs} seeds: {mean:.1} ± {std:.1} (mean ± sample std of the seeds' means)",
            "{n_runs} 个随机种子：{mean:.1} ± {std:.1}（各随机种子均值的平均 ± 样本标准差）"
        )
    )?;
    let spread = Spread::of(&finals);
    if let Some(line) = spread.line() {
        writeln!(out, "{line}")?;
    }
    if !args.quiet {
        let width = crossterm::terminal::size().map_or(80, |(w, _)| usize::from(w));
        writeln!(out)?;
        for line in ascii_band_plot((&band, window), runs.len(), width.clamp(30, 120) - 8, 14) {
            writeln!(out, "{line}")?;
        }
    }
    let mut written = Written::new(args, seeds.len() * episodes, interrupt);
    if let Some(path) = &args.json {
        if let Some(code) = written.interrupted() {
            return Ok(code);
        }
        let value = seeds_json(
            setup,
            &runs,
            (&smoothed, window),
            &band,
            (mean, std, &spread),
            wall_s,
        );
        write_output(path, format!("{value}\n").as_bytes())?;
        written.done("--json", path);
    }
    if let Some(path) = &args.plot {
        if let Some(code) = written.interrupted() {
            return Ok(code);
        }
        save_band_plot(path, &title, &band, runs.len())?;
        let shown = path.display();
        writeln!(
            out,
            "{}",
            tr!(
                "drew the seeds' curves to {shown}",
                "已把各随机种子的曲线画到 {shown}"
            )
        )?;
    }
    Ok(ExitCode::SUCCESS)
}

/// The `--json` document of a several-seed run: every seed's returns and moving average,
/// the summary over seeds (`mean_last_50`; on Pendulum-v1 `mean_last_100` too, the one
/// `(mean, std)` gives) and the band.
fn seeds_json(
    setup: &RunConfig,
    runs: &[SeedRun],
    (smoothed, window): (&[Vec<f64>], usize),
    band: &Band,
    (mean, std, spread): (f64, f64, &Spread),
    wall_s: f64,
) -> serde_json::Value {
    let key = format!("mean_last_{}", setup.agent().spec().summary_window);
    let over_seeds = |k: usize| {
        if k == setup.agent().spec().summary_window {
            (mean, std)
        } else {
            let means: Vec<f64> = runs.iter().map(|r| r.summary.mean_last(k)).collect();
            mean_std(&means)
        }
    };
    let (mean_50, std_50) = over_seeds(50);
    let mut value = json!({
        "episodes": setup.num_episodes(),
        "seeds": runs.iter().map(|r| r.seed).collect::<Vec<_>>(),
        "env": setup.env_id(),
        "wall_s": wall_s,
        "peak_rss_mb": peak_rss_mb(),
        "mean_last_50": { "mean": mean_50, "std": std_50 },
        "runs": runs.iter().zip(smoothed).map(|(r, s)| {
            let mut run = json!({
                "seed": r.seed,
                "env_steps": r.summary.env_steps,
                "mean_last_50": r.summary.mean_last(50),
                "returns": r.summary.returns,
                "moving_average": s,
            });
            run[&key] = json!(r.summary.mean_last(setup.agent().spec().summary_window));
            run
        }).collect::<Vec<_>>(),
        "moving_average_window": window,
        "band": { "of": "moving_average", "mean": band.mean, "low": band.low, "high": band.high },
        "config": setup,
    });
    value[&key] = json!({
        "mean": mean,
        "std": std,
        "iqm": spread.iqm,
        "mean_ci95": spread.mean_ci.map(|ci| json!({ "low": ci.low, "high": ci.high })),
    });
    value
}

/// The robust summary of the seeds' scores beside mean ± std: the interquartile mean and
/// the 95% bootstrap interval of the mean ([`crate::stats`]); no interval from one seed.
struct Spread {
    iqm: Option<f64>,
    mean_ci: Option<crate::stats::Interval>,
}

impl Spread {
    fn of(finals: &[f64]) -> Self {
        Self {
            iqm: crate::stats::iqm(finals),
            mean_ci: crate::stats::Bootstrap::default()
                .mean(finals)
                .ok()
                .map(|e| e.ci),
        }
    }

    fn line(&self) -> Option<String> {
        let (iqm, ci) = (self.iqm?, self.mean_ci?);
        Some(tr!(
            "  interquartile mean {iqm:.1}; 95% bootstrap interval of the mean [{:.1}, {:.1}]",
            "  四分位均值 {iqm:.1}；均值的 95% 自助法置信区间 [{:.1}, {:.1}]",
            ci.low,
            ci.high
        ))
    }
}

/// Trains every seed of any agent, for [`RunConfig::visit`].
struct Seeds<'a> {
    seeds: &'a [u64],
    threads: usize,
    on_episode: &'a (dyn Fn(u64, usize) + Sync),
}

impl RunVisitor for Seeds<'_> {
    type Output = Result<Vec<SeedRun>, SeedError>;

    fn visit<C: Tunable>(self, config: &C) -> Self::Output {
        let on_episode = self.on_episode;
        train_seeds(
            config,
            self.seeds,
            self.threads,
            |seed, report: &ReportOf<C>| {
                on_episode(seed, report.episode);
            },
        )
    }
}
