//! `ppo-tutor cartpole`: run the native CartPole and print what Gymnasium would; with
//! `--envs N`, N of them as Gymnasium's `SyncVectorEnv` ([`vector`]).

pub mod vector;

use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Duration;

use anyhow::Context;
use clap::{Args, ValueEnum};

use super::args::{ActionList, parse_actions, parse_env, parse_seed};
use super::pad_left;
use crate::env::{Autoreset, CartPoleConfig, EnvId, Integrator, Policy, Trajectory};
use crate::i18n::t as t_;
use crate::tr;

/// Arguments of `ppo-tutor cartpole`.
#[derive(Debug, Args)]
#[command(
    after_help = "Examples:\n  ppo-tutor cartpole --seed 0 --actions 0,1,1,0 --json\n  ppo-tutor cartpole --seed 3 --policy lean --render\n  ppo-tutor cartpole --envs 4 --seed 0 --autoreset next-step --actions-file steps.json --json"
)]
pub struct CartpoleArgs {
    /// Seed for reset(seed=...), any integer from 0 to 2^64-1.
    #[arg(long, default_value = "0", value_parser = parse_seed, allow_hyphen_values = true)]
    pub seed: u64,
    /// Actions to apply in order, comma-separated 0 (left) / 1 (right); '' only resets.
    #[arg(long, value_parser = parse_actions, conflicts_with = "policy", allow_hyphen_values = true)]
    pub actions: Option<ActionList>,
    /// Pick actions with a policy instead of --actions.
    #[arg(long, value_enum)]
    pub policy: Option<PolicyArg>,
    /// Most steps a --policy plays (the time limit also ends the episode).
    #[arg(long, default_value_t = 500)]
    pub max_steps: usize,
    /// Gymnasium environment id: CartPole-v1 (500-step limit) or CartPole-v0 (200).
    #[arg(long = "env", default_value = "CartPole-v1", value_parser = parse_env)]
    pub env_id: EnvId,
    /// Use semi-implicit Euler instead of Gymnasium's default explicit Euler.
    #[arg(long)]
    pub semi_implicit: bool,
    /// Gymnasium's sutton_barto_reward: 0 per step, -1 when the pole falls.
    #[arg(long)]
    pub sutton_barto_reward: bool,
    /// Also record the states of N further unseeded resets (as `next_resets`).
    #[arg(long, default_value_t = 0, value_parser = super::args::parse_whole, allow_hyphen_values = true)]
    pub resets: usize,
    /// Print one JSON object in the schema of Gymnasium's fixture traces.
    #[arg(long, conflicts_with = "render")]
    pub json: bool,
    /// Animate the cart and pole in the terminal instead of printing a table.
    #[arg(long)]
    pub render: bool,
    /// Step N CartPoles together, as Gymnasium's SyncVectorEnv (env i reset with seed + i); needs --actions-file.
    #[arg(long, value_name = "N", value_parser = parse_envs, requires = "actions_file",
          conflicts_with_all = ["actions", "policy", "render", "resets"], allow_hyphen_values = true)]
    pub envs: Option<usize>,
    /// With --envs: how an env whose episode ended is reset, same-step (gymnasium 0.29, CleanRL) or next-step (Gymnasium 1.x).
    #[arg(long, value_name = "MODE", value_enum, default_value_t = AutoresetArg::SameStep, requires = "envs")]
    pub autoreset: AutoresetArg,
    /// With --envs N: a JSON file of steps, each an array of N actions 0 or 1, like [[0, 1], [1, 1]].
    #[arg(long, value_name = "FILE", requires = "envs")]
    pub actions_file: Option<PathBuf>,
}

/// `--envs`: a number of environments, 1 or more.
fn parse_envs(s: &str) -> Result<usize, String> {
    match s.trim().parse::<usize>() {
        Ok(n) if n > 0 => Ok(n),
        _ => Err(tr!(
            "expected a number of environments, 1 or more, got '{s}'",
            "应为环境的个数，至少 1，实际是 '{s}'"
        )),
    }
}

