//! `ppo-tutor replay FILE`: re-run recorded PyTorch updates and print ours, to compare.

use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::Context;
use clap::Args;
use serde_json::json;

use crate::ppo::replay::{ReplayOutput, parse_replay, replay_case};

/// Arguments of `ppo-tutor replay`.
#[derive(Debug, Args)]
#[command(
    after_help = "FILE has the schema of ppo_update_pytorch.json (made by ppo_fixtures.py): \
{\"cases\": [{\"hyper\", \"weights_before\", \"batch\"}, ...]}.\n\nExample:\n  ppo-tutor replay tests/fixtures/ppo_update_pytorch.json --json > ours.json"
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
    let text = std::fs::read_to_string(&args.file).with_context(|| format!("reading {name}"))?;
    let cases = parse_replay(&text, &name)?;
    let outputs = cases
        .iter()
        .enumerate()
        .map(|(i, case)| replay_case(case).with_context(|| format!("replaying cases[{i}]")))
        .collect::<anyhow::Result<Vec<ReplayOutput>>>()?;
    let mut out = std::io::stdout().lock();
    if args.json {
        writeln!(out, "{}", json!({ "cases": outputs }))?;
        return Ok(ExitCode::SUCCESS);
    }
    for (i, (case, o)) in cases.iter().zip(&outputs).enumerate() {
        writeln!(
            out,
            "case {i}: {} transitions, {} epochs",
            case.batch.len(),
            o.epochs.len()
        )?;
        writeln!(
            out,
            "{:>7} {:>14} {:>14}",
            "epoch", "actor_loss", "critic_loss"
        )?;
        for (e, epoch) in o.epochs.iter().enumerate() {
            writeln!(
                out,
                "{e:>7} {:>14.7} {:>14.7}",
                epoch.actor_loss, epoch.critic_loss
            )?;
        }
    }
    writeln!(
        out,
        "(--json prints every tensor, in the fixture's key names and shapes)"
    )?;
    Ok(ExitCode::SUCCESS)
}
