//! `ppo-tutor train --env Pendulum-v1` and `ppo-tutor play` of its agent, as a user runs
//! them: the JSON, the checkpoint (PyTorch's names), the figure, several seeds, the flags
//! that only CartPole has, and the animation in a real terminal.

use std::collections::BTreeSet;
use std::path::Path;
use std::process::Output;

use serde_json::Value;

type TestResult = Result<(), Box<dyn std::error::Error>>;

/// Pendulum-v1's worst reward per step, `−(π² + 0.1·8² + 0.001·2²)`, times 200 steps.
const WORST_RETURN: f64 = -16.2736044 * 200.0;

/// The book's `state_dict()` names, prefixed `actor.` / `critic.`.
const PYTORCH_NAMES: [&str; 10] = [
    "actor.fc1.bias",
    "actor.fc1.weight",
    "actor.fc_mu.bias",
    "actor.fc_mu.weight",
    "actor.fc_std.bias",
    "actor.fc_std.weight",
    "critic.fc1.bias",
    "critic.fc1.weight",
    "critic.fc2.bias",
    "critic.fc2.weight",
];

use crate::common;
use common::{english, numbers};

fn ppo_tutor(args: &[&str]) -> Result<Output, std::io::Error> {
    english().args(args).output()
}

fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

fn path(p: &Path) -> Result<&str, &'static str> {
    p.to_str().ok_or("non-UTF-8 temp path")
}

fn read_json(p: &Path) -> Result<Value, Box<dyn std::error::Error>> {
    Ok(serde_json::from_str(&std::fs::read_to_string(p)?)?)
}

fn keys(v: &Value) -> BTreeSet<String> {
    v.as_object()
        .map(|o| o.keys().cloned().collect())
        .unwrap_or_default()
}

/// A short run with the book's defaults: the summary, the JSON (CartPole's keys plus
/// `mean_last_100`), the figure, and a checkpoint with PyTorch's names that `play` loads
/// and plays with μ, the same way every time.
#[test]
fn train_writes_json_checkpoint_and_figure_and_play_loads_it() -> TestResult {
    let dir = tempfile::tempdir()?;
    let json = dir.path().join("run.json");
    let agent = dir.path().join("pendulum.safetensors");
    let plot = dir.path().join("returns.svg");
    let out = ppo_tutor(&[
        "train",
        "--env",
        "pendulum-V1", // any case
        "--episodes",
        "3",
        "--seed",
        "2",
        "--json",
        path(&json)?,
        "--save",
        path(&agent)?,
        "--plot",
        path(&plot)?,
    ])?;
    assert!(out.status.success(), "{}", stderr(&out));
    let stdout = String::from_utf8(out.stdout)?;
    assert!(
        stdout.contains("PPO on Pendulum-v1, seed 2: 3 episodes, 600 env steps"),
        "{stdout}"
    );
    assert!(
        stdout.contains("mean return of the last 3 episodes: -"),
        "{stdout}"
    );
    assert!(stdout.contains("Episodes"), "the terminal plot: {stdout}");

    let run = read_json(&json)?;
    assert_eq!(run["env"], "Pendulum-v1");
    assert_eq!(run["seed"], 2);
    assert_eq!(run["episodes"], 3);
    assert_eq!(run["env_steps"], 600, "200 steps per episode");
    let returns = numbers(&run["returns"]);
    assert_eq!(returns.len(), 3);
    assert!(
        returns.iter().all(|r| (WORST_RETURN..0.0).contains(r)),
        "{returns:?}"
    );
    assert_eq!(numbers(&run["moving_average"]).len(), 3);
    let mean = returns.iter().sum::<f64>() / 3.0;
    for key in ["mean_last_50", "mean_last_100"] {
        let got = run[key].as_f64().ok_or(key)?;
        assert!((got - mean).abs() < 1e-9, "{key}: {got} vs {mean}");
    }
    let book = [
        ("actor_lr", 1e-4),
        ("critic_lr", 5e-3),
        ("gamma", 0.9),
        ("lmbda", 0.9),
        ("eps", 0.2),
    ];
    for (key, value) in book {
        assert_eq!(run["config"][key], value, "{key}");
    }
    assert_eq!(run["config"]["hidden_dim"], 128);
    assert_eq!(run["config"]["epochs"], 10);

    // The same keys as a CartPole run's, plus the book's mean_last_100.
    let cartpole_json = dir.path().join("cartpole.json");
    let out = ppo_tutor(&[
        "train",
        "-q",
        "--episodes",
        "2",
        "--json",
        path(&cartpole_json)?,
    ])?;
    assert!(out.status.success(), "{}", stderr(&out));
    let extra: Vec<String> = keys(&run)
        .difference(&keys(&read_json(&cartpole_json)?))
        .cloned()
        .collect();
    assert_eq!(extra, ["mean_last_100"]);
    assert!(keys(&read_json(&cartpole_json)?).is_subset(&keys(&run)));

    let svg = std::fs::read_to_string(&plot)?;
    assert!(svg.contains("PPO on Pendulum-v1"), "the figure's title");

    // The checkpoint: PyTorch's names, marked as a Pendulum-v1 PPOContinuous agent.
    let bytes = std::fs::read(&agent)?;
    let (_, header) = safetensors::SafeTensors::read_metadata(&bytes)?;
    let names: BTreeSet<String> = header.offset_keys().into_iter().collect();
    assert_eq!(names, PYTORCH_NAMES.iter().map(|n| n.to_string()).collect());
    let metadata = header.metadata().clone().unwrap_or_default();
    assert_eq!(metadata.get("env").map(String::as_str), Some("Pendulum-v1"));
    assert_eq!(
        metadata.get("algorithm").map(String::as_str),
        Some("ppo-continuous")
    );

    // play recognises it, plays μ (the same returns twice), in Pendulum's range.
    let play = [
        "play",
        "--load",
        path(&agent)?,
        "--episodes",
        "2",
        "--no-render",
    ];
    let out = ppo_tutor(&play)?;
    assert!(out.status.success(), "{}", stderr(&out));
    let text = String::from_utf8(out.stdout)?;
    let played: Vec<f64> = text
        .lines()
        .filter_map(|l| l.split("return ").nth(1)?.split(' ').next()?.parse().ok())
        .collect();
    assert_eq!(played.len(), 2, "{text}");
    assert!(played.iter().all(|r| (WORST_RETURN..0.0).contains(r)));
    assert!(text.contains("(time limit after 200 steps)"), "{text}");
    let again = ppo_tutor(&play)?;
    assert_eq!(String::from_utf8(again.stdout)?, text, "μ is deterministic");

    // The file is refused as a CartPole agent, and --env must match it.
    let out = ppo_tutor(&["play", "--load", path(&agent)?, "--env", "CartPole-v1"])?;
    assert_eq!(out.status.code(), Some(2));
    assert!(
        stderr(&out).contains("it holds a ppo-continuous agent for Pendulum-v1"),
        "{}",
        stderr(&out)
    );
    Ok(())
}

