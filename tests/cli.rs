//! The `ppo-tutor` binary as a user runs it: help, output formats, bad input.

use std::process::{Command, Output};

type TestResult = Result<(), Box<dyn std::error::Error>>;

fn run(args: &[&str]) -> std::io::Result<Output> {
    Command::new(env!("CARGO_BIN_EXE_ppo-tutor"))
        .args(args)
        .output()
}

#[test]
fn help_exists_for_every_subcommand() -> TestResult {
    let top = run(&["--help"])?;
    assert!(top.status.success());
    let text = String::from_utf8(top.stdout)?;
    let subcommands: Vec<&str> = text
        .lines()
        .skip_while(|l| !l.starts_with("Commands:"))
        .skip(1)
        .take_while(|l| l.starts_with("  "))
        .filter_map(|l| l.split_whitespace().next())
        .filter(|name| *name != "help")
        .collect();
    assert!(subcommands.contains(&"cartpole"), "{text}");
    for sub in subcommands {
        let out = run(&[sub, "--help"])?;
        assert!(out.status.success(), "{sub} --help failed");
        assert!(
            String::from_utf8(out.stdout)?.contains("Usage:"),
            "{sub} --help has no usage"
        );
    }
    Ok(())
}

/// The developer command `dev` is hidden from the main help but has its own, which says
/// how to run `dev notebooks` (it needs the `notebook-runner` feature).
#[test]
fn dev_is_hidden_and_documented() -> TestResult {
    let top = String::from_utf8(run(&["--help"])?.stdout)?;
    assert!(
        !top.lines().any(|l| l.trim_start().starts_with("dev ")),
        "{top}"
    );
    let dev = run(&["dev", "--help"])?;
    assert!(dev.status.success());
    assert!(String::from_utf8(dev.stdout)?.contains("notebooks"));
    let notebooks = run(&["dev", "notebooks", "--help"])?;
    assert!(notebooks.status.success());
    let text = String::from_utf8(notebooks.stdout)?;
    assert!(
        text.contains("cargo run --features notebook-runner -- dev notebooks"),
        "{text}"
    );
    Ok(())
}

/// Each bad input gives one line on stderr naming the argument, exit code 2, no panic.
#[test]
fn bad_input_is_one_line_and_exit_2() -> TestResult {
    let cases: [(&[&str], &str); 9] = [
        (
            &["cartpole", "--env", "CartPole-v9", "--actions", "0"],
            "--env",
        ),
        (&["cartpole", "--actions", "0,x,1"], "--actions"),
        (&["cartpole", "--actions", "0,2"], "--actions"),
        (&["cartpole", "--seed", "abc", "--actions", "0"], "--seed"),
        (&["cartpole", "--seed", "-3", "--actions", "0"], "--seed"),
        (&["cartpole", "--seed", "1"], "--actions"),
        (&["train", "--seeds", "4-1"], "--seeds"),
        (&["train", "--seeds", "0-2", "--seed", "3"], "--seeds"),
        (
            &["train", "--seeds", "0,1", "--save", "a.safetensors"],
            "--save",
        ),
    ];
    for (args, names) in cases {
        let out = run(args)?;
        let err = String::from_utf8(out.stderr)?;
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert_eq!(
            err.trim_end().lines().count(),
            1,
            "{args:?}: not one line: {err}"
        );
        assert!(
            err.contains(names),
            "{args:?}: does not name {names}: {err}"
        );
        assert!(!err.contains("panicked"), "{args:?}: {err}");
    }
    Ok(())
}

#[test]
fn v0_truncates_at_200_through_the_cli() -> TestResult {
    let out = run(&[
        "cartpole",
        "--env",
        "CartPole-v0",
        "--policy",
        "lean",
        "--seed",
        "5",
        "--json",
    ])?;
    assert!(out.status.success());
    let v: serde_json::Value = serde_json::from_slice(&out.stdout)?;
    let truncated = v["truncated"].as_array().ok_or("no truncated")?;
    let terminated = v["terminated"].as_array().ok_or("no terminated")?;
    assert!(truncated.len() <= 200);
    let ended_by_limit = truncated.last().and_then(serde_json::Value::as_bool) == Some(true);
    assert_eq!(ended_by_limit, truncated.len() == 200);
    assert!(ended_by_limit || terminated.last().and_then(serde_json::Value::as_bool) == Some(true));
    Ok(())
}

#[test]
fn table_output_is_readable() -> TestResult {
    let out = run(&["cartpole", "--seed", "0", "--actions", "0,1,1"])?;
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout)?;
    assert!(text.contains("theta"), "{text}");
    assert!(text.contains("return 3 over 3 steps"), "{text}");
    Ok(())
}

/// `ppo-tutor cartpole ... | head`: when the reader closes the pipe, the command stops
/// quietly, as other command-line tools do, instead of reporting an error.
#[test]
fn a_closed_pipe_is_not_an_error() -> TestResult {
    use std::io::Read;
    use std::process::Stdio;
    // Far more output than a pipe holds (about 430 kB), so the writer meets the closed end.
    let mut child = Command::new(env!("CARGO_BIN_EXE_ppo-tutor"))
        .args([
            "cartpole",
            "--seed",
            "0",
            "--actions",
            "",
            "--resets",
            "5000",
        ])
        .args(["--json"])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()?;
    let mut stdout = child.stdout.take().ok_or("no stdout")?;
    let mut first = [0_u8; 16];
    stdout.read_exact(&mut first)?;
    drop(stdout);
    let out = child.wait_with_output()?;
    let stderr = String::from_utf8(out.stderr)?;
    assert!(out.status.success(), "exit {:?}: {stderr}", out.status);
    assert!(stderr.is_empty(), "{stderr}");
    Ok(())
}
