//! `ppo-tutor train`: the seed's `train_on_policy_agent` with tqdm-like progress bars, a
//! summary, the return curve in the terminal, and optional JSON, checkpoint and figure.
//! `--env Pendulum-v1` trains the book's `PPOContinuous` the same way ([`setup`]).

use std::io::{IsTerminal, Write};
use std::ops::ControlFlow;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use anyhow::Context;
use clap::Args;
use indicatif::{ProgressBar, ProgressStyle};
use serde_json::json;

use super::args::{SeedList, parse_seed, parse_seeds};
use super::interrupt::Interrupt;
use crate::env::EnvId;
use crate::i18n::t;
use crate::lesson::RunConfig;
use crate::plot::{XAxis, ascii_return_plot, labels, save_return_plot_over};
use crate::ppo::knobs::Tunable;
use crate::ppo::train::mean_last;
use crate::ppo::{
    Algorithm, EpisodeReport, Objective, OnPolicyAgent, PpoConfig, PpoError, TrainSummary,
    UpdatePath, train,
};
use crate::run::RunVisitor;
use crate::tr;

pub mod setup;
mod several;

pub use setup::{parse_train_env, run_config};

/// Arguments of `ppo-tutor train`; defaults are the seed's on CartPole, the book's on
/// Pendulum-v1.
#[derive(Debug, Args)]
#[command(
    after_help = "Examples:\n  ppo-tutor train\n  ppo-tutor train --seed 3 --json run.json --save agent.safetensors --plot returns.svg\n  ppo-tutor play --load agent.safetensors\n  ppo-tutor train --seeds 0-4 --plot seeds.svg --json seeds.json\n  ppo-tutor train --env Pendulum-v1 --save pendulum.safetensors && ppo-tutor play --load pendulum.safetensors"
)]
pub struct TrainArgs {
    /// Episodes to train for (one update per episode) [default: 500 on CartPole, 2000 on
    /// Pendulum-v1].
    #[arg(long, value_parser = super::args::parse_count, allow_hyphen_values = true)]
    pub episodes: Option<usize>,
    /// Seed of the network initialisation, the action sampling and the first env.reset.
    #[arg(long, default_value = "0", value_parser = parse_seed, allow_hyphen_values = true)]
    pub seed: u64,
    /// Train several seeds in parallel (a range or a list: 0-4, 1,3,8): prints each seed's
    /// mean of the last 50 returns (100 on Pendulum-v1) and their mean ± std, and draws the
    /// mean curve over the band of the seeds.
    #[arg(long, value_name = "LIST", value_parser = parse_seeds, conflicts_with_all = ["seed", "save"])]
    pub seeds: Option<SeedList>,
    /// Gymnasium environment id, in any case: CartPole-v1 and CartPole-v0 (the seed's PPO) or
    /// Pendulum-v1 (the book's PPOContinuous, a Gaussian policy).
    #[arg(long = "env", default_value = "CartPole-v1", value_parser = parse_train_env)]
    pub env_id: crate::run::Choice,
    /// Write returns, env steps and timing as JSON to FILE.
    #[arg(long, value_name = "FILE")]
    pub json: Option<PathBuf>,
    /// Save the trained agent to FILE.safetensors (watch it with `ppo-tutor play --load`).
    #[arg(long, value_name = "FILE")]
    pub save: Option<PathBuf>,
    /// Draw the return curve and its moving average to FILE.png or FILE.svg.
    #[arg(long, value_name = "FILE")]
    pub plot: Option<PathBuf>,
    /// What --plot draws the returns against: each episode's number, or the environment
    /// steps taken when it ended (the axis on which runs of different episode lengths or
    /// rollouts compare).
    #[arg(long, value_enum, default_value_t = XAxisArg::Episodes, requires = "plot", conflicts_with = "seeds")]
    pub x_axis: XAxisArg,
    /// No progress bars and no terminal plot: only the summary.
    #[arg(long, short)]
    pub quiet: bool,
    /// Actor (policy) learning rate [default: 1e-3 on CartPole, 1e-4 on Pendulum-v1].
    #[arg(long, allow_hyphen_values = true)]
    pub actor_lr: Option<f64>,
    /// Critic (value) learning rate [default: 1e-2 on CartPole, 5e-3 on Pendulum-v1].
    #[arg(long, allow_hyphen_values = true)]
    pub critic_lr: Option<f64>,
    /// Discount factor γ, in (0, 1] [default: 0.98 on CartPole, 0.9 on Pendulum-v1].
    #[arg(long, allow_hyphen_values = true)]
    pub gamma: Option<f64>,
    /// GAE λ, in [0, 1] [default: 0.95 on CartPole, 0.9 on Pendulum-v1].
    #[arg(long, allow_hyphen_values = true)]
    pub lmbda: Option<f64>,
    /// Clip range ε, in (0, 1) [default: 0.2].
    #[arg(long, allow_hyphen_values = true)]
    pub eps: Option<f64>,
    /// Epochs per update [default: 10].
    #[arg(long, value_parser = super::args::parse_whole, allow_hyphen_values = true)]
    pub epochs: Option<usize>,
    /// The critic's steps per update, when they should differ from the actor's --epochs
    /// (the clip lab's epochs experiment) [default: as many as the actor's; CartPole only].
    #[arg(long, value_parser = super::args::parse_whole, allow_hyphen_values = true)]
    pub critic_epochs: Option<usize>,
    /// Hidden width of both networks [default: 128].
    #[arg(long, value_parser = super::args::parse_whole, allow_hyphen_values = true)]
    pub hidden_dim: Option<usize>,
    /// Bootstrap from V(s') when the time limit cuts an episode (not in the seed; CartPole
    /// only).
    #[arg(long)]
    pub bootstrap_truncation: bool,
    /// Normalise advantages to mean 0, std 1 (not in the seed; CartPole only).
    #[arg(long)]
    pub normalize_advantage: bool,
    /// Entropy bonus coefficient; 0 is off (the seed; CartPole only).
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    pub entropy_coef: f64,
    /// Clip each network's gradient norm to this value (off in the seed; CartPole only).
    #[arg(long, allow_hyphen_values = true)]
    pub max_grad_norm: Option<f64>,
    /// Stop an update's epochs once approx_kl exceeds 1.5 × this (Spinning Up); off in the
    /// seed; CartPole only.
    #[arg(long, allow_hyphen_values = true)]
    pub target_kl: Option<f64>,
    /// Drop the clip: the actor loss is −mean(ratio·Â) (the clip-lab experiment); off in the
    /// seed; CartPole only.
    #[arg(long)]
    pub no_clip: bool,
    /// The update rule: ppo (the seed) or reinforce (REINFORCE with a baseline: one step per
    /// episode on log π·(G_t − V(s_t)), no ratio, no clip; CartPole only).
    #[arg(long, value_enum, default_value = "ppo")]
    pub algorithm: AlgorithmArg,
    /// PPO's objective for the actor: clip (the seed's PPO-Clip), penalty (PPO-Penalty:
    /// −mean(ratio·Â) + β·mean(KL(π_old‖π)), β halved or doubled after each update to keep
    /// the KL near --kl-delta) or line-search (a KL-constrained line search on the
    /// surrogate's gradient, TRPO's constraint without its natural gradient: one actor step
    /// per update, halved until the mean KL ≤ --kl-delta and the surrogate improves);
    /// CartPole only.
    #[arg(long, value_enum, default_value = "clip")]
    pub objective: ObjectiveArg,
    /// PPO-Penalty's first β [default: 1].
    #[arg(long, allow_hyphen_values = true)]
    pub beta_init: Option<f64>,
    /// PPO-Penalty's KL target δ: β halves below δ/1.5 and doubles above 1.5·δ; the line
    /// search's bound on the mean KL [default: 0.01]. Not --target-kl, which stops epochs
    /// early.
    #[arg(long, allow_hyphen_values = true)]
    pub kl_delta: Option<f64>,
    /// The line search's first step length α along the gradient's unit direction
    /// [default: 0.25].
    #[arg(long, allow_hyphen_values = true)]
    pub ls_max_step: Option<f64>,
    /// The line search's most halvings of α before the actor keeps θ_old [default: 10].
    #[arg(long, value_parser = super::args::parse_whole, allow_hyphen_values = true)]
    pub ls_backtracks: Option<usize>,
}

