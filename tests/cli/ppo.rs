//! `ppo-tutor train`, `replay` and `play` as a user runs them, including bad input.

use std::process::Output;

use serde_json::Value;

type TestResult = Result<(), Box<dyn std::error::Error>>;

const FIXTURE: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/tests/fixtures/ppo_update_pytorch.json"
);

const PENALTY_FIXTURE: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/tests/fixtures/ppo_penalty_update_pytorch.json"
);

use crate::common;
use common::english;

fn ppo_tutor(args: &[&str]) -> Result<Output, std::io::Error> {
    english().args(args).output()
}

fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

/// `--seeds`: each seed's run is the run `--seed` gives, and the summary is computed from
/// them (mean ± sample std of the seeds' means of the last 50 returns, the band).
#[test]
fn train_over_seeds_summarises_the_single_seed_runs() -> TestResult {
    let dir = tempfile::tempdir()?;
    let json = dir.path().join("seeds.json");
    let plot = dir.path().join("seeds.svg");
    let out = ppo_tutor(&[
        "train",
        "--episodes",
        "6",
        "--seeds",
        "2,0-1",
        "--json",
        path(&json)?,
        "--plot",
        path(&plot)?,
    ])?;
    assert!(out.status.success(), "{}", stderr(&out));
    let stdout = String::from_utf8(out.stdout)?;
    assert!(stdout.contains("3 seeds, 6 episodes each"), "{stdout}");
    assert!(
        stdout.contains("(* mean, : lowest to highest seed)"),
        "{stdout}"
    );
    let all: Value = serde_json::from_str(&std::fs::read_to_string(&json)?)?;
    let runs = all["runs"].as_array().ok_or("no runs")?;
    let mut means = Vec::new();
    for (run, seed) in runs.iter().zip([2, 0, 1]) {
        assert_eq!(run["seed"].as_u64(), Some(seed));
        let one = dir.path().join(format!("seed{seed}.json"));
        let single = ppo_tutor(&[
            "train",
            "--quiet",
            "--episodes",
            "6",
            "--seed",
            &seed.to_string(),
            "--json",
            path(&one)?,
        ])?;
        assert!(single.status.success(), "{}", stderr(&single));
        let alone: Value = serde_json::from_str(&std::fs::read_to_string(&one)?)?;
        assert_eq!(run["returns"], alone["returns"], "seed {seed}");
        assert_eq!(run["mean_last_50"], alone["mean_last_50"], "seed {seed}");
        let line = format!("seed {seed:>3}: mean return of the last 6 episodes");
        assert!(stdout.contains(&line), "{line:?} in {stdout}");
        means.push(alone["mean_last_50"].as_f64().ok_or("no mean")?);
    }
    let mean = means.iter().sum::<f64>() / 3.0;
    let std = (means.iter().map(|m| (m - mean).powi(2)).sum::<f64>() / 2.0).sqrt();
    let summary = &all["mean_last_50"];
    assert!((summary["mean"].as_f64().ok_or("no mean")? - mean).abs() < 1e-9);
    assert!((summary["std"].as_f64().ok_or("no std")? - std).abs() < 1e-9);
    assert!(
        stdout.contains(&format!("over 3 seeds: {mean:.1} ± {std:.1}")),
        "{stdout}"
    );
    // the robust summary beside it: the IQM and the mean's bootstrap interval, the
    // statistics module's on the same three scores
    let iqm = ppo_tutor::stats::iqm(&means).ok_or("no IQM")?;
    let ci = ppo_tutor::stats::Bootstrap::default().mean(&means)?.ci;
    assert!((summary["iqm"].as_f64().ok_or("no iqm")? - iqm).abs() < 1e-9);
    assert_eq!(summary["mean_ci95"]["low"].as_f64(), Some(ci.low));
    assert_eq!(summary["mean_ci95"]["high"].as_f64(), Some(ci.high));
    assert!(ci.low <= mean && mean <= ci.high, "{ci:?} around {mean}");
    let line = format!(
        "interquartile mean {iqm:.1}; 95% bootstrap interval of the mean [{:.1}, {:.1}]",
        ci.low, ci.high
    );
    assert!(stdout.contains(&line), "{line:?} in {stdout}");
    let band = &all["band"];
    for key in ["mean", "low", "high"] {
        assert_eq!(band[key].as_array().map(Vec::len), Some(6), "{key}");
    }
    let svg = std::fs::read_to_string(&plot)?;
    assert!(svg.contains("lowest to highest of 3 seeds"));
    Ok(())
}

