//! `ppo-tutor play --load FILE`: watch a saved agent in the terminal: the cart and pole of
//! a CartPole agent, or the swinging pendulum of a Pendulum-v1 agent. The checkpoint says
//! which it holds ([`CheckpointKind`]).

use std::io::{IsTerminal, Write};
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Duration;

use anyhow::Context;
use clap::Args;
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::widgets::{Block, Widget};

use super::args::parse_seed;
use super::cartpole::ascii_frame;
use super::train::parse_train_env;
use crate::env::{CartPole, EnvId, Pendulum};
use crate::i18n::t;
use crate::ppo::{Agent, CheckpointKind, PpoConfig, PpoContinuous, PpoContinuousConfig};
use crate::run::{AgentKind, Choice, RunConfig};
use crate::tr;
use crate::tui::widgets::pendulum::PendulumView;

/// Arguments of `ppo-tutor play`.
#[derive(Debug, Args)]
#[command(
    after_help = "Examples:\n  ppo-tutor train --save agent.safetensors && ppo-tutor play --load agent.safetensors\n  ppo-tutor train --env Pendulum-v1 --save pendulum.safetensors && ppo-tutor play --load pendulum.safetensors"
)]
pub struct PlayArgs {
    /// The agent, as written by `ppo-tutor train --save FILE.safetensors` (CartPole or
    /// Pendulum-v1: the file says which).
    #[arg(long, value_name = "FILE")]
    pub load: PathBuf,
    /// Episodes to play.
    #[arg(long, value_parser = super::args::parse_count, allow_hyphen_values = true, default_value_t = 1)]
    pub episodes: usize,
    /// Seed of the first reset and of the action sampling.
    #[arg(long, default_value = "0", value_parser = parse_seed, allow_hyphen_values = true)]
    pub seed: u64,
    /// Gymnasium environment id, in any case [default: the checkpoint's, CartPole-v1 or
    /// Pendulum-v1]; CartPole-v0 plays a CartPole agent with a 200-step limit.
    #[arg(long = "env", value_parser = parse_train_env)]
    pub env_id: Option<Choice>,
    /// Take the most probable action instead of sampling as in training (a Pendulum-v1
    /// agent always plays its mean torque μ).
    #[arg(long)]
    pub greedy: bool,
    /// Milliseconds per frame, 0 or more [default: 20 for CartPole (Gymnasium's 50 fps), 33
    /// for Pendulum-v1 (30 fps)].
    #[arg(long, value_parser = parse_delay, allow_hyphen_values = true)]
    pub delay_ms: Option<u64>,
    /// Print only each episode's return, without animation.
    #[arg(long)]
    pub no_render: bool,
}

/// Runs `ppo-tutor play`.
///
/// # Errors
/// The checkpoint is missing or malformed (the message names the tensor and its expected
/// shape), `--env` names another environment than the checkpoint's, or writing to the
/// terminal failed.
pub fn run(args: &PlayArgs) -> anyhow::Result<ExitCode> {
    let kinds = AgentKind::ALL.map(AgentKind::checkpoint);
    let kind = CheckpointKind::of_file(&args.load, &kinds);
    let file_agent = AgentKind::ALL
        .into_iter()
        .find(|a| Some(a.checkpoint()) == kind);
    let choice = match (args.env_id, file_agent) {
        // The file's own agent on its default environment; an unreadable file goes to the
        // first agent's loader, which says why.
        (None, agent) => RunConfig::default_for(agent.unwrap_or_default()).choice(),
        // An unreadable file goes to the loader of the environment asked, which says why.
        (Some(asked), None) => asked,
        (Some(asked), Some(agent)) if asked.agent == agent => asked,
        (Some(asked), Some(_)) => {
            let holds = kind.map_or(t("another agent", "别的智能体").to_string(), |k| {
                let (algorithm, env) = (k.algorithm, k.env);
                tr!(
                    "a {algorithm} agent for {env}",
                    "{env} 上的 {algorithm} 智能体"
                )
            });
            let file = args.load.display();
            eprintln!(
                "{}{}{}",
                super::error_prefix(),
                tr!(
                    "--env {asked} does not match {file}: it holds {holds}; drop --env to play \
                     it on its own environment",
                    "--env {asked} 与 {file} 不符：它保存的是 {holds}。去掉 --env 即可在它自己的环境中运行"
                ),
                super::see_help()
            );
            return Ok(ExitCode::from(super::EXIT_USAGE));
        }
    };
    match choice.agent {
        AgentKind::CartPole => play_cartpole(args, choice.id.parse()?),
        AgentKind::Pendulum => play_pendulum(args),
    }
}

