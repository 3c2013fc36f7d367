//! `ppo-tutor train`: the seed's `train_on_policy_agent` with tqdm-like progress bars, a
//! summary, the return curve in the terminal, and optional JSON, checkpoint and figure.

use std::io::{IsTerminal, Write};
use std::ops::ControlFlow;
use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::Context;
use clap::Args;
use indicatif::{ProgressBar, ProgressStyle};
use serde_json::json;

use super::args::{SeedList, parse_env, parse_seed, parse_seeds};
use crate::env::EnvId;
use crate::plot::{ascii_return_plot, save_return_plot, smoothed_returns};
use crate::ppo::train::mean_last;
use crate::ppo::{Algorithm, EpisodeReport, PpoConfig, PpoError, TrainSummary, train};

/// Arguments of `ppo-tutor train`; defaults are the seed's.
#[derive(Debug, Args)]
#[command(
    after_help = "Examples:\n  ppo-tutor train\n  ppo-tutor train --seed 3 --json run.json --save agent.safetensors --plot returns.svg\n  ppo-tutor play --load agent.safetensors\n  ppo-tutor train --seeds 0-4 --plot seeds.svg --json seeds.json"
)]
pub struct TrainArgs {
    /// Episodes to train for (one update per episode).
    #[arg(long, default_value_t = 500)]
    pub episodes: usize,
    /// Seed of the network initialisation, the action sampling and the first env.reset.
    #[arg(long, default_value = "0", value_parser = parse_seed, allow_hyphen_values = true)]
    pub seed: u64,
    /// Train several seeds in parallel (a range or a list: 0-4, 1,3,8): prints each seed's
    /// mean of the last 50 returns and their mean ± std, and draws the mean curve over the
    /// band of the seeds.
    #[arg(long, value_name = "LIST", value_parser = parse_seeds, conflicts_with_all = ["seed", "save"])]
    pub seeds: Option<SeedList>,
    /// Gymnasium environment id.
    #[arg(long = "env", default_value = "CartPole-v1", value_parser = parse_env)]
    pub env_id: EnvId,
    /// Write returns, env steps and timing as JSON to FILE.
    #[arg(long, value_name = "FILE")]
    pub json: Option<PathBuf>,
    /// Save the trained agent to FILE.safetensors (watch it with `ppo-tutor play --load`).
    #[arg(long, value_name = "FILE")]
    pub save: Option<PathBuf>,
    /// Draw the return curve and its moving average to FILE.png or FILE.svg.
    #[arg(long, value_name = "FILE")]
    pub plot: Option<PathBuf>,
    /// No progress bars and no terminal plot: only the summary.
    #[arg(long, short)]
    pub quiet: bool,
    /// Actor (policy) learning rate.
    #[arg(long, default_value_t = 1e-3, allow_hyphen_values = true)]
    pub actor_lr: f64,
    /// Critic (value) learning rate.
    #[arg(long, default_value_t = 1e-2, allow_hyphen_values = true)]
    pub critic_lr: f64,
    /// Discount factor γ, in (0, 1].
    #[arg(long, default_value_t = 0.98, allow_hyphen_values = true)]
    pub gamma: f64,
    /// GAE λ, in [0, 1].
    #[arg(long, default_value_t = 0.95, allow_hyphen_values = true)]
    pub lmbda: f64,
    /// Clip range ε, in (0, 1).
    #[arg(long, default_value_t = 0.2, allow_hyphen_values = true)]
    pub eps: f64,
    /// Epochs per update.
    #[arg(long, default_value_t = 10)]
    pub epochs: usize,
    /// Hidden width of both networks.
    #[arg(long, default_value_t = 128)]
    pub hidden_dim: usize,
    /// Bootstrap from V(s') when the time limit cuts an episode (not in the seed).
    #[arg(long)]
    pub bootstrap_truncation: bool,
    /// Normalise advantages to mean 0, std 1 (not in the seed).
    #[arg(long)]
    pub normalize_advantage: bool,
    /// Entropy bonus coefficient; 0 is off (the seed).
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    pub entropy_coef: f64,
    /// Clip each network's gradient norm to this value (off in the seed).
    #[arg(long, allow_hyphen_values = true)]
    pub max_grad_norm: Option<f64>,
    /// Stop an update's epochs once approx_kl exceeds 1.5 × this (Spinning Up); off in the seed.
    #[arg(long, allow_hyphen_values = true)]
    pub target_kl: Option<f64>,
    /// Drop the clip: the actor loss is −mean(ratio·Â) (the clip-lab experiment); off in the seed.
    #[arg(long)]
    pub no_clip: bool,
    /// The update rule: ppo (the seed) or reinforce (REINFORCE with a baseline: one step per
    /// episode on log π·(G_t − V(s_t)), no ratio, no clip).
    #[arg(long, value_enum, default_value = "ppo")]
    pub algorithm: AlgorithmArg,
}