/// The `--autoreset` choices.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum AutoresetArg {
    /// The ending step returns the next episode's first observation, the last one in final_obs.
    SameStep,
    /// The ending step returns the last observation; the next step resets that env.
    NextStep,
}

impl From<AutoresetArg> for Autoreset {
    fn from(mode: AutoresetArg) -> Self {
        match mode {
            AutoresetArg::SameStep => Autoreset::SameStep,
            AutoresetArg::NextStep => Autoreset::NextStep,
        }
    }
}

/// The `--policy` choices.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum PolicyArg {
    /// Uniformly random actions (seeded by --seed).
    Random,
    /// Push towards the pole's lean, with 10% random actions: long episodes.
    Lean,
}

/// Runs `ppo-tutor cartpole`.
///
/// # Errors
/// Writing to standard output failed, or JSON encoding failed.
pub fn run(args: &CartpoleArgs) -> anyhow::Result<ExitCode> {
    let mut config = CartPoleConfig::new(args.env_id);
    if args.semi_implicit {
        config.integrator = Integrator::SemiImplicitEuler;
    }
    config.sutton_barto_reward = args.sutton_barto_reward;
    if let (Some(n), Some(file)) = (args.envs, &args.actions_file) {
        return vector::run(config, n, args.seed, args.autoreset.into(), file, args.json);
    }
    let (policy, max_steps) = match (&args.actions, args.policy) {
        (Some(ActionList(list)), _) => (Policy::Actions(list.clone()), list.len()),
        (None, Some(PolicyArg::Random)) => (Policy::Random, args.max_steps),
        (None, Some(PolicyArg::Lean)) => (Policy::Lean, args.max_steps),
        (None, None) => {
            eprintln!(
                "{}{}{}",
                super::error_prefix(),
                t_(
                    "give --actions 0,1,... or --policy random|lean (or --envs N --actions-file FILE)",
                    "请给出 --actions 0,1,...，或者 --policy random 或 --policy lean（或者 --envs <个数> --actions-file <文件>）"
                ),
                super::see_help()
            );
            return Ok(ExitCode::from(super::EXIT_USAGE));
        }
    };
    let t = Trajectory::record(config, args.seed, &policy, max_steps, args.resets)
        .context(t_("recording the episode", "记录回合"))?;
    if let Policy::Actions(list) = &policy
        && t.actions.len() < list.len()
    {
        let (done, all) = (t.actions.len(), list.len());
        eprintln!(
            "{}",
            tr!(
                "note: the episode ended after {done} of the {all} actions; the rest were not applied",
                "注意：回合在 {all} 个动作中的第 {done} 个之后就结束了，其余动作没有执行"
            )
        );
    }
    if args.json {
        let mut value =
            serde_json::to_value(&t).context(t_("encoding the trajectory", "编码轨迹"))?;
        if let Some(map) = value.as_object_mut() {
            map.insert("env".into(), args.env_id.as_str().into());
            if args.resets > 0 && !map.contains_key("next_resets") {
                map.insert("next_resets".into(), serde_json::Value::Array(vec![]));
            }
        }
        writeln!(std::io::stdout(), "{value}")?;
    } else if args.render {
        render(&t, args.env_id)?;
    } else {
        print_table(&t, args.env_id)?;
    }
    Ok(ExitCode::SUCCESS)
}