/// `--objective` values.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum ObjectiveArg {
    /// PPO-Clip, the seed's.
    Clip,
    /// PPO-Penalty, an adaptive KL penalty.
    Penalty,
    /// A KL-constrained line search on the surrogate's gradient (not TRPO).
    LineSearch,
}

impl From<ObjectiveArg> for Objective {
    fn from(o: ObjectiveArg) -> Self {
        match o {
            ObjectiveArg::Clip => Self::Clip,
            ObjectiveArg::Penalty => Self::Penalty,
            ObjectiveArg::LineSearch => Self::LineSearch,
        }
    }
}

/// `--x-axis` values.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum XAxisArg {
    /// Episode 0, 1, 2, ...
    Episodes,
    /// The environment steps since training began, at each episode's end.
    Steps,
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
    /// The CartPole configuration these arguments describe, on `env_id`; flags left out
    /// take the seed's values.
    #[must_use]
    pub fn config_for(&self, env_id: EnvId) -> PpoConfig {
        let seed = PpoConfig::default();
        PpoConfig {
            actor_lr: self.actor_lr.unwrap_or(seed.actor_lr),
            critic_lr: self.critic_lr.unwrap_or(seed.critic_lr),
            hidden_dim: self.hidden_dim.unwrap_or(seed.hidden_dim),
            gamma: self.gamma.unwrap_or(seed.gamma),
            lmbda: self.lmbda.unwrap_or(seed.lmbda),
            epochs: self.epochs.unwrap_or(seed.epochs),
            critic_epochs: self.critic_epochs,
            eps: self.eps.unwrap_or(seed.eps),
            num_episodes: self.episodes.unwrap_or(seed.num_episodes),
            env_id,
            bootstrap_on_truncation: self.bootstrap_truncation,
            normalize_advantage: self.normalize_advantage,
            entropy_coef: self.entropy_coef,
            max_grad_norm: self.max_grad_norm,
            target_kl: self.target_kl,
            no_clip: self.no_clip,
            algorithm: self.algorithm.into(),
            objective: self.objective.into(),
            beta_init: self.beta_init.unwrap_or(seed.beta_init),
            kl_delta: self.kl_delta.unwrap_or(seed.kl_delta),
            ls_max_step: self.ls_max_step.unwrap_or(seed.ls_max_step),
            ls_backtracks: self.ls_backtracks.unwrap_or(seed.ls_backtracks),
        }
    }
}

