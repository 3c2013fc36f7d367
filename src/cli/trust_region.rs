//! `ppo-tutor trust-region`: trains the seed's agent for a few episodes, then measures how
//! far the surrogate's prediction of the latest batch holds: steps of growing length along
//! its gradient, each with the mean KL to `π_old`, the predicted and the true change in the
//! discounted return, and the change in score (see
//! [`crate::ppo::trust_region`]).

use std::io::Write;
use std::process::ExitCode;

use anyhow::Context;
use clap::Args;

use super::args::{parse_count, parse_seed};
use crate::i18n::t;
use crate::lesson::Session;
use crate::ppo::PpoConfig;
use crate::ppo::trust_region::{ProbeSettings, TrustRegionProbe, probe_snapshot};
use crate::tr;

/// Arguments of `ppo-tutor trust-region`.
#[derive(Debug, Args)]
#[command(
    after_help = "Examples:\n  ppo-tutor trust-region\n  ppo-tutor trust-region --seed 3 --train-episodes 60 --steps 0,0.1,0.4,1.6 --eval-episodes 200\n  ppo-tutor trust-region --json > probe.json"
)]
pub struct TrustRegionArgs {
    /// Seed of the training run and of the held-out episodes.
    #[arg(long, default_value = "0", value_parser = parse_seed, allow_hyphen_values = true)]
    pub seed: u64,
    /// Episodes to train the seed's PPO for before probing its latest batch.
    #[arg(long, default_value_t = 40, value_parser = parse_count, allow_hyphen_values = true)]
    pub train_episodes: usize,
    /// Held-out episodes per step (at least 2) [default: 150].
    #[arg(long, value_parser = parse_eval_episodes, allow_hyphen_values = true)]
    pub eval_episodes: Option<usize>,
    /// Step lengths α (L2 norm in parameter space), comma-separated, e.g. 0,0.1,0.4,1.6
    /// [default: 0,0.025,0.05,0.1,0.2,0.3,0.4,0.6,0.8,1.2,1.6,3.2].
    #[arg(long, value_name = "LIST", value_parser = parse_steps, allow_hyphen_values = true)]
    pub steps: Option<StepList>,
    /// Print the probe as JSON on stdout instead of the table.
    #[arg(long)]
    pub json: bool,
}

/// Step lengths given on the command line (one clap value, not many).
#[derive(Debug, Clone, PartialEq)]
pub struct StepList(pub Vec<f32>);

/// Parses `0,0.1,0.4`: finite numbers separated by commas.
///
/// # Errors
/// A message naming the entry that is not a finite number.
pub fn parse_steps(s: &str) -> Result<StepList, String> {
    s.split(',')
        .map(|part| match part.trim().parse::<f32>() {
            Ok(x) if x.is_finite() => Ok(x),
            _ => Err(tr!(
                "step '{}' is not a number: give step lengths like 0,0.1,0.4,1.6",
                "步长 '{}' 不是数：请写成 0,0.1,0.4,1.6 这样的步长",
                part.trim()
            )),
        })
        .collect::<Result<_, _>>()
        .map(StepList)
}

/// Parses a count of held-out episodes: a whole number of at least 2.
fn parse_eval_episodes(s: &str) -> Result<usize, String> {
    match s.trim().parse::<usize>() {
        Ok(n) if n >= 2 => Ok(n),
        _ => Err(tr!(
            "expected a whole number of at least 2 (a standard error needs two episodes), got '{s}'",
            "应为不小于 2 的整数（标准误至少要两个回合），实际是 '{s}'"
        )),
    }
}

/// Runs `ppo-tutor trust-region`.
///
/// # Errors
/// A run that diverged, or stdout closed.
pub fn run(args: &TrustRegionArgs) -> anyhow::Result<ExitCode> {
    let config = PpoConfig {
        num_episodes: args.train_episodes,
        ..PpoConfig::default()
    };
    let defaults = ProbeSettings::default();
    let settings = ProbeSettings {
        steps: args.steps.as_ref().map_or(defaults.steps, |s| s.0.clone()),
        episodes: args.eval_episodes.unwrap_or(defaults.episodes),
        seed: args.seed,
    };
    let snapshot = Session::run(config.clone(), args.seed, args.train_episodes)
        .context(t("training stopped", "训练中止"))?;
    let probe = probe_snapshot(&snapshot, &config, &settings)
        .context(t("probing the trust region", "探测信任区域"))?;
    let mut out = std::io::stdout().lock();
    if args.json {
        let text =
            serde_json::to_string_pretty(&probe).context(t("encoding the results", "编码结果"))?;
        writeln!(out, "{text}")?;
        return Ok(ExitCode::SUCCESS);
    }
    let batch = snapshot.batch().map_or(0, |b| b.states.len());
    let last = snapshot.returns.last().copied().unwrap_or(0.0);
    let (seed, trained) = (args.seed, snapshot.episodes);
    writeln!(
        out,
        "{}",
        tr!(
            "trust region: seed {seed}, {trained} training episodes (last return {last}); the latest batch has {batch} steps",
            "信任区域：随机种子 {seed}，训练了 {trained} 个回合（最后一个回合的回报 {last}）；最近一批有 {batch} 个时间步"
        )
    )?;
    for line in table(&probe) {
        writeln!(out, "{line}")?;
    }
    Ok(ExitCode::SUCCESS)
}

/// The probe as lines of text: a header, one row per step, a legend.
#[must_use]
/// The probe as a table: the notebooks' and this command's one layout.
pub fn table(probe: &TrustRegionProbe) -> Vec<String> {
    crate::notebook::trust_region_table(probe)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn steps_parse_and_bad_ones_are_named() {
        assert_eq!(parse_steps("0, 0.1,1.6"), Ok(StepList(vec![0.0, 0.1, 1.6])));
        assert_eq!(parse_steps("-0.5"), Ok(StepList(vec![-0.5])));
        for bad in ["0,x", "", "0,,1", "inf", "NaN"] {
            let e = parse_steps(bad).err().unwrap_or_default();
            assert!(e.contains("is not a number"), "{bad}: {e}");
        }
        assert!(parse_eval_episodes("1").is_err() && parse_eval_episodes("2") == Ok(2));
    }
}