fn print_table(t: &Trajectory, env_id: EnvId) -> anyhow::Result<()> {
    let mut out = std::io::stdout().lock();
    writeln!(out, "{env_id}, reset(seed={})", t.seed)?;
    writeln!(
        out,
        "{} {} {:>11} {:>11} {:>11} {:>11} {}  {}",
        pad_left(t_("step", "步"), 5),
        pad_left(t_("action", "动作"), 6),
        "x",
        "x_dot",
        "theta",
        "theta_dot",
        pad_left(t_("reward", "奖励"), 6),
        t_("end", "结束")
    )?;
    let o = t.reset_obs;
    writeln!(
        out,
        "{:>5} {:>6} {:>11.6} {:>11.6} {:>11.6} {:>11.6} {:>6}",
        0, "-", o[0], o[1], o[2], o[3], "-"
    )?;
    for (i, o) in t.obs.iter().enumerate() {
        let end = match (t.terminated[i], t.truncated[i]) {
            (true, true) => t_("terminated+truncated", "终止+时限中断"),
            (true, false) => t_("terminated", "终止"),
            (false, true) => t_("truncated", "时限中断"),
            (false, false) => "",
        };
        let action = if t.actions[i] == 1 {
            t_("right", "右")
        } else {
            t_("left", "左")
        };
        writeln!(
            out,
            "{:>5} {} {:>11.6} {:>11.6} {:>11.6} {:>11.6} {:>6.1}  {end}",
            i + 1,
            pad_left(action, 6),
            o[0],
            o[1],
            o[2],
            o[3],
            t.rewards[i]
        )?;
    }
    writeln!(out, "{}", return_line(t))?;
    for (i, s) in t.next_resets.iter().enumerate() {
        let n = i + 1;
        writeln!(out, "{}{s:?}", tr!("next reset {n}: ", "下一次重置 {n}："))?;
    }
    Ok(())
}

/// `return R over N steps`, in the current language.
fn return_line(t: &Trajectory) -> String {
    let (r, n) = (t.episode_return(), t.actions.len());
    tr!("return {r} over {n} steps", "共 {n} 步，回报 {r}")
}

/// Draws the cart and pole as text, one frame per state.
#[must_use]
pub fn ascii_frame(state: [f64; 4], width: usize) -> Vec<String> {
    let height = 9_usize;
    let width = width.max(20);
    let mut grid = vec![vec![' '; width]; height];
    let x_to_col = |x: f64| -> isize {
        let frac = (x + 2.4) / 4.8;
        (frac * (width as f64 - 1.0)).round() as isize
    };
    let cart_col = x_to_col(state[0]);
    let track_row = height - 1;
    grid[track_row].fill('─');
    let cart_row = height - 2;
    for dc in -2..=2 {
        let c = cart_col + dc;
        if (0..width as isize).contains(&c) {
            grid[cart_row][c as usize] = '█';
        }
    }
    // The pole: from the cart's top, length 6 rows, leaning by theta (x stretched 2x for aspect).
    let theta = state[2];
    for k in 1..=12 {
        let r = k as f64 * 0.5;
        let row = cart_row as f64 - r * theta.cos();
        let col = cart_col as f64 + 2.0 * r * theta.sin();
        let (row, col) = (row.round() as isize, col.round() as isize);
        if (0..height as isize).contains(&row) && (0..width as isize).contains(&col) {
            grid[row as usize][col as usize] = '●';
        }
    }
    grid.into_iter().map(|r| r.into_iter().collect()).collect()
}

fn render(t: &Trajectory, env_id: EnvId) -> anyhow::Result<()> {
    let mut out = std::io::stdout().lock();
    let frames = std::iter::once(t.reset_state).chain(t.states.iter().copied());
    for (i, state) in frames.enumerate() {
        let lines = ascii_frame(state, 64);
        if i > 0 {
            write!(out, "\x1b[{}A", lines.len() + 1)?;
        }
        writeln!(
            out,
            "{env_id} {} {} {} {i:>3}  x={:+.3} θ={:+.3}      ",
            t_("seed", "随机种子"),
            t.seed,
            t_("step", "步"),
            state[0],
            state[2]
        )?;
        for line in lines {
            writeln!(out, "{line}")?;
        }
        out.flush()?;
        std::thread::sleep(Duration::from_millis(20));
    }
    writeln!(out, "{}", return_line(t))?;
    Ok(())
}
