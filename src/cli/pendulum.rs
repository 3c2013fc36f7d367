//! `ppo-tutor pendulum`: run the native Pendulum-v1 and print what Gymnasium would.

use std::io::Write;
use std::process::ExitCode;

use anyhow::Context;
use clap::Args;

use super::args::parse_seed;
use super::pad_left;
use crate::env::PendulumTrajectory;
use crate::env::pendulum::{ENV_ID, MAX_TORQUE, PendulumConfig};
use crate::i18n::t as t_;
use crate::tr;

/// Arguments of `ppo-tutor pendulum`.
#[derive(Debug, Args)]
#[command(
    after_help = "Examples:\n  ppo-tutor pendulum --seed 0 --actions=-0.5,1.25,2 --json\n  ppo-tutor pendulum --seed 3 --actions -2,-2,2,2 --resets 3"
)]
pub struct PendulumArgs {
    /// Seed for reset(seed=...), any integer from 0 to 2^64-1.
    #[arg(long, default_value = "0", value_parser = parse_seed, allow_hyphen_values = true)]
    pub seed: u64,
    /// Torques to apply in order, comma-separated decimals in N·m (clipped to [-2, 2]),
    /// like -0.5,1.25; '' only resets.
    #[arg(long, value_name = "TORQUES", value_parser = parse_torques, allow_hyphen_values = true)]
    pub actions: Option<TorqueList>,
    /// Also record the states of N further unseeded resets (as `next_resets`).
    #[arg(long, default_value_t = 0, value_parser = super::args::parse_whole, allow_hyphen_values = true)]
    pub resets: usize,
    /// Print one JSON object in the schema of Gymnasium's fixture traces.
    #[arg(long)]
    pub json: bool,
}

/// Torques given on the command line as one list (one clap value, not many).
#[derive(Debug, Clone, PartialEq)]
pub struct TorqueList(pub Vec<f64>);

/// Parses a comma-separated list of torques such as `-0.5,1.25,2`; the empty string is
/// no torques. Out-of-range torques are accepted (the environment clips them, as
/// Gymnasium does); NaN and infinities are not.
///
/// # Errors
/// A message naming the first entry that is not a finite number, its position, and the
/// expected form.
pub fn parse_torques(s: &str) -> Result<TorqueList, String> {
    if s.trim().is_empty() {
        return Ok(TorqueList(Vec::new()));
    }
    let fix = tr!(
        "give decimal torques in N·m, comma-separated like -0.5,1.25 (clipped to [-{MAX_TORQUE}, {MAX_TORQUE}])",
        "请给出以 N·m 为单位的小数力矩，用逗号分隔，如 -0.5,1.25（超出 [-{MAX_TORQUE}, {MAX_TORQUE}] 的会被限幅）"
    );
    s.split(',')
        .enumerate()
        .map(|(i, part)| {
            let part = part.trim();
            match part.parse::<f64>() {
                Ok(u) if u.is_finite() => Ok(u),
                Ok(_) => Err(tr!(
                    "torque {} is '{part}', which is not a finite number: {fix}",
                    "第 {} 个力矩是 '{part}'，不是有限数：{fix}",
                    i + 1
                )),
                Err(_) => Err(tr!(
                    "torque {} is '{part}', not a number: {fix}",
                    "第 {} 个力矩是 '{part}'，不是数：{fix}",
                    i + 1
                )),
            }
        })
        .collect::<Result<_, _>>()
        .map(TorqueList)
}