/// `--algorithm` values.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum AlgorithmArg {
    /// The seed's PPO.
    Ppo,
    /// REINFORCE with the critic as baseline.
    Reinforce,
}

impl From<AlgorithmArg> for Algorithm {
    fn from(a: AlgorithmArg) -> Self {
        match a {
            AlgorithmArg::Ppo => Self::Ppo,
            AlgorithmArg::Reinforce => Self::Reinforce,
        }
    }
}

impl TrainArgs {
    /// The configuration these arguments describe.
    #[must_use]
    pub fn config(&self) -> PpoConfig {
        PpoConfig {
            actor_lr: self.actor_lr,
            critic_lr: self.critic_lr,
            hidden_dim: self.hidden_dim,
            gamma: self.gamma,
            lmbda: self.lmbda,
            epochs: self.epochs,
            eps: self.eps,
            num_episodes: self.episodes,
            env_id: self.env_id,
            bootstrap_on_truncation: self.bootstrap_truncation,
            normalize_advantage: self.normalize_advantage,
            entropy_coef: self.entropy_coef,
            max_grad_norm: self.max_grad_norm,
            target_kl: self.target_kl,
            no_clip: self.no_clip,
            algorithm: self.algorithm.into(),
        }
    }
}

/// Runs `ppo-tutor train`.
///
/// # Errors
/// Training diverged, or an output file could not be written.
pub fn run(args: &TrainArgs) -> anyhow::Result<ExitCode> {
    let config = args.config();
    if let Err(err) = config.validate() {
        let err = match err {
            PpoError::InvalidConfig {
                field,
                value,
                expected,
            } => format!("invalid --{} {value}: expected {expected}", flag_of(field)),
            other => other.to_string(),
        };
        eprintln!("error: {err} (see --help)");
        return Ok(ExitCode::from(super::EXIT_USAGE));
    }
    if let Some(seeds) = &args.seeds {
        return several::run(args, &config, &seeds.0);
    }
    let mut bars = Bars::new(!args.quiet && std::io::stderr().is_terminal(), !args.quiet);
    let (summary, agent) = train(config.clone(), args.seed, |report| {
        bars.update(report);
        ControlFlow::Continue(())
    })
    .context("training stopped")?;
    bars.finish();

    let smoothed = smoothed_returns(&summary.returns);
    print_summary(&summary, &config, args.seed, &smoothed, !args.quiet)?;
    if let Some(path) = &args.json {
        let value = run_json(&summary, &config, args.seed, &smoothed);
        std::fs::write(path, format!("{value}\n"))
            .with_context(|| format!("writing {}", path.display()))?;
    }
    let mut out = std::io::stdout();
    if let Some(path) = &args.save {
        agent.save(path).context("saving the agent")?;
        writeln!(out, "saved the agent to {}", path.display())?;
    }
    if let Some(path) = &args.plot {
        let title = format!("PPO on {}", config.env_id);
        save_return_plot(path, &title, &summary.returns, &smoothed)?;
        writeln!(out, "drew the return curve to {}", path.display())?;
    }
    Ok(ExitCode::SUCCESS)
}

mod several;

/// The `--flag` spelling of a config field.
fn flag_of(field: &str) -> String {
    match field {
        "num_episodes" => "episodes".into(),
        "bootstrap_on_truncation" => "bootstrap-truncation".into(),
        other => other.replace('_', "-"),
    }
}