/// Runs `ppo-tutor train`.
///
/// # Errors
/// Training diverged, or an output file could not be written.
pub fn run(args: &TrainArgs) -> anyhow::Result<ExitCode> {
    let setup = match run_config(args) {
        Ok(setup) => setup,
        Err(err) => {
            eprintln!("{}{err}{}", super::error_prefix(), super::see_help());
            return Ok(ExitCode::from(super::EXIT_USAGE));
        }
    };
    // Every output path is checked before training, not found bad after it.
    for (flag, path) in outputs(args) {
        if let Err(err) = super::args::check_output(flag, path, extensions(flag)) {
            eprintln!("{}{err}", super::error_prefix());
            return Ok(ExitCode::from(super::EXIT_USAGE));
        }
    }
    let interrupt = Interrupt::install();
    if let Some(seeds) = &args.seeds {
        return several::run(args, &setup, &seeds.0, &interrupt);
    }
    let mut bars = Bars::new(!args.quiet && std::io::stderr().is_terminal(), !args.quiet);
    let mut paths = Paths::default();
    let (summary, agent) = setup
        .visit(TrainOne {
            seed: args.seed,
            bars: &mut bars,
            paths: &mut paths,
            interrupt: &interrupt,
        })
        .context(t("training stopped", "训练中止"))?;
    bars.finish();
    let mut written = Written::new(args, setup.num_episodes(), &interrupt);
    if summary.returns.len() < setup.num_episodes() {
        return Ok(written.stopped(summary.returns.len()));
    }

    let (window, smoothed) = crate::plot::window::smoothed(&summary.returns);
    print_summary(
        &summary,
        &setup,
        args.seed,
        (&smoothed, window),
        &paths,
        !args.quiet,
    )?;
    let mut out = std::io::stdout();
    if let Some(path) = &args.json {
        if let Some(code) = written.interrupted() {
            return Ok(code);
        }
        let value = run_json(&summary, &setup, args.seed, (&smoothed, window));
        write_output(path, format!("{value}\n").as_bytes())?;
        written.done("--json", path);
    }
    if let Some(path) = &args.save {
        if let Some(code) = written.interrupted() {
            return Ok(code);
        }
        agent(path).context(t("saving the agent", "保存智能体"))?;
        written.done("--save", path);
        let shown = path.display();
        writeln!(
            out,
            "{}",
            tr!("saved the agent to {shown}", "已把智能体保存到 {shown}")
        )?;
    }
    if let Some(path) = &args.plot {
        if let Some(code) = written.interrupted() {
            return Ok(code);
        }
        let title = labels::return_title(labels::algorithm(&setup), setup.env_id());
        let x = match args.x_axis {
            XAxisArg::Episodes => XAxis::Episodes,
            XAxisArg::Steps => XAxis::Steps(&summary.episode_end_steps),
        };
        save_return_plot_over(path, &title, &summary.returns, (&smoothed, window), x)?;
        written.done("--plot", path);
        let shown = path.display();
        writeln!(
            out,
            "{}",
            tr!(
                "drew the return curve to {shown}",
                "已把回报曲线画到 {shown}"
            )
        )?;
    }
    Ok(ExitCode::SUCCESS)
}