/// Every hyper-parameter flag reaches the configuration; the hidden width travels with the
/// checkpoint to `play`.
#[test]
fn hyper_parameter_flags_apply_to_pendulum() -> TestResult {
    let dir = tempfile::tempdir()?;
    let json = dir.path().join("run.json");
    let agent = dir.path().join("small.safetensors");
    let out = ppo_tutor(&[
        "train",
        "-q",
        "--env",
        "Pendulum-v1",
        "--episodes",
        "2",
        "--actor-lr",
        "3e-4",
        "--critic-lr",
        "1e-3",
        "--gamma",
        "0.95",
        "--lmbda",
        "0.8",
        "--eps",
        "0.1",
        "--epochs",
        "3",
        "--hidden-dim",
        "16",
        "--json",
        path(&json)?,
        "--save",
        path(&agent)?,
    ])?;
    assert!(out.status.success(), "{}", stderr(&out));
    let config = &read_json(&json)?["config"];
    for (key, value) in [
        ("actor_lr", 3e-4),
        ("critic_lr", 1e-3),
        ("gamma", 0.95),
        ("lmbda", 0.8),
        ("eps", 0.1),
    ] {
        assert_eq!(config[key], value, "{key}: {config}");
    }
    assert_eq!(config["epochs"], 3);
    assert_eq!(config["hidden_dim"], 16);
    assert_eq!(config["num_episodes"], 2);
    let out = ppo_tutor(&["play", "--load", path(&agent)?, "--no-render"])?;
    assert!(out.status.success(), "{}", stderr(&out));

    let out = ppo_tutor(&["train", "--env", "Pendulum-v1", "--lmbda", "1.5"])?;
    assert_eq!(out.status.code(), Some(2));
    assert!(
        stderr(&out).contains("invalid --lmbda 1.5: expected a number in [0, 1]"),
        "{}",
        stderr(&out)
    );
    Ok(())
}