/// The `--json` document: what `seed_ppo.py --json` writes, plus the configuration.
pub(super) fn run_json(
    summary: &TrainSummary,
    config: &PpoConfig,
    seed: u64,
    smoothed: &[f64],
) -> serde_json::Value {
    json!({
        "episodes": summary.returns.len(),
        "seed": seed,
        "env": config.env_id.as_str(),
        "env_steps": summary.env_steps,
        "wall_s": summary.wall_s,
        "steps_per_s": summary.steps_per_s(),
        "mean_last_50": summary.mean_last(50),
        "peak_rss_mb": peak_rss_mb(),
        "returns": summary.returns,
        "moving_average": smoothed,
        "config": config,
    })
}

/// The process's peak resident memory in MB (Linux `VmHWM`), `None` elsewhere.
#[must_use]
pub fn peak_rss_mb() -> Option<f64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kb: f64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb / 1024.0)
}

fn print_summary(
    summary: &TrainSummary,
    config: &PpoConfig,
    seed: u64,
    smoothed: &[f64],
    plot: bool,
) -> anyhow::Result<()> {
    let mut out = std::io::stdout().lock();
    let best = summary.returns.iter().copied().fold(0.0, f64::max);
    writeln!(
        out,
        "PPO on {}, seed {seed}: {} episodes, {} env steps in {:.2} s ({:.0} steps/s)",
        config.env_id,
        summary.returns.len(),
        summary.env_steps,
        summary.wall_s,
        summary.steps_per_s()
    )?;
    writeln!(
        out,
        "mean return of the last {} episodes: {:.1}   (last 10: {:.1}, best: {best})",
        summary.returns.len().min(50),
        summary.mean_last(50),
        summary.mean_last(10),
    )?;
    if plot {
        let width = crossterm::terminal::size().map_or(80, |(w, _)| usize::from(w));
        writeln!(out)?;
        for line in ascii_return_plot(&summary.returns, smoothed, width.clamp(30, 120) - 8, 14) {
            writeln!(out, "{line}")?;
        }
    }
    Ok(())
}

/// The seed's ten tqdm bars ("Iteration i"), with the same postfix every 10 episodes.
struct Bars {
    bar: Option<ProgressBar>,
    draw: bool,
    lines: bool,
    returns: Vec<f64>,
}

impl Bars {
    /// `draw`: animated bars (a terminal); else `lines`: one line per finished iteration.
    fn new(draw: bool, lines: bool) -> Self {
        Self {
            bar: None,
            draw,
            lines: lines && !draw,
            returns: Vec::new(),
        }
    }

    fn update(&mut self, r: &EpisodeReport) {
        self.returns.push(r.episode_return);
        if self.draw && r.episode_in_iteration == 0 {
            let style = ProgressStyle::with_template(
                "{prefix}: {percent:>3}%|{bar:20}| {pos}/{len} [{elapsed}<{eta}{msg}]",
            )
            .unwrap_or_else(|_| ProgressStyle::default_bar());
            let bar = ProgressBar::new(r.iteration_len as u64)
                .with_style(style.progress_chars("█▉▊▋▌▍▎▏ "))
                .with_prefix(format!("Iteration {}", r.iteration));
            self.bar = Some(bar);
        }
        let postfix = (r.episode_in_iteration + 1).is_multiple_of(10);
        let message = format!(
            ", episode={}, return={:.3}",
            r.episode + 1,
            mean_last(&self.returns, 10)
        );
        if let Some(bar) = &self.bar {
            if postfix {
                bar.set_message(message.clone());
            }
            bar.inc(1);
            if r.episode_in_iteration + 1 == r.iteration_len {
                bar.finish();
            }
        }
        if self.lines && r.episode_in_iteration + 1 == r.iteration_len {
            eprintln!(
                "Iteration {}: {}/{}{message}",
                r.iteration, r.iteration_len, r.iteration_len
            );
        }
    }

    fn finish(&mut self) {
        if let Some(bar) = self.bar.take()
            && !bar.is_finished()
        {
            bar.abandon();
        }
    }
}