/// Runs `ppo-tutor pendulum`.
///
/// # Errors
/// Writing to standard output failed, or JSON encoding failed.
pub fn run(args: &PendulumArgs) -> anyhow::Result<ExitCode> {
    let Some(TorqueList(torques)) = &args.actions else {
        eprintln!(
            "{}{}",
            super::error_prefix(),
            t_(
                "give --actions with the torques to apply, like --actions=-0.5,1.25 ('' only resets; see --help)",
                "请用 --actions 给出要施加的力矩，如 --actions=-0.5,1.25（'' 表示只 reset；见 --help）"
            )
        );
        return Ok(ExitCode::from(super::EXIT_USAGE));
    };
    let t = PendulumTrajectory::record(PendulumConfig::default(), args.seed, torques, args.resets)
        .context(t_("recording the episode", "记录回合"))?;
    if t.actions.len() < torques.len() {
        let (done, all) = (t.actions.len(), torques.len());
        eprintln!(
            "{}",
            tr!(
                "note: the episode was truncated after {done} of the {all} torques; the rest were not applied",
                "注意：回合在 {all} 个力矩中的第 {done} 个之后因时限中断，其余力矩没有施加"
            )
        );
    }
    if args.json {
        let mut value =
            serde_json::to_value(&t).context(t_("encoding the trajectory", "编码轨迹"))?;
        if let Some(map) = value.as_object_mut() {
            map.insert("env".into(), ENV_ID.into());
            if args.resets > 0 && !map.contains_key("next_resets") {
                map.insert("next_resets".into(), serde_json::Value::Array(vec![]));
            }
        }
        writeln!(std::io::stdout(), "{value}")?;
    } else {
        print_table(&t)?;
    }
    Ok(ExitCode::SUCCESS)
}

fn print_table(t: &PendulumTrajectory) -> anyhow::Result<()> {
    let mut out = std::io::stdout().lock();
    writeln!(out, "{ENV_ID}, reset(seed={})", t.seed)?;
    writeln!(
        out,
        "{} {} {:>11} {:>10} {:>10} {:>10} {}  {}",
        pad_left(t_("step", "步"), 5),
        pad_left(t_("torque", "力矩"), 8),
        "theta",
        "cos_theta",
        "sin_theta",
        "theta_dot",
        pad_left(t_("reward", "奖励"), 10),
        t_("end", "结束")
    )?;
    let (s, o) = (t.reset_state, t.reset_obs);
    writeln!(
        out,
        "{:>5} {:>8} {:>11.6} {:>10.6} {:>10.6} {:>10.6} {:>10}",
        0, "-", s[0], o[0], o[1], o[2], "-"
    )?;
    for (i, (s, o)) in t.states.iter().zip(&t.obs).enumerate() {
        let end = if t.truncated[i] {
            t_("  truncated", "  时限中断")
        } else {
            ""
        };
        writeln!(
            out,
            "{:>5} {:>8.4} {:>11.6} {:>10.6} {:>10.6} {:>10.6} {:>10.5}{end}",
            i + 1,
            t.actions[i],
            s[0],
            o[0],
            o[1],
            o[2],
            t.rewards[i]
        )?;
    }
    let (r, n) = (t.episode_return(), t.actions.len());
    writeln!(
        out,
        "{}",
        tr!("return {r} over {n} steps", "共 {n} 步，回报 {r}")
    )?;
    for (i, s) in t.next_resets.iter().enumerate() {
        let n = i + 1;
        writeln!(out, "{}{s:?}", tr!("next reset {n}: ", "下一次重置 {n}："))?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn torques_parse_and_reject() {
        assert_eq!(
            parse_torques("-0.5, 1.25,3,-1e-3"),
            Ok(TorqueList(vec![-0.5, 1.25, 3.0, -0.001]))
        );
        assert_eq!(parse_torques(""), Ok(TorqueList(vec![])));
        for (bad, says) in [
            ("0.5,x", "torque 2 is 'x', not a number"),
            ("0.5,,1", "torque 2 is '', not a number"),
            ("nan", "torque 1 is 'nan', which is not a finite number"),
            ("1,-inf", "torque 2 is '-inf', which is not a finite number"),
            ("1,2,infinity", "torque 3 is 'infinity'"),
        ] {
            let err = parse_torques(bad).err().unwrap_or_default();
            assert!(err.contains(says), "{bad:?}: {err}");
            assert!(err.contains("like -0.5,1.25"), "{bad:?}: {err}");
        }
    }
}