#[test]
fn train_writes_json_checkpoint_and_figure() -> TestResult {
    let dir = tempfile::tempdir()?;
    let json = dir.path().join("run.json");
    let agent = dir.path().join("agent.safetensors");
    let plot = dir.path().join("returns.svg");
    let out = ppo_tutor(&[
        "train",
        "--episodes",
        "12",
        "--seed",
        "4",
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
        stdout.contains("PPO on CartPole-v1, seed 4: 12 episodes"),
        "{stdout}"
    );
    assert!(
        stdout.contains("Episodes"),
        "the terminal plot is drawn: {stdout}"
    );
    let run: Value = serde_json::from_str(&std::fs::read_to_string(&json)?)?;
    let returns = run["returns"].as_array().ok_or("no returns")?;
    assert_eq!(returns.len(), 12);
    let total: f64 = returns.iter().filter_map(Value::as_f64).sum();
    assert_eq!(run["env_steps"].as_f64(), Some(total), "reward 1 per step");
    assert!(run["wall_s"].as_f64().is_some_and(|s| s > 0.0));
    // The seed's moving average over 9 episodes, said in the legend and the JSON.
    assert_eq!(run["moving_average_window"].as_u64(), Some(9));
    let svg = std::fs::read_to_string(&plot)?;
    assert!(svg.contains("PPO on CartPole-v1"));
    assert!(svg.contains("moving average (9 episodes)"));
    assert!(stdout.contains("* moving average of 9)"), "{stdout}");

    let out = ppo_tutor(&[
        "play",
        "--load",
        path(&agent)?,
        "--episodes",
        "2",
        "--no-render",
    ])?;
    assert!(out.status.success(), "{}", stderr(&out));
    assert_eq!(String::from_utf8(out.stdout)?.matches("return").count(), 2);
    Ok(())
}

#[test]
fn out_of_range_hyper_parameters_are_usage_errors() -> TestResult {
    for (flag, value, expected) in [
        ("--eps", "0", "(0, 1)"),
        ("--eps", "1", "(0, 1)"),
        ("--gamma", "1.5", "(0, 1]"),
        ("--actor-lr", "0", "> 0"),
        ("--critic-lr", "-0.1", "> 0"),
        ("--episodes", "0", "at least 1"),
    ] {
        let out = ppo_tutor(&["train", flag, value])?;
        assert_eq!(out.status.code(), Some(2), "{flag} {value}");
        let err = stderr(&out);
        // Either the settings' check ("invalid --eps 0: ...") or, for a count, its value
        // parser ("invalid value '0' for '--episodes <EPISODES>': ...").
        let named = err.contains(&format!("invalid {flag} {value}"))
            || err.contains(&format!("invalid value '{value}' for '{flag}"));
        assert!(named && err.contains(expected), "{err}");
    }
    Ok(())
}

#[test]
fn replay_prints_the_fixture_schema() -> TestResult {
    let out = ppo_tutor(&["replay", FIXTURE, "--json"])?;
    assert!(out.status.success(), "{}", stderr(&out));
    let ours: Value = serde_json::from_slice(&out.stdout)?;
    let fixture: Value = serde_json::from_str(&std::fs::read_to_string(FIXTURE)?)?;
    let cases = ours["cases"].as_array().ok_or("no cases")?;
    assert_eq!(cases.len(), 3);
    for (case, want) in cases
        .iter()
        .zip(fixture["cases"].as_array().ok_or("no cases")?)
    {
        let n = want["batch"]["actions"].as_array().map(Vec::len);
        for key in ["td_target", "td_delta", "advantage", "old_log_probs"] {
            assert_eq!(case[key].as_array().map(Vec::len), n, "{key}");
            assert_eq!(
                case[key][0].as_array().map(Vec::len),
                Some(1),
                "{key} is (N, 1)"
            );
        }
        assert_eq!(case["epochs"].as_array().map(Vec::len), Some(10));
        for key in ["ratio", "surr1", "surr2", "actor_loss", "critic_loss"] {
            assert!(!case["epochs"][0][key].is_null(), "{key}");
        }
        let names: Vec<_> = want["weights_after"]
            .as_object()
            .ok_or("no weights")?
            .keys()
            .collect();
        for name in names {
            let (a, b) = (&case["weights_after"][name], &want["weights_after"][name]);
            assert_eq!(
                a.as_array().map(Vec::len),
                b.as_array().map(Vec::len),
                "{name}"
            );
        }
    }
    Ok(())
}

/// `replay` on PPO-Penalty's recording: every case replays from its recorded β, and the
/// output has the fixture's keys (per epoch `kl`, no `surr1`/`surr2`; `beta_before`,
/// `kl_after`, `beta_after`), with β equal to PyTorch's before and after.
#[test]
fn replay_runs_the_penalty_fixture() -> TestResult {
    let out = ppo_tutor(&["replay", PENALTY_FIXTURE, "--json"])?;
    assert!(out.status.success(), "{}", stderr(&out));
    let ours: Value = serde_json::from_slice(&out.stdout)?;
    let fixture: Value = serde_json::from_str(&std::fs::read_to_string(PENALTY_FIXTURE)?)?;
    let cases = ours["cases"].as_array().ok_or("no cases")?;
    let want = fixture["cases"].as_array().ok_or("no cases")?;
    assert_eq!(cases.len(), want.len());
    for (case, want) in cases.iter().zip(want) {
        let n = want["batch"]["actions"].as_array().map(Vec::len);
        let epochs = case["epochs"].as_array().ok_or("no epochs")?;
        assert_eq!(epochs.len(), 10);
        for epoch in epochs {
            let mut keys: Vec<&String> = epoch.as_object().ok_or("no epoch")?.keys().collect();
            keys.sort();
            assert_eq!(keys, ["actor_loss", "critic_loss", "kl", "ratio"]);
            assert_eq!(epoch["kl"].as_array().map(Vec::len), n);
        }
        for key in ["beta_before", "beta_after"] {
            assert_eq!(case[key], want["expected"][key], "{key}");
        }
        let kl_after = case["kl_after"].as_f64().ok_or("no kl_after")?;
        let want_kl = want["expected"]["kl_after"].as_f64().ok_or("no kl_after")?;
        assert!((kl_after - want_kl).abs() < 1e-6, "{kl_after} vs {want_kl}");
    }
    // the table names the cases too
    let out = ppo_tutor(&["replay", PENALTY_FIXTURE])?;
    assert!(out.status.success(), "{}", stderr(&out));
    let table = String::from_utf8(out.stdout)?;
    assert!(
        table.contains("case 3: 101 transitions, 10 epochs"),
        "{table}"
    );
    Ok(())
}

/// `--objective penalty` trains PPO-Penalty on candle (its configuration in the JSON), and
/// the flags that would change nothing, or do not fit it, are refused with their reason.
#[test]
fn train_with_the_penalty_objective() -> TestResult {
    let dir = tempfile::tempdir()?;
    let json = dir.path().join("run.json");
    let out = ppo_tutor(&[
        "train",
        "--quiet",
        "--episodes",
        "4",
        "--objective",
        "penalty",
        "--kl-delta",
        "0.02",
        "--json",
        path(&json)?,
    ])?;
    assert!(out.status.success(), "{}", stderr(&out));
    let stdout = String::from_utf8(out.stdout)?;
    assert!(
        stdout.contains("update path: candle (autograd) for all 4 updates"),
        "{stdout}"
    );
    let run: Value = serde_json::from_str(&std::fs::read_to_string(&json)?)?;
    let config = run["config"].to_string();
    assert!(
        config.contains(r#""objective":"penalty""#) && config.contains(r#""kl_delta":0.02"#),
        "{config}"
    );
    assert!(
        !config.contains("beta_init"),
        "the default β₀ is left out: {config}"
    );

    for (args, expected) in [
        (
            &["--kl-delta", "0.02"][..],
            "--kl-delta is a setting of PPO-Penalty: add --objective penalty",
        ),
        (
            &["--objective", "penalty", "--algorithm", "reinforce"][..],
            "--objective penalty and --algorithm reinforce do not go together",
        ),
        (
            &["--objective", "penalty", "--no-clip"][..],
            "--objective penalty and --no-clip do not go together",
        ),
        (
            &["--algorithm", "reinforce", "--no-clip"][..],
            "--algorithm reinforce and --no-clip do not go together: REINFORCE has no ratio",
        ),
        (
            &["--objective", "penalty", "--beta-init", "0"][..],
            "invalid --beta-init 0: expected a finite number > 0",
        ),
        (
            &["--env", "Pendulum-v1", "--objective", "penalty"][..],
            "--objective works only with CartPole",
        ),
    ] {
        train_refuses(args, expected)?;
    }
    Ok(())
}

/// `--objective line-search` trains the KL line search on candle (its settings in the
/// JSON), and its flags are refused without it, as are the flags that do not fit it.
#[test]
fn train_with_the_line_search_objective() -> TestResult {
    let dir = tempfile::tempdir()?;
    let json = dir.path().join("run.json");
    let out = ppo_tutor(&[
        "train",
        "--quiet",
        "--episodes",
        "4",
        "--objective",
        "line-search",
        "--ls-max-step",
        "0.5",
        "--ls-backtracks",
        "6",
        "--kl-delta",
        "0.02",
        "--json",
        path(&json)?,
    ])?;
    assert!(out.status.success(), "{}", stderr(&out));
    let stdout = String::from_utf8(out.stdout)?;
    assert!(
        stdout.contains("update path: candle (autograd) for all 4 updates"),
        "{stdout}"
    );
    let run: Value = serde_json::from_str(&std::fs::read_to_string(&json)?)?;
    let config = run["config"].to_string();
    for key in [
        r#""objective":"line-search""#,
        r#""ls_max_step":0.5"#,
        r#""ls_backtracks":6"#,
        r#""kl_delta":0.02"#,
    ] {
        assert!(config.contains(key), "{key} missing: {config}");
    }
    // at the defaults the settings are left out
    let out = ppo_tutor(&[
        "train",
        "--quiet",
        "--episodes",
        "2",
        "--objective",
        "line-search",
        "--json",
        path(&json)?,
    ])?;
    assert!(out.status.success(), "{}", stderr(&out));
    let run: Value = serde_json::from_str(&std::fs::read_to_string(&json)?)?;
    let config = run["config"].to_string();
    assert!(
        config.contains(r#""objective":"line-search""#) && !config.contains("ls_"),
        "{config}"
    );

    for (args, expected) in [
        (
            &["--ls-max-step", "0.5"][..],
            "--ls-max-step is a setting of the KL line search: add --objective line-search",
        ),
        (
            &["--objective", "penalty", "--ls-backtracks", "3"][..],
            "--ls-backtracks is a setting of the KL line search: add --objective line-search",
        ),
        (
            &["--objective", "line-search", "--beta-init", "2"][..],
            "--beta-init is a setting of PPO-Penalty: add --objective penalty",
        ),
        (
            &["--objective", "line-search", "--algorithm", "reinforce"][..],
            "--objective line-search and --algorithm reinforce do not go together",
        ),
        (
            &["--objective", "line-search", "--no-clip"][..],
            "--objective line-search and --no-clip do not go together",
        ),
        (
            &["--objective", "line-search", "--ls-max-step", "0"][..],
            "invalid --ls-max-step 0: expected a finite number > 0",
        ),
        (
            &["--objective", "line-search", "--ls-backtracks", "51"][..],
            "invalid --ls-backtracks 51",
        ),
        (
            &["--objective", "line-search", "--entropy-coef", "0.01"][..],
            "invalid --entropy-coef 0.01",
        ),
        (
            &["--env", "Pendulum-v1", "--objective", "line-search"][..],
            "--objective works only with CartPole",
        ),
    ] {
        train_refuses(args, expected)?;
    }
    Ok(())
}

#[test]
fn replay_names_a_missing_key_and_a_wrong_shape() -> TestResult {
    let dir = tempfile::tempdir()?;
    let mut fixture: Value = serde_json::from_str(&std::fs::read_to_string(FIXTURE)?)?;
    let bad = dir.path().join("bad.json");
    fixture["cases"][1]["batch"]
        .as_object_mut()
        .ok_or("no batch")?
        .remove("rewards");
    std::fs::write(&bad, fixture.to_string())?;
    let out = ppo_tutor(&["replay", path(&bad)?, "--json"])?;
    let err = stderr(&out);
    assert!(!out.status.success());
    assert!(
        err.contains("missing key 'cases[1].batch.rewards'") && err.contains("81 numbers"),
        "{err}"
    );

    let mut fixture: Value = serde_json::from_str(&std::fs::read_to_string(FIXTURE)?)?;
    fixture["cases"][0]["weights_before"]["actor.fc2.bias"] = serde_json::json!([0.0, 0.0, 0.0]);
    std::fs::write(&bad, fixture.to_string())?;
    let out = ppo_tutor(&["replay", path(&bad)?])?;
    let err = stderr(&out);
    assert!(
        err.contains("cases[0].weights_before.actor.fc2.bias") && err.contains("[2]"),
        "{err}"
    );
    Ok(())
}

#[test]
fn play_names_a_tensor_of_the_wrong_shape() -> TestResult {
    let dir = tempfile::tempdir()?;
    let file = dir.path().join("bad.safetensors");
    // `critic.fc2.weight` is [1, 64]: the hidden width is 128.
    let mut tensors = crate::common::cartpole_tensors_with_a_wrong_shape()?;
    candle_core::safetensors::save(&tensors, &file)?;
    let out = ppo_tutor(&["play", "--load", path(&file)?, "--no-render"])?;
    let err = stderr(&out);
    assert!(!out.status.success());
    assert!(
        err.contains("critic.fc2.weight") && err.contains("[1, 128]") && err.contains("[1, 64]"),
        "{err}"
    );

    tensors.remove("actor.fc2.bias");
    candle_core::safetensors::save(&tensors, &file)?;
    let err = stderr(&ppo_tutor(&[
        "play",
        "--load",
        path(&file)?,
        "--no-render",
    ])?);
    assert!(
        err.contains("missing key 'actor.fc2.bias'") && err.contains("[2]"),
        "{err}"
    );

    std::fs::write(&file, "not a checkpoint")?;
    let err = stderr(&ppo_tutor(&[
        "play",
        "--load",
        path(&file)?,
        "--no-render",
    ])?);
    assert!(
        err.contains("not a readable safetensors checkpoint"),
        "{err}"
    );
    Ok(())
}

fn path(p: &std::path::Path) -> Result<&str, &'static str> {
    p.to_str().ok_or("non-UTF-8 temp path")
}

/// `ppo-tutor lab`: the list, a short experiment whose base arm is the plain run of each
/// seed, its JSON and figure, and a wrong name.
#[test]
fn lab_runs_an_experiment_over_seeds_and_refuses_an_unknown_one() -> TestResult {
    let out = ppo_tutor(&["lab"])?;
    assert!(out.status.success(), "{}", stderr(&out));
    let list = String::from_utf8(out.stdout)?;
    for name in ["eps", "epochs", "actor-lr", "target-kl", "reinforce"] {
        assert!(
            list.contains(&format!("  {name} ")),
            "{name} missing: {list}"
        );
    }
    let out = ppo_tutor(&["lab", "clip"])?;
    assert_eq!(out.status.code(), Some(2));
    assert!(
        stderr(&out).contains("choose one of eps, epochs"),
        "{}",
        stderr(&out)
    );

    let dir = tempfile::tempdir()?;
    let json = dir.path().join("lab.json");
    let plot = dir.path().join("lab.svg");
    let out = ppo_tutor(&[
        "lab",
        "reinforce",
        "--episodes",
        "8",
        "--seeds",
        "0-1",
        "--json",
        path(&json)?,
        "--plot",
        path(&plot)?,
    ])?;
    assert!(out.status.success(), "{}", stderr(&out));
    let stdout = String::from_utf8(out.stdout)?;
    assert!(
        stdout.contains("2 settings x 2 seeds, 8 episodes each"),
        "{stdout}"
    );
    assert!(
        stdout.contains("REINFORCE + baseline") && stdout.contains("against PPO"),
        "{stdout}"
    );
    let lab: Value = serde_json::from_str(&std::fs::read_to_string(&json)?)?;
    let arms = lab["arms"].as_array().ok_or("no arms")?;
    assert_eq!(arms.len(), 2);
    assert_eq!(arms[1]["config"]["algorithm"], "reinforce");
    // The arms are compared seed by seed: each seed's difference of final scores, with the
    // statistics module's interval and a verdict only where the interval excludes zero.
    let finals = |arm: &Value| -> Result<Vec<f64>, &'static str> {
        arm["finals"]
            .as_array()
            .ok_or("no finals")?
            .iter()
            .map(|v| v.as_f64().ok_or("a final that is not a number"))
            .collect()
    };
    let paired =
        ppo_tutor::stats::Bootstrap::default().paired(&finals(&arms[1])?, &finals(&arms[0])?)?;
    let recorded = &lab["paired_with_first"][0];
    assert_eq!(
        recorded["mean_difference"].as_f64(),
        Some(paired.mean_difference)
    );
    assert_eq!(recorded["ci"]["low"].as_f64(), Some(paired.ci.low));
    assert!(
        stdout.contains("each setting − PPO") && stdout.contains("on the same 2 seeds"),
        "{stdout}"
    );
    let words = ppo_tutor::ppo::lab::paired_words(&paired);
    assert!(stdout.contains(&words), "{words:?} in {stdout}");
    // The base arm's seed 1 is `train --seed 1` with the same episodes.
    let single = dir.path().join("one.json");
    let out = ppo_tutor(&[
        "train",
        "--episodes",
        "8",
        "--seed",
        "1",
        "-q",
        "--json",
        path(&single)?,
    ])?;
    assert!(out.status.success(), "{}", stderr(&out));
    let one: Value = serde_json::from_str(&std::fs::read_to_string(&single)?)?;
    assert_eq!(arms[0]["returns"][1], one["returns"]);
    assert!(std::fs::read_to_string(&plot)?.contains("lab reinforce: 2 seeds"));
    Ok(())
}

/// `--algorithm reinforce` takes one step per episode, `--no-clip` keeps ten, `--critic-epochs`
/// sets the critic's apart from the actor's, and each is recorded in the run's configuration.
#[test]
fn train_switches_to_reinforce_or_drops_the_clip() -> TestResult {
    let dir = tempfile::tempdir()?;
    for (flag, key, value) in [
        (
            &["--algorithm", "reinforce"][..],
            "algorithm",
            Value::from("reinforce"),
        ),
        (&["--no-clip"][..], "no_clip", Value::from(true)),
        (
            &["--critic-epochs", "1"][..],
            "critic_epochs",
            Value::from(1),
        ),
    ] {
        let json = dir.path().join(format!("{key}.json"));
        let mut args = vec!["train", "--episodes", "4", "-q", "--json", path(&json)?];
        args.extend_from_slice(flag);
        let out = ppo_tutor(&args)?;
        assert!(out.status.success(), "{}", stderr(&out));
        let run: Value = serde_json::from_str(&std::fs::read_to_string(&json)?)?;
        assert_eq!(run["config"][key], value, "{run}");
    }
    // The summary and the figure are titled by what trained, one seed or several.
    for (flag, title) in [
        (
            &["--algorithm", "reinforce"][..],
            "REINFORCE on CartPole-v1",
        ),
        (&["--no-clip"][..], "PPO without the clip on CartPole-v1"),
        (
            &["--objective", "penalty"][..],
            "PPO-Penalty on CartPole-v1",
        ),
        (
            &["--objective", "line-search"][..],
            "KL line search on CartPole-v1",
        ),
    ] {
        for seeds in [&[][..], &["--seeds", "0-1"]] {
            let plot = dir.path().join("titled.svg");
            let mut args = vec!["train", "--episodes", "2", "-q", "--plot", path(&plot)?];
            args.extend_from_slice(flag);
            args.extend_from_slice(seeds);
            let out = ppo_tutor(&args)?;
            assert!(out.status.success(), "{args:?}: {}", stderr(&out));
            let stdout = String::from_utf8(out.stdout)?;
            assert!(stdout.starts_with(title), "{args:?}: {stdout}");
            let svg = std::fs::read_to_string(&plot)?;
            assert!(svg.contains(title) && !svg.contains(">PPO on"), "{args:?}");
        }
    }
    let out = ppo_tutor(&["train", "--algorithm", "a2c"])?;
    assert_eq!(out.status.code(), Some(2));
    Ok(())
}

/// `train` says which implementation ran its updates, and
/// `PPO_TUTOR_UPDATE=candle` runs every update on candle with the same numbers, on both
/// agents; a value it does not know changes nothing.
#[test]
fn train_names_the_update_path_and_candle_can_be_forced() -> TestResult {
    use ppo_tutor::ppo::update_path::UPDATE_VAR;
    let dir = tempfile::tempdir()?;
    let plain = ppo_tutor::ppo::UpdatePath::plain_available();
    if !plain {
        eprintln!(
            "this CPU lacks AVX2+FMA: both runs below are on candle (the comparison of the two \
             paths is skipped; the lines and the switch are still checked)"
        );
    }
    for (env, episodes) in [("CartPole-v1", 6), ("Pendulum-v1", 2)] {
        let run = |setting: Option<&str>,
                   lang: &str|
         -> Result<(String, Value), Box<dyn std::error::Error>> {
            let json = dir.path().join(format!("{env}-{setting:?}-{lang}.json"));
            let mut cmd = english();
            match setting {
                Some(value) => cmd.env(UPDATE_VAR, value),
                None => cmd.env_remove(UPDATE_VAR),
            };
            let n = episodes.to_string();
            let out = cmd
                .args([
                    "--lang",
                    lang,
                    "train",
                    "-q",
                    "--env",
                    env,
                    "--episodes",
                    &n,
                ])
                .args(["--json", path(&json)?])
                .output()?;
            assert!(out.status.success(), "{env} {setting:?}: {}", stderr(&out));
            let run: Value = serde_json::from_str(&std::fs::read_to_string(&json)?)?;
            Ok((String::from_utf8(out.stdout)?, run["returns"].clone()))
        };
        let (auto, auto_returns) = run(None, "en")?;
        let (forced, forced_returns) = run(Some("candle"), "en")?;
        let (unknown, unknown_returns) = run(Some("turbo"), "en")?;
        let automatic_line = if plain {
            format!("update path: plain f32 kernels for all {episodes} updates")
        } else {
            format!(
                "update path: candle (autograd) for all {episodes} updates, as this CPU lacks AVX2+FMA"
            )
        };
        assert!(auto.contains(&automatic_line), "{env}: {auto}");
        assert!(unknown.contains(&automatic_line), "{env}: {unknown}");
        let forced_line = format!(
            "update path: candle (autograd) for all {episodes} updates, forced by PPO_TUTOR_UPDATE=candle"
        );
        assert!(forced.contains(&forced_line), "{env}: {forced}");
        // the plain path is candle's operations one for one: the same returns, bit for bit
        assert!(auto_returns.as_array().is_some_and(|r| r.len() == episodes));
        assert_eq!(forced_returns, auto_returns, "{env}");
        assert_eq!(unknown_returns, auto_returns, "{env}");
        let (zh, _) = run(Some("candle"), "zh")?;
        let zh_line = format!(
            "更新路径：全部 {episodes} 次更新均用 candle（自动求导），由 PPO_TUTOR_UPDATE=candle 强制"
        );
        assert!(zh.contains(&zh_line), "{env}: {zh}");
    }
    Ok(())
}

/// `train --episodes 1 ARGS` exits with a usage error whose text contains `expected`.
fn train_refuses(args: &[&str], expected: &str) -> TestResult {
    let out = ppo_tutor(&[&["train", "--episodes", "1"][..], args].concat())?;
    assert_eq!(out.status.code(), Some(2), "{args:?}");
    let err = stderr(&out);
    assert!(err.contains(expected), "{args:?}: {err}");
    Ok(())
}

/// A run longer than the seed's smooths over more episodes (one per fifty, odd: 11 for
/// 550), and every output says so; the seed's 500 episodes keep its 9 (checked above with
/// 12 episodes, and by the parity tests).
#[test]
fn a_longer_run_smooths_over_more_episodes() -> TestResult {
    let dir = tempfile::tempdir()?;
    let json = dir.path().join("long.json");
    let plot = dir.path().join("long.svg");
    let out = ppo_tutor(&[
        "train",
        "--episodes",
        "550",
        "--json",
        path(&json)?,
        "--plot",
        path(&plot)?,
    ])?;
    assert!(out.status.success(), "{}", stderr(&out));
    let stdout = String::from_utf8(out.stdout)?;
    assert!(stdout.contains("* moving average of 11)"), "{stdout}");
    assert!(std::fs::read_to_string(&plot)?.contains("moving average (11 episodes)"));
    let run: Value = serde_json::from_str(&std::fs::read_to_string(&json)?)?;
    assert_eq!(run["moving_average_window"].as_u64(), Some(11));
    // The curve is the seed's rl_utils.moving_average over 11.
    let (returns, average) = (
        crate::common::numbers(&run["returns"]),
        crate::common::numbers(&run["moving_average"]),
    );
    assert_eq!(returns.len(), 550);
    assert_eq!(average, ppo_tutor::ppo::moving_average(&returns, 11)?);
    Ok(())
}

/// `--x-axis steps` draws the returns against the environment steps at each episode's end,
/// the steps the JSON lists (one per episode, ending at the run's total); it needs `--plot`
/// and is refused with `--seeds`, whose runs end their episodes at different steps.
#[test]
fn the_return_plot_can_be_drawn_against_environment_steps() -> TestResult {
    let dir = tempfile::tempdir()?;
    let (json, plot) = (dir.path().join("run.json"), dir.path().join("run.svg"));
    let out = ppo_tutor(&[
        "train",
        "--quiet",
        "--episodes",
        "5",
        "--json",
        path(&json)?,
        "--plot",
        path(&plot)?,
        "--x-axis",
        "steps",
    ])?;
    assert!(out.status.success(), "{}", stderr(&out));
    let run: Value = serde_json::from_str(&std::fs::read_to_string(&json)?)?;
    let ends: Vec<u64> = run["episode_end_steps"]
        .as_array()
        .ok_or("no episode_end_steps")?
        .iter()
        .filter_map(Value::as_u64)
        .collect();
    let returns = common::numbers(&run["returns"]);
    assert_eq!(ends.len(), returns.len());
    // CartPole pays 1 per step, so each episode's steps are its return.
    let mut total = 0;
    for (end, r) in ends.iter().zip(&returns) {
        total += *r as u64;
        assert_eq!(*end, total);
    }
    assert_eq!(run["env_steps"].as_u64(), Some(total));
    let svg = std::fs::read_to_string(&plot)?;
    assert!(
        svg.contains("Environment steps") && !svg.contains(">Episodes<"),
        "x label"
    );

    for (args, named) in [
        (vec!["train", "--x-axis", "steps"], "--plot"),
        (
            vec![
                "train", "--seeds", "0-1", "--plot", "x.svg", "--x-axis", "steps",
            ],
            "--x-axis",
        ),
    ] {
        let out = ppo_tutor(&args)?;
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        assert!(stderr(&out).contains(named), "{}", stderr(&out));
    }
    Ok(())
}
