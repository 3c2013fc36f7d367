//! `ppo-tutor cartpole --envs N`: N CartPoles stepped together as Gymnasium's
//! `SyncVectorEnv`, with the autoreset mode named, actions read from a file.

use std::io::Write;
use std::path::Path;
use std::process::ExitCode;

use anyhow::Context;
use serde::Serialize;

use crate::env::{Autoreset, CartPole, CartPoleConfig, SyncVectorEnv, VectorEnv};
use crate::i18n::t as t_;
use crate::tr;

/// One final observation, as the fixtures key it.
#[derive(Debug, Serialize)]
struct FinalObs {
    step: usize,
    env: usize,
    obs: [f32; 4],
}

/// What `--json` prints: the keys and shapes of Gymnasium's vector traces.
#[derive(Debug, Serialize)]
struct VectorTrace {
    env: &'static str,
    seed: u64,
    num_envs: usize,
    autoreset: Autoreset,
    reset_obs: Vec<[f32; 4]>,
    actions: Vec<Vec<usize>>,
    obs: Vec<Vec<[f32; 4]>>,
    rewards: Vec<Vec<f64>>,
    terminated: Vec<Vec<bool>>,
    truncated: Vec<Vec<bool>>,
    final_obs: Vec<FinalObs>,
}

/// Reads `path`, a JSON array of steps each holding `n` actions 0 or 1; a message naming
/// the file, the step and the env for anything else.
fn read_actions(path: &Path, n: usize) -> Result<Vec<Vec<usize>>, String> {
    let file = path.display();
    let text = std::fs::read_to_string(path).map_err(|e| {
        tr!(
            "cannot read --actions-file {file}: {e}",
            "无法读取 --actions-file {file}：{e}"
        )
    })?;
    let value: serde_json::Value = serde_json::from_str(&text).map_err(|e| {
        tr!(
            "{file} is not JSON ({e}): write an array of steps, each an array of {n} actions, like [[0, 1], [1, 1]]",
            "{file} 不是 JSON（{e}）：请写成由步组成的数组，每步是 {n} 个动作的数组，例如 [[0, 1], [1, 1]]"
        )
    })?;
    let Some(steps) = value.as_array() else {
        return Err(tr!(
            "{file} holds no array of steps: write one, each step an array of {n} actions, like [[0, 1], [1, 1]]",
            "{file} 里没有由步组成的数组：请写成每步 {n} 个动作的数组，例如 [[0, 1], [1, 1]]"
        ));
    };
    let mut out = Vec::with_capacity(steps.len());
    for (step, actions) in steps.iter().enumerate() {
        let got = actions.as_array().map_or(0, Vec::len);
        let Some(actions) = actions.as_array().filter(|a| a.len() == n) else {
            return Err(tr!(
                "{file}, step {step}: {got} actions, but --envs {n} needs {n} (one per env)",
                "{file}，第 {step} 步：有 {got} 个动作，但 --envs {n} 需要 {n} 个（每个环境一个）"
            ));
        };
        let mut row = Vec::with_capacity(n);
        for (env, a) in actions.iter().enumerate() {
            match a.as_u64() {
                Some(a @ (0 | 1)) => row.push(a as usize),
                _ => {
                    return Err(tr!(
                        "{file}, step {step}, env {env}: action {a} is not 0 (push left) or 1 (push right)",
                        "{file}，第 {step} 步，环境 {env}：动作 {a} 不是 0（向左推）或 1（向右推）"
                    ));
                }
            }
        }
        out.push(row);
    }
    Ok(out)
}

/// Runs `ppo-tutor cartpole --envs n`.
///
/// # Errors
/// Writing to standard output failed, or JSON encoding failed.
pub fn run(
    config: CartPoleConfig,
    n: usize,
    seed: u64,
    autoreset: Autoreset,
    actions_file: &Path,
    json: bool,
) -> anyhow::Result<ExitCode> {
    let actions = match read_actions(actions_file, n) {
        Ok(actions) => actions,
        Err(message) => {
            eprintln!("{}{message}", super::super::error_prefix());
            return Ok(ExitCode::from(super::super::EXIT_USAGE));
        }
    };
    let envs = (0..n).map(|_| CartPole::with_config(config)).collect();
    let mut vec = SyncVectorEnv::new(envs, autoreset)
        .context(t_("making the vector environment", "创建向量环境"))?;
    let mut trace = VectorTrace {
        env: config.env_id.as_str(),
        seed,
        num_envs: n,
        autoreset,
        reset_obs: vec.reset(Some(seed)).to_vec(),
        actions: Vec::with_capacity(actions.len()),
        obs: Vec::with_capacity(actions.len()),
        rewards: Vec::with_capacity(actions.len()),
        terminated: Vec::with_capacity(actions.len()),
        truncated: Vec::with_capacity(actions.len()),
        final_obs: Vec::new(),
    };
    for (step, row) in actions.into_iter().enumerate() {
        let out = vec
            .step(&row)
            .with_context(|| tr!("step {step}", "第 {step} 步"))?;
        for (env, last) in out.final_obs.iter().enumerate() {
            if let Some(obs) = *last {
                trace.final_obs.push(FinalObs { step, env, obs });
            }
        }
        trace.obs.push(out.obs.clone());
        trace.rewards.push(out.rewards.clone());
        trace.terminated.push(out.terminated.clone());
        trace.truncated.push(out.truncated.clone());
        trace.actions.push(row);
    }
    let mut stdout = std::io::stdout().lock();
    if json {
        let text = serde_json::to_string(&trace).context(t_("encoding the trace", "编码轨迹"))?;
        writeln!(stdout, "{text}")?;
    } else {
        print_summary(&mut stdout, &trace)?;
    }
    Ok(ExitCode::SUCCESS)
}

/// The run in words: where each episode ended, then the totals.
fn print_summary(out: &mut impl Write, t: &VectorTrace) -> anyhow::Result<()> {
    let (env, n, seed, mode) = (t.env, t.num_envs, t.seed, t.autoreset);
    writeln!(
        out,
        "{}",
        tr!(
            "{n} × {env}, reset(seed={seed}) seeds env i with {seed} + i, {mode} autoreset",
            "{n} 个 {env}，reset(seed={seed}) 给环境 i 的种子是 {seed} + i，自动重置：{mode}"
        )
    )?;
    let mut ended = 0;
    for (step, (term, trunc)) in t.terminated.iter().zip(&t.truncated).enumerate() {
        for (env, (&a, &b)) in term.iter().zip(trunc).enumerate() {
            let how = match (a, b) {
                (true, true) => t_("terminated+truncated", "终止+时限中断"),
                (true, false) => t_("terminated", "终止"),
                (false, true) => t_("truncated", "时限中断"),
                (false, false) => continue,
            };
            ended += 1;
            writeln!(
                out,
                "{}",
                tr!(
                    "step {step}: env {env} {how}",
                    "第 {step} 步：环境 {env} {how}"
                )
            )?;
        }
    }
    let steps = t.actions.len();
    let reward: f64 = t.rewards.iter().flatten().sum();
    writeln!(
        out,
        "{}",
        tr!(
            "{steps} steps, {ended} episodes ended, total reward {reward}",
            "共 {steps} 步，{ended} 个回合结束，奖励合计 {reward}"
        )
    )?;
    Ok(())
}