fn play_cartpole(args: &PlayArgs, env_id: EnvId) -> anyhow::Result<ExitCode> {
    let config = PpoConfig {
        env_id,
        ..PpoConfig::default()
    };
    let mut agent = Agent::load(&args.load, &config, args.seed).context(loading())?;
    let render = !args.no_render && std::io::stdout().is_terminal();
    let delay = Duration::from_millis(args.delay_ms.unwrap_or(20));
    let mut env = CartPole::new(env_id);
    let mut out = std::io::stdout().lock();
    for episode in 0..args.episodes {
        let mut obs = env.reset((episode == 0).then_some(args.seed));
        let (mut total, mut steps, mut drawn) = (0.0, 0, 0);
        loop {
            if render {
                drawn = draw_cartpole(&mut out, &env, env_id, (episode, steps), drawn)?;
                std::thread::sleep(delay);
            }
            let action = if args.greedy {
                agent.greedy_action(&obs)
            } else {
                agent.take_action(&obs)?
            };
            let step = env.step(action)?;
            obs = step.obs;
            total += step.reward;
            steps += 1;
            if step.terminated || step.truncated {
                if render {
                    draw_cartpole(&mut out, &env, env_id, (episode, steps), drawn)?;
                }
                let line = if step.terminated {
                    tr!(
                        "episode {episode}: return {total} (the pole fell after {steps} steps)",
                        "回合 {episode}：回报 {total}（{steps} 步后杆倒下）"
                    )
                } else {
                    tr!(
                        "episode {episode}: return {total} (time limit after {steps} steps)",
                        "回合 {episode}：回报 {total}（{steps} 步后到达时限）"
                    )
                };
                writeln!(out, "{line}")?;
                break;
            }
        }
    }
    Ok(ExitCode::SUCCESS)
}

/// Draws one CartPole frame over the previous one; returns the number of lines drawn.
fn draw_cartpole(
    out: &mut impl Write,
    env: &CartPole,
    env_id: EnvId,
    (episode, step): (usize, usize),
    previous: usize,
) -> anyhow::Result<usize> {
    let Some(state) = env.state() else {
        return Ok(previous);
    };
    let lines = ascii_frame(state, 64);
    if previous > 0 {
        write!(out, "\x1b[{previous}A")?;
    }
    let (x, theta) = (state[0], state[2]);
    writeln!(
        out,
        "{}",
        tr!(
            "{env_id} episode {episode} step {step:>3}  x={x:+.3} θ={theta:+.3}      ",
            "{env_id} 回合 {episode} 第 {step:>3} 步  x={x:+.3} θ={theta:+.3}      "
        )
    )?;
    for line in &lines {
        writeln!(out, "{line}")?;
    }
    out.flush()?;
    Ok(lines.len() + 1)
}

/// Plays a Pendulum-v1 agent's mean torque μ(s), as the book watches a trained policy.
fn play_pendulum(args: &PlayArgs) -> anyhow::Result<ExitCode> {
    let agent = PpoContinuous::load(&args.load, &PpoContinuousConfig::default(), args.seed)
        .context(loading())?;
    let render = !args.no_render && std::io::stdout().is_terminal();
    let delay = Duration::from_millis(args.delay_ms.unwrap_or(33));
    let mut env = Pendulum::new();
    let mut out = std::io::stdout().lock();
    for episode in 0..args.episodes {
        let mut obs = env.reset((episode == 0).then_some(args.seed));
        let (mut total, mut steps, mut drawn, mut torque) = (0.0, 0, 0, 0.0);
        loop {
            if render {
                let frame = PendulumFrame {
                    episode,
                    step: steps,
                    torque,
                };
                drawn = draw_pendulum(&mut out, &env, &frame, drawn)?;
                std::thread::sleep(delay);
            }
            torque = f64::from(agent.deterministic_action(&obs));
            let step = env.step(torque)?;
            obs = step.obs;
            total += step.reward;
            steps += 1;
            if step.terminated || step.truncated {
                if render {
                    let frame = PendulumFrame {
                        episode,
                        step: steps,
                        torque,
                    };
                    draw_pendulum(&mut out, &env, &frame, drawn)?;
                }
                writeln!(
                    out,
                    "{}",
                    tr!(
                        "episode {episode}: return {total:.2} (time limit after {steps} steps)",
                        "回合 {episode}：回报 {total:.2}（{steps} 步后到达时限）"
                    )
                )?;
                break;
            }
        }
    }
    Ok(ExitCode::SUCCESS)
}

