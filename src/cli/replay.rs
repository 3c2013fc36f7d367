//! `ppo-tutor replay FILE`: re-run recorded PyTorch updates and print ours, to compare.
//!
//! FILE is either agent's fixture, told apart by its keys: the seed's discrete PPO
//! (`ppo_update_pytorch.json`) or the book's `PPOContinuous` on Pendulum
//! (`ppo_continuous_update_pytorch.json`, whose actor has `fc_mu` and `fc_std`).

use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::Context;
use clap::Args;
use serde_json::json;

use crate::i18n::t;
use crate::ppo::continuous::replay::{ContinuousReplayOutput, replay_continuous_case};
use crate::ppo::replay::{ReplayOutput, replay_case};
use crate::ppo::replay_file::{AnyReplay, parse_any_replay};
use crate::tr;

/// Arguments of `ppo-tutor replay`.
#[derive(Debug, Args)]
#[command(
    after_help = "FILE has the schema of ppo_update_pytorch.json (made by ppo_fixtures.py) or of \
ppo_continuous_update_pytorch.json (made by ppo_continuous_fixtures.py; its actor has fc_mu and fc_std): \
{\"cases\": [{\"hyper\", \"weights_before\", \"batch\"}, ...]}.\n\nExamples:\n  ppo-tutor replay tests/fixtures/ppo_update_pytorch.json --json > ours.json\n  ppo-tutor replay tests/fixtures/ppo_continuous_update_pytorch.json --json > ours_continuous.json"
)]
pub struct ReplayArgs {
    /// The recorded updates.
    pub file: PathBuf,
    /// Print `{"cases": [...]}` with the fixture's key names and shapes, instead of a table.
    #[arg(long)]
    pub json: bool,
}

/// Runs `ppo-tutor replay`.
///
/// # Errors
/// The file is unreadable or malformed (the message names the key and its expected shape).
pub fn run(args: &ReplayArgs) -> anyhow::Result<ExitCode> {
    let name = args.file.display().to_string();
    let text = std::fs::read_to_string(&args.file)
        .with_context(|| tr!("reading {name}", "读取 {name}"))?;
    let mut out = std::io::stdout().lock();
    // (transitions, [(actor_loss, critic_loss)] per epoch) of each case, for the table
    let summary: Vec<(usize, Vec<(f32, f32)>)> = match parse_any_replay(&text, &name)? {
        AnyReplay::Discrete(cases) => {
            let outputs = run_cases(&cases, replay_case)?;
            if args.json {
                writeln!(out, "{}", json!({ "cases": outputs }))?;
                return Ok(ExitCode::SUCCESS);
            }
            cases
                .iter()
                .zip(&outputs)
                .map(|(case, o): (_, &ReplayOutput)| {
                    let losses = o.epochs.iter().map(|e| (e.actor_loss, e.critic_loss));
                    (case.batch.len(), losses.collect())
                })
                .collect()
        }
        AnyReplay::Continuous(cases) => {
            let outputs = run_cases(&cases, replay_continuous_case)?;
            if args.json {
                writeln!(out, "{}", json!({ "cases": outputs }))?;
                return Ok(ExitCode::SUCCESS);
            }
            cases
                .iter()
                .zip(&outputs)
                .map(|(case, o): (_, &ContinuousReplayOutput)| {
                    let losses = o.epochs.iter().map(|e| (e.actor_loss, e.critic_loss));
                    (case.batch.len(), losses.collect())
                })
                .collect()
        }
    };
    for (i, (transitions, losses)) in summary.iter().enumerate() {
        let epochs = losses.len();
        writeln!(
            out,
            "{}",
            tr!(
                "case {i}: {transitions} transitions, {epochs} epochs",
                "用例 {i}：{transitions} 条转移，{epochs} 轮"
            )
        )?;
        writeln!(
            out,
            "{} {:>14} {:>14}",
            super::pad_left(t("epoch", "轮"), 7),
            "actor_loss",
            "critic_loss"
        )?;
        for (e, (actor_loss, critic_loss)) in losses.iter().enumerate() {
            writeln!(out, "{e:>7} {actor_loss:>14.7} {critic_loss:>14.7}")?;
        }
    }
    writeln!(
        out,
        "{}",
        t(
            "(--json prints every tensor, in the fixture's key names and shapes)",
            "（--json 会输出每个张量，键名和形状与录制文件相同）"
        )
    )?;
    Ok(ExitCode::SUCCESS)
}

/// Replays every case, naming the case in an error.
fn run_cases<C, O>(
    cases: &[C],
    replay: impl Fn(&C) -> Result<O, crate::ppo::PpoError>,
) -> anyhow::Result<Vec<O>> {
    cases
        .iter()
        .enumerate()
        .map(|(i, case)| {
            replay(case).with_context(|| tr!("replaying cases[{i}]", "重放 cases[{i}]"))
        })
        .collect()
}
