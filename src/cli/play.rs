//! `ppo-tutor play --load FILE`: watch a saved agent balance the pole in the terminal.

use std::io::{IsTerminal, Write};
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Duration;

use anyhow::Context;
use clap::Args;

use super::args::{parse_env, parse_seed};
use super::cartpole::ascii_frame;
use crate::env::{CartPole, EnvId};
use crate::ppo::{Agent, PpoConfig};

/// Arguments of `ppo-tutor play`.
#[derive(Debug, Args)]
#[command(
    after_help = "Example:\n  ppo-tutor train --save agent.safetensors && ppo-tutor play --load agent.safetensors"
)]
pub struct PlayArgs {
    /// The agent, as written by `ppo-tutor train --save FILE.safetensors`.
    #[arg(long, value_name = "FILE")]
    pub load: PathBuf,
    /// Episodes to play.
    #[arg(long, default_value_t = 1)]
    pub episodes: usize,
    /// Seed of the first reset and of the action sampling.
    #[arg(long, default_value = "0", value_parser = parse_seed, allow_hyphen_values = true)]
    pub seed: u64,
    /// Gymnasium environment id.
    #[arg(long = "env", default_value = "CartPole-v1", value_parser = parse_env)]
    pub env_id: EnvId,
    /// Take the most probable action instead of sampling as in training.
    #[arg(long)]
    pub greedy: bool,
    /// Milliseconds per frame (Gymnasium renders CartPole at 50 fps: 20 ms).
    #[arg(long, default_value_t = 20)]
    pub delay_ms: u64,
    /// Print only each episode's return, without animation.
    #[arg(long)]
    pub no_render: bool,
}

/// Runs `ppo-tutor play`.
///
/// # Errors
/// The checkpoint is missing or malformed (the message names the tensor and its expected
/// shape), or writing to the terminal failed.
pub fn run(args: &PlayArgs) -> anyhow::Result<ExitCode> {
    let config = PpoConfig {
        env_id: args.env_id,
        ..PpoConfig::default()
    };
    let mut agent = Agent::load(&args.load, &config, args.seed)
        .with_context(|| format!("loading the agent from {}", args.load.display()))?;
    let render = !args.no_render && std::io::stdout().is_terminal();
    let mut env = CartPole::new(args.env_id);
    let mut out = std::io::stdout().lock();
    for episode in 0..args.episodes {
        let mut obs = env.reset((episode == 0).then_some(args.seed));
        let (mut total, mut steps, mut drawn) = (0.0, 0, 0);
        loop {
            if render {
                drawn = draw(&mut out, &env, args, episode, steps, drawn)?;
                std::thread::sleep(Duration::from_millis(args.delay_ms));
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
                    draw(&mut out, &env, args, episode, steps, drawn)?;
                }
                let how = if step.terminated {
                    "the pole fell"
                } else {
                    "time limit"
                };
                writeln!(
                    out,
                    "episode {episode}: return {total} ({how} after {steps} steps)"
                )?;
                break;
            }
        }
    }
    Ok(ExitCode::SUCCESS)
}

/// Draws one frame over the previous one; returns the number of lines drawn.
fn draw(
    out: &mut impl Write,
    env: &CartPole,
    args: &PlayArgs,
    episode: usize,
    step: usize,
    previous: usize,
) -> anyhow::Result<usize> {
    let Some(state) = env.state() else {
        return Ok(previous);
    };
    let lines = ascii_frame(state, 64);
    if previous > 0 {
        write!(out, "\x1b[{previous}A")?;
    }
    writeln!(
        out,
        "{} episode {episode} step {step:>3}  x={:+.3} θ={:+.3}      ",
        args.env_id, state[0], state[2]
    )?;
    for line in &lines {
        writeln!(out, "{line}")?;
    }
    out.flush()?;
    Ok(lines.len() + 1)
}