/// What the status line of a pendulum frame shows.
struct PendulumFrame {
    episode: usize,
    step: usize,
    /// The torque the agent asked for at the previous step (the env clips it to ±2).
    torque: f64,
}

/// Canvas size of a pendulum frame, in terminal cells (twice as wide as high: square dots).
const PENDULUM_CELLS: (u16, u16) = (44, 20);

/// Draws one Pendulum frame over the previous one; returns the number of lines drawn.
fn draw_pendulum(
    out: &mut impl Write,
    env: &Pendulum,
    frame: &PendulumFrame,
    previous: usize,
) -> anyhow::Result<usize> {
    let Some([theta, theta_dot]) = env.state() else {
        return Ok(previous);
    };
    let lines = pendulum_lines(theta, frame.torque);
    if previous > 0 {
        write!(out, "\x1b[{previous}A")?;
    }
    writeln!(
        out,
        "{}",
        tr!(
            "Pendulum-v1 episode {} step {:>3}  θ={:+.3} θ̇={:+.3} u={:+.3}      ",
            "Pendulum-v1 回合 {} 第 {:>3} 步  θ={:+.3} θ̇={:+.3} u={:+.3}      ",
            frame.episode,
            frame.step,
            crate::env::pendulum::angle_normalize(theta),
            theta_dot,
            frame.torque.clamp(-2.0, 2.0),
        )
    )?;
    for line in &lines {
        writeln!(out, "{line}")?;
    }
    out.flush()?;
    Ok(lines.len() + 1)
}

/// `loading the agent`, the context of a checkpoint that cannot be loaded (the loader's
/// error names the file: `loading the agent: FILE: not a readable ...`).
fn loading() -> &'static str {
    t("loading the agent", "加载智能体")
}

/// Parses `--delay-ms`: a whole number of milliseconds, 0 or more (`-5` is refused by
/// name, not taken for a flag).
fn parse_delay(s: &str) -> Result<u64, String> {
    s.trim().parse::<u64>().map_err(|_| {
        tr!(
            "expected a whole number of milliseconds, 0 or more, got '{s}'",
            "应为毫秒数，即不小于 0 的整数，实际是 '{s}'"
        )
    })
}

/// The pendulum drawn by [`PendulumView`] as lines of text.
fn pendulum_lines(theta: f64, torque: f64) -> Vec<String> {
    let area = Rect::new(0, 0, PENDULUM_CELLS.0, PENDULUM_CELLS.1);
    let mut buf = Buffer::empty(area);
    PendulumView {
        theta,
        torque,
        block: Block::bordered().title(t(" torque: arc around the pivot ", " 力矩：绕转轴的弧 ")),
        color: false,
    }
    .render(area, &mut buf);
    (0..area.height)
        .map(|y| {
            (0..area.width)
                .map(|x| buf[(x, y)].symbol())
                .collect::<String>()
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_pendulum_frame_is_a_box_of_text() {
        let lines = pendulum_lines(0.3, 1.0);
        assert_eq!(lines.len(), usize::from(PENDULUM_CELLS.1));
        assert!(
            lines
                .iter()
                .all(|l| l.chars().count() == usize::from(PENDULUM_CELLS.0))
        );
        assert!(lines[0].contains("torque"));
    }

    #[test]
    fn a_delay_is_a_whole_number_of_milliseconds() {
        assert_eq!(parse_delay("0"), Ok(0));
        assert_eq!(parse_delay(" 40 "), Ok(40));
        for bad in ["-5", "1.5", "abc", ""] {
            let e = parse_delay(bad).err().unwrap_or_default();
            assert!(
                e.contains("milliseconds, 0 or more") && e.contains(&format!("'{bad}'")),
                "{bad}: {e}"
            );
        }
    }
}