/// The output paths given, by flag, in the order they are written.
fn outputs(args: &TrainArgs) -> Vec<(&'static str, &Path)> {
    [
        ("--json", args.json.as_deref()),
        ("--save", args.save.as_deref()),
        ("--plot", args.plot.as_deref()),
    ]
    .into_iter()
    .filter_map(|(flag, path)| path.map(|p| (flag, p)))
    .collect()
}

/// The extensions an output flag's file may have (`None`: any).
fn extensions(flag: &str) -> Option<&'static [&'static str]> {
    match flag {
        "--plot" => Some(&["png", "svg"]),
        "--save" => Some(&["safetensors"]),
        _ => None,
    }
}

/// Writes an output file whole or not at all ([`ppo_engine::files::write_atomically`]); the
/// error names the user's path.
pub(super) fn write_output(path: &Path, bytes: &[u8]) -> anyhow::Result<()> {
    ppo_engine::files::write_atomically(path, bytes).with_context(|| writing(path))
}

/// Which outputs have been written, to say so when Ctrl-C stops the command.
pub(super) struct Written<'a> {
    interrupt: &'a Interrupt,
    episodes: usize,
    written: Vec<String>,
    pending: Vec<String>,
}

impl<'a> Written<'a> {
    /// None written yet of those `args` asks for, after a run of `episodes`.
    pub(super) fn new(args: &TrainArgs, episodes: usize, interrupt: &'a Interrupt) -> Self {
        let pending = outputs(args)
            .into_iter()
            .map(|(flag, path)| format!("{flag} {}", path.display()))
            .collect();
        Self {
            interrupt,
            episodes,
            written: Vec::new(),
            pending,
        }
    }

    /// Notes that `flag`'s `path` was written.
    pub(super) fn done(&mut self, flag: &str, path: &Path) {
        let entry = format!("{flag} {}", path.display());
        self.pending.retain(|p| *p != entry);
        self.written.push(entry);
    }