/// The CartPole agent's switches are refused on Pendulum-v1, each naming the flag and why,
/// before any training; an unknown id lists the ones there are.
#[test]
fn cartpole_only_flags_are_refused_on_pendulum() -> TestResult {
    for flag in [
        &["--normalize-advantage"][..],
        &["--bootstrap-truncation"],
        &["--entropy-coef", "0.01"],
        &["--max-grad-norm", "0.5"],
        &["--target-kl", "0.02"],
        &["--no-clip"],
        &["--critic-epochs", "1"],
        &["--algorithm", "reinforce"],
    ] {
        let mut args = vec!["train", "--env", "Pendulum-v1"];
        args.extend_from_slice(flag);
        let out = ppo_tutor(&args)?;
        assert_eq!(out.status.code(), Some(2), "{flag:?}");
        let err = stderr(&out);
        assert!(
            err.contains(&format!("{} works only with CartPole: the book's", flag[0]))
                || err.contains(&format!("{} works only with CartPole: REINFORCE", flag[0])),
            "{flag:?}: {err}"
        );
        assert!(err.contains(&format!("drop {}", flag[0])), "{err}");
        assert!(out.stdout.is_empty(), "nothing trained for {flag:?}");
    }
    let out = ppo_tutor(&["train", "--env", "Acrobot-v1"])?;
    assert_eq!(out.status.code(), Some(2));
    let err = stderr(&out);
    assert!(
        err.contains("unknown environment 'Acrobot-v1'")
            && err.contains("CartPole-v1")
            && err.contains("Pendulum-v1"),
        "{err}"
    );
    Ok(())
}

/// `--seeds` on Pendulum-v1: each seed's run is `--seed`'s, summarised over the last 100
/// episodes (the book's measure), drawn as a band.
#[test]
fn pendulum_over_seeds_equals_the_single_seed_runs() -> TestResult {
    let dir = tempfile::tempdir()?;
    let json = dir.path().join("seeds.json");
    let plot = dir.path().join("seeds.svg");
    let out = ppo_tutor(&[
        "train",
        "--env",
        "Pendulum-v1",
        "--episodes",
        "2",
        "--seeds",
        "1,0",
        "--json",
        path(&json)?,
        "--plot",
        path(&plot)?,
    ])?;
    assert!(out.status.success(), "{}", stderr(&out));
    let stdout = String::from_utf8(out.stdout)?;
    assert!(
        stdout.contains("PPO on Pendulum-v1, 2 seeds, 2 episodes each"),
        "{stdout}"
    );
    let all = read_json(&json)?;
    assert_eq!(all["env"], "Pendulum-v1");
    assert!(all["mean_last_100"]["mean"].is_f64() && all["mean_last_50"]["std"].is_f64());
    let runs = all["runs"].as_array().ok_or("no runs")?;
    assert_eq!(runs.len(), 2);
    for (run, seed) in runs.iter().zip([1, 0]) {
        let one = dir.path().join(format!("seed{seed}.json"));
        let out = ppo_tutor(&[
            "train",
            "-q",
            "--env",
            "Pendulum-v1",
            "--episodes",
            "2",
            "--seed",
            &seed.to_string(),
            "--json",
            path(&one)?,
        ])?;
        assert!(out.status.success(), "{}", stderr(&out));
        let alone = read_json(&one)?;
        assert_eq!(run["seed"], seed);
        assert_eq!(run["returns"], alone["returns"], "seed {seed}");
        assert_eq!(run["mean_last_100"], alone["mean_last_100"], "seed {seed}");
        let line = format!("seed {seed:>3}: mean return of the last 2 episodes");
        assert!(stdout.contains(&line), "{line:?} in {stdout}");
    }
    assert!(std::fs::read_to_string(&plot)?.contains("lowest to highest of 2 seeds"));
    Ok(())
}

/// In a real terminal, `play` animates the pendulum (the canvas in a box, the status line
/// with θ and the torque) through the time limit, then prints the return.
#[test]
fn play_animates_the_pendulum_in_a_terminal() -> TestResult {
    let dir = tempfile::tempdir()?;
    let agent = dir.path().join("pendulum.safetensors");
    let out = ppo_tutor(&[
        "train",
        "-q",
        "--env",
        "Pendulum-v1",
        "--episodes",
        "1",
        "--save",
        path(&agent)?,
    ])?;
    assert!(out.status.success(), "{}", stderr(&out));

    let words = ["play", "--load", path(&agent)?, "--delay-ms", "0"];
    let play: Vec<&std::ffi::OsStr> = words.iter().map(std::ffi::OsStr::new).collect();
    let run = common::in_terminal(&play, &[("PPO_TUTOR_LANG", "en")], (40, 100), ("", b""))?;
    let (bytes, text) = (run.bytes, run.screen);
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&bytes));
    assert!(
        text.contains("Pendulum-v1 episode 0 step 200"),
        "the last frame: {text}"
    );
    assert!(text.contains("u=") && text.contains("θ="), "{text}");
    assert!(text.contains('┌') && text.contains("torque"), "{text}");
    assert!(
        text.chars().any(|c| ('\u{2801}'..='\u{28FF}').contains(&c)),
        "the rod in Braille dots: {text}"
    );
    assert!(
        text.contains("episode 0: return -") && text.contains("time limit after 200 steps"),
        "{text}"
    );
    // One frame before each of the 200 steps, and the last state: 201 frames.
    let frames = String::from_utf8_lossy(&bytes)
        .matches("Pendulum-v1 episode 0 step")
        .count();
    assert_eq!(frames, 201);
    Ok(())
}
