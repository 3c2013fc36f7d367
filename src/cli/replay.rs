//! `ppo-tutor replay FILE`: re-run recorded PyTorch updates and print ours, to compare.
//!
//! FILE is either agent's fixture, told apart by its keys: the seed's discrete PPO
//! (`ppo_update_pytorch.json`, or PPO-Penalty's `ppo_penalty_update_pytorch.json`, whose
//! cases say `"objective": "penalty"`) or the book's `PPOContinuous` on Pendulum
//! (`ppo_continuous_update_pytorch.json`, whose actor has `fc_mu` and `fc_std`).

use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::Context;
use clap::Args;

use crate::i18n::t;
use crate::run::replay_any;
use crate::tr;

/// Arguments of `ppo-tutor replay`.
#[derive(Debug, Args)]
#[command(
    after_help = "FILE has the schema of ppo_update_pytorch.json (made by ppo_fixtures.py), of \
ppo_penalty_update_pytorch.json (ppo_fixtures.py --objective penalty: each case has \"objective\": \"penalty\", \
hyper adds beta and kl_target, and the update starts from expected.beta_before) or of \
ppo_continuous_update_pytorch.json (made by ppo_continuous_fixtures.py; its actor has fc_mu and fc_std): \
{\"cases\": [{\"hyper\", \"weights_before\", \"batch\"}, ...]}.\n\nExamples:\n  ppo-tutor replay tests/fixtures/ppo_update_pytorch.json --json > ours.json\n  ppo-tutor replay tests/fixtures/ppo_penalty_update_pytorch.json --json > ours_penalty.json\n  ppo-tutor replay tests/fixtures/ppo_continuous_update_pytorch.json --json > ours_continuous.json"
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
    let cases = replay_any(&text, &name)?
        .into_iter()
        .enumerate()
        .map(|(i, case)| case.with_context(|| tr!("replaying cases[{i}]", "回放 cases[{i}]")))
        .collect::<anyhow::Result<Vec<_>>>()?;
    if args.json {
        // The outputs' own JSON, in the fixture's key order: `{"cases":[...]}`.
        let outputs: Vec<&str> = cases.iter().map(|c| c.output.as_str()).collect();
        writeln!(out, "{{\"cases\":[{}]}}", outputs.join(","))?;
        return Ok(ExitCode::SUCCESS);
    }
    let summary: Vec<(usize, &[(f32, f32)])> = cases
        .iter()
        .map(|c| (c.transitions, c.losses.as_slice()))
        .collect();
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