    /// Says where Ctrl-C stopped training (after `done` episodes) and what was written;
    /// the exit code to return.
    pub(super) fn stopped(&self, done: usize) -> ExitCode {
        eprintln!(
            "{}",
            super::interrupt::stopped_line(done, self.episodes, &self.written, &self.pending)
        );
        ExitCode::from(super::interrupt::EXIT_INTERRUPTED)
    }

    /// After training: when Ctrl-C was pressed since, says so and what was written, and
    /// gives the exit code to return.
    pub(super) fn interrupted(&self) -> Option<ExitCode> {
        self.interrupt
            .pressed()
            .then(|| self.stopped(self.episodes))
    }
}

/// Saves the trained agent to a file.
type SaveAgent = Box<dyn FnOnce(&Path) -> Result<(), PpoError>>;

/// Trains one seed of any agent, drawing the progress bars, until the last episode or
/// Ctrl-C.
struct TrainOne<'a> {
    seed: u64,
    bars: &'a mut Bars,
    paths: &'a mut Paths,
    interrupt: &'a Interrupt,
}

impl RunVisitor for TrainOne<'_> {
    type Output = Result<(TrainSummary, SaveAgent), PpoError>;

    fn visit<C: Tunable>(self, config: &C) -> Self::Output {
        let (bars, paths, interrupt) = (self.bars, self.paths, self.interrupt);
        let (summary, agent) = train(config.clone(), self.seed, |report| {
            bars.update(&Progress::from(report));
            paths.add(C::Agent::path_of(&report.trace));
            if interrupt.pressed() {
                ControlFlow::Break(())
            } else {
                ControlFlow::Continue(())
            }
        })?;
        Ok((summary, Box::new(move |path| agent.save_to(path))))
    }
}

/// The `--json` document: what `seed_ppo.py --json` writes, plus the configuration, the
/// moving average's window (and, on Pendulum-v1, `book_ppo_continuous.py`'s
/// `mean_last_100`).
pub(super) fn run_json(
    summary: &TrainSummary,
    setup: &RunConfig,
    seed: u64,
    (smoothed, window): (&[f64], usize),
) -> serde_json::Value {
    let mut value = json!({
        "episodes": summary.returns.len(),
        "seed": seed,
        "env": setup.env_id(),
        "env_steps": summary.env_steps,
        "episode_end_steps": summary.episode_end_steps,
        "wall_s": summary.wall_s,
        "steps_per_s": summary.steps_per_s(),
        "mean_last_50": summary.mean_last(50),
        "peak_rss_mb": peak_rss_mb(),
        "returns": summary.returns,
        "moving_average": smoothed,
        "moving_average_window": window,
        "config": setup,
    });
    // book_ppo_continuous.py's figure, beside the seed's.
    let window = setup.agent().spec().summary_window;
    if window != 50 {
        value[format!("mean_last_{window}")] = json!(summary.mean_last(window));
    }
    value
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
    setup: &RunConfig,
    seed: u64,
    smoothed: (&[f64], usize),
    paths: &Paths,
    plot: bool,
) -> anyhow::Result<()> {
    let mut out = std::io::stdout().lock();
    let best = summary
        .returns
        .iter()
        .copied()
        .fold(f64::NEG_INFINITY, f64::max);
    // CartPole's returns are whole numbers; Pendulum's are not.
    let best = setup.agent().format_return(best);
    let title = labels::return_title(labels::algorithm(setup), setup.env_id());
    let (episodes, steps) = (summary.returns.len(), summary.env_steps);
    let (wall, rate) = (summary.wall_s, summary.steps_per_s());
    writeln!(
        out,
        "{}",
        tr!(
            "{title}, seed {seed}: {episodes} episodes, {steps} env steps in {wall:.2} s ({rate:.0} steps/s)",
            "{title}，随机种子 {seed}：{episodes} 个回合，环境共 {steps} 步，用时 {wall:.2} 秒（每秒 {rate:.0} 步）"
        )
    )?;
    let last = setup.agent().spec().summary_window;
    let (n, mean, mean10) = (
        summary.returns.len().min(last),
        summary.mean_last(last),
        summary.mean_last(10),
    );
    writeln!(
        out,
        "{}",
        tr!(
            "mean return of the last {n} episodes: {mean:.1}   (last 10: {mean10:.1}, best: {best})",
            "最后 {n} 个回合的平均回报：{mean:.1}（最后 10 个：{mean10:.1}，最高：{best}）"
        )
    )?;
    writeln!(out, "{}", paths.line())?;
    if plot {
        let width = crossterm::terminal::size().map_or(80, |(w, _)| usize::from(w));
        writeln!(out)?;
        for line in ascii_return_plot(&summary.returns, smoothed, width.clamp(30, 120) - 8, 14) {
            writeln!(out, "{line}")?;
        }
    }
    Ok(())
}

/// How many updates ran on each [`UpdatePath`], for the summary.
#[derive(Debug, Default)]
struct Paths {
    plain: usize,
    candle: usize,
}

impl Paths {
    fn add(&mut self, path: UpdatePath) {
        match path {
            UpdatePath::Plain => self.plain += 1,
            UpdatePath::Candle => self.candle += 1,
        }
    }

    /// The summary's line: which implementation ran the updates, and why candle if it ran
    /// every one of them.
    fn line(&self) -> String {
        let (plain, candle) = (self.plain, self.candle);
        if candle == 0 {
            return tr!(
                "update path: plain f32 kernels for all {plain} updates",
                "更新路径：全部 {plain} 次更新均用纯 f32 内核"
            );
        }
        if plain > 0 {
            return tr!(
                "update path: plain f32 kernels for {plain} updates, candle (autograd) for {candle}",
                "更新路径：{plain} 次更新用纯 f32 内核，{candle} 次用 candle（自动求导）"
            );
        }
        let why = if UpdatePath::forced() == Some(UpdatePath::Candle) {
            t(
                ", forced by PPO_TUTOR_UPDATE=candle",
                "，由 PPO_TUTOR_UPDATE=candle 强制",
            )
        } else if UpdatePath::plain_available() {
            t(
                ", which these options or shapes need",
                "，因为这些选项或形状需要自动求导",
            )
        } else {
            t(
                ", as this CPU lacks AVX2+FMA",
                "，因为本机 CPU 不支持 AVX2+FMA",
            )
        };
        tr!(
            "update path: candle (autograd) for all {candle} updates{why}",
            "更新路径：全部 {candle} 次更新均用 candle（自动求导）{why}"
        )
    }
}

/// What the progress bars need from one episode, of either agent.
struct Progress {
    episode: usize,
    iteration: usize,
    episode_in_iteration: usize,
    iteration_len: usize,
    episode_return: f64,
}

impl<T> From<&EpisodeReport<T>> for Progress {
    fn from(r: &EpisodeReport<T>) -> Self {
        Self {
            episode: r.episode,
            iteration: r.iteration,
            episode_in_iteration: r.episode_in_iteration,
            iteration_len: r.iteration_len,
            episode_return: r.episode_return,
        }
    }
}

/// `writing PATH`, the context of a file that could not be written.
pub(super) fn writing(path: &Path) -> String {
    let shown = path.display();
    tr!("writing {shown}", "写入 {shown}")
}

/// The seed's tqdm prefix, `Iteration i`, in the current language.
fn iteration_label(i: usize) -> String {
    tr!("Iteration {i}", "第 {i} 次迭代")
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

    fn update(&mut self, r: &Progress) {
        self.returns.push(r.episode_return);
        if self.draw && r.episode_in_iteration == 0 {
            let style = ProgressStyle::with_template(
                "{prefix}: {percent:>3}%|{bar:20}| {pos}/{len} [{elapsed}<{eta}{msg}]",
            )
            .unwrap_or_else(|_| ProgressStyle::default_bar());
            let bar = ProgressBar::new(r.iteration_len as u64)
                .with_style(style.progress_chars("█▉▊▋▌▍▎▏ "))
                .with_prefix(iteration_label(r.iteration));
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
                "{}: {}/{}{message}",
                iteration_label(r.iteration),
                r.iteration_len,
                r.iteration_len
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
