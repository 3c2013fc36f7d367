//! The `ppo-tutor` binary as a user runs it: help, output formats, bad input.

use std::process::{Command, Output};

type TestResult = Result<(), Box<dyn std::error::Error>>;

use crate::common;
use common::{english, with_env};

/// [`with_env`] with its progress file and grading cache in `dir` (not the user's).
fn sandboxed(dir: &std::path::Path) -> Command {
    let mut cmd = with_env(&[]);
    cmd.env("PPO_TUTOR_STATE", dir.join("state.json"))
        .env("PPO_TUTOR_GRADE_CACHE", dir.join("cache"));
    cmd
}

fn run(args: &[&str]) -> std::io::Result<Output> {
    english().args(args).output()
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
    let mut child = english()
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

/// The TOML front matter of a lesson file (between the `+++` lines).
fn front_matter(path: &std::path::Path) -> Result<toml::Table, Box<dyn std::error::Error>> {
    let text = std::fs::read_to_string(path)?;
    let body = text
        .strip_prefix("+++\n")
        .and_then(|t| t.split_once("\n+++"))
        .map(|(front, _)| front)
        .ok_or_else(|| format!("{} has no +++ front matter", path.display()))?;
    Ok(body.parse::<toml::Table>()?)
}

/// `id<TAB>title` of every lesson, in course order (folder order), with the title of
/// `file` (`lesson.md` or `lesson.zh.md`); the id is always `lesson.md`'s.
fn listing(file: &str) -> Result<String, Box<dyn std::error::Error>> {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("lessons");
    let mut folders: Vec<_> = std::fs::read_dir(&root)?
        .filter_map(Result::ok)
        .map(|e| e.path())
        .filter(|p| p.join("lesson.md").is_file())
        .collect();
    folders.sort();
    let mut out = String::new();
    for folder in folders {
        let en = front_matter(&folder.join("lesson.md"))?;
        let id = en.get("id").and_then(toml::Value::as_str).ok_or("no id")?;
        let ours = front_matter(&folder.join(file))?;
        let title = ours
            .get("title")
            .and_then(toml::Value::as_str)
            .ok_or_else(|| format!("{}: no title in {file}", folder.display()))?;
        out.push_str(&format!("{id}\t{title}\n"));
    }
    Ok(out)
}

fn stdout_of(out: &Output) -> Result<String, Box<dyn std::error::Error>> {
    assert!(
        out.status.success(),
        "exit {:?}: {}",
        out.status,
        String::from_utf8_lossy(&out.stderr)
    );
    Ok(String::from_utf8(out.stdout.clone())?)
}

/// `--lang zh`, `PPO_TUTOR_LANG=zh` and a Chinese locale each list the Chinese titles
/// (before or after the subcommand); English stays the default.
#[test]
fn lessons_are_listed_in_the_language_asked_for() -> TestResult {
    let zh = listing("lesson.zh.md")?;
    let en = listing("lesson.md")?;
    assert_ne!(zh, en);
    for (how, cmd) in [
        (
            "--lang zh first",
            with_env(&[]).args(["--lang", "zh", "lessons"]).output(),
        ),
        (
            "--lang zh after",
            with_env(&[]).args(["lessons", "--lang=zh"]).output(),
        ),
        (
            "PPO_TUTOR_LANG=zh",
            with_env(&[("PPO_TUTOR_LANG", "zh")])
                .arg("lessons")
                .output(),
        ),
        (
            "LANG=zh_CN.UTF-8",
            with_env(&[("LANG", "zh_CN.UTF-8")]).arg("lessons").output(),
        ),
        (
            "LC_ALL=zh_CN.UTF-8",
            with_env(&[("LC_ALL", "zh_CN.UTF-8"), ("LANG", "en_US.UTF-8")])
                .arg("lessons")
                .output(),
        ),
    ] {
        assert_eq!(stdout_of(&cmd?)?, zh, "{how}");
    }
    for (how, cmd) in [
        ("nothing set", with_env(&[]).arg("lessons").output()),
        (
            "LANG=en_US.UTF-8",
            with_env(&[("LANG", "en_US.UTF-8")]).arg("lessons").output(),
        ),
        ("LANG=C", with_env(&[("LANG", "C")]).arg("lessons").output()),
        // The flag beats the variable, which beats the locale.
        (
            "--lang en over PPO_TUTOR_LANG=zh",
            with_env(&[("PPO_TUTOR_LANG", "zh")])
                .args(["--lang", "en", "lessons"])
                .output(),
        ),
        (
            "PPO_TUTOR_LANG=en over LANG=zh",
            with_env(&[("PPO_TUTOR_LANG", "en"), ("LANG", "zh_CN.UTF-8")])
                .arg("lessons")
                .output(),
        ),
    ] {
        assert_eq!(stdout_of(&cmd?)?, en, "{how}");
    }
    Ok(())
}

/// A language that does not exist is a usage error naming the fix, in one line, exit 2.
#[test]
fn a_bad_language_is_exit_2_with_the_fix() -> TestResult {
    for (how, out, names) in [
        (
            "--lang fr",
            with_env(&[]).args(["--lang", "fr", "lessons"]).output()?,
            "--lang",
        ),
        (
            "PPO_TUTOR_LANG=klingon",
            with_env(&[("PPO_TUTOR_LANG", "klingon")])
                .arg("lessons")
                .output()?,
            "PPO_TUTOR_LANG",
        ),
    ] {
        let err = String::from_utf8(out.stderr)?;
        assert_eq!(out.status.code(), Some(2), "{how}: {err}");
        assert!(out.stdout.is_empty(), "{how}");
        assert_eq!(err.trim_end().lines().count(), 1, "{how}: {err}");
        assert!(
            err.contains(names) && err.contains("en or zh"),
            "{how}: {err}"
        );
        assert!(!err.contains("panicked"), "{how}: {err}");
    }
    // --lang given: a bad variable does not matter.
    let out = with_env(&[("PPO_TUTOR_LANG", "klingon")])
        .args(["--lang", "en", "lessons"])
        .output()?;
    assert_eq!(stdout_of(&out)?, listing("lesson.md")?);
    Ok(())
}

/// `--lang` is accepted by every subcommand, and the help says how the language is chosen.
#[test]
fn every_subcommand_takes_lang_and_the_help_explains_it() -> TestResult {
    let top = String::from_utf8(run(&["--help"])?.stdout)?;
    for says in ["--lang", "PPO_TUTOR_LANG", "LANG"] {
        assert!(top.contains(says), "{top}");
    }
    for sub in [
        "cartpole", "pendulum", "lessons", "show", "train", "lab", "play", "replay", "grade",
        "watch", "reset", "init",
    ] {
        let out = run(&[sub, "--lang", "zh", "--help"])?;
        assert!(out.status.success(), "{sub} --lang zh --help");
        assert!(String::from_utf8(out.stdout)?.contains("--lang"), "{sub}");
    }
    Ok(())
}

/// Errors are translated around what they quote, and the exit code does not change.
#[test]
fn errors_speak_the_language_and_keep_their_exit_code() -> TestResult {
    let en = run(&["show", "no-such-lesson"])?;
    let zh = with_env(&[])
        .args(["--lang", "zh", "show", "no-such-lesson"])
        .output()?;
    assert_eq!(en.status.code(), Some(2));
    assert_eq!(zh.status.code(), Some(2));
    let (en, zh) = (String::from_utf8(en.stderr)?, String::from_utf8(zh.stderr)?);
    assert!(en.contains("unknown lesson 'no-such-lesson'"), "{en}");
    assert!(
        zh.contains("错误") && zh.contains("'no-such-lesson'") && zh.contains("td-target"),
        "{zh}"
    );
    let zh = with_env(&[])
        .args(["--lang", "zh", "cartpole", "--seed", "1"])
        .output()?;
    assert_eq!(zh.status.code(), Some(2));
    let err = String::from_utf8(zh.stderr)?;
    assert!(err.contains("--actions") && err.contains("请"), "{err}");
    Ok(())
}

/// The cartpole table in Chinese: the same numbers, the words translated, the columns where
/// the English ones are (a Chinese character is two columns wide).
#[test]
fn the_cartpole_table_reads_in_chinese() -> TestResult {
    let args = ["cartpole", "--seed", "0", "--actions", "0,1,1"];
    let en = stdout_of(&run(&args)?)?;
    let zh = stdout_of(&with_env(&[("PPO_TUTOR_LANG", "zh")]).args(args).output()?)?;
    assert!(zh.contains("共 3 步，回报 3"), "{zh}");
    assert!(zh.contains("左") && zh.contains("右"), "{zh}");
    assert_eq!(en.lines().count(), zh.lines().count());
    use unicode_width::UnicodeWidthStr;
    // The header's columns end where the English ones do, up to the last numeric column.
    let upto = |l: &str, word: &str| l.find(word).map(|i| l[..i + word.len()].width());
    let (eh, zh_h) = (
        en.lines().nth(1).unwrap_or(""),
        zh.lines().nth(1).unwrap_or(""),
    );
    assert_eq!(
        upto(eh, "theta_dot"),
        upto(zh_h, "theta_dot"),
        "{eh}\n{zh_h}"
    );
    assert!(zh_h.contains("奖励"), "{zh_h}");
    // Every row has the same numbers at the same columns (no row ends the episode here).
    for (e, z) in en.lines().zip(zh.lines()).skip(2).take(4) {
        let numbers = |l: &str| -> Vec<String> {
            l.split_whitespace()
                .filter(|w| w.parse::<f64>().is_ok())
                .map(str::to_string)
                .collect()
        };
        assert_eq!(numbers(e), numbers(z), "{e}\n{z}");
        assert_eq!(e.trim_end().width(), z.trim_end().width(), "{e}\n{z}");
    }
    Ok(())
}

/// `grade` reports in Chinese with `--lang zh`: the marks, the labels and the mistake's
/// hint from `exercise.zh.toml`, with the exit code of the English report.
#[test]
fn a_wrong_answer_is_graded_in_chinese_with_the_same_exit_code() -> TestResult {
    let dir = tempfile::tempdir()?;
    let lesson = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("lessons/08-gae");
    // A classic mistake: each advantage is its own TD error, nothing of the steps after it.
    let starter = std::fs::read_to_string(lesson.join("exercise.rs"))?;
    let at = starter
        .find("pub fn compute_advantage(")
        .ok_or("no compute_advantage")?;
    let todo = at + starter[at..].find("todo!()").ok_or("no todo!()")?;
    let wrong = format!(
        "{}td_delta.to_vec(){}",
        &starter[..todo],
        &starter[todo + "todo!()".len()..]
    );
    let file = dir.path().join("wrong.rs");
    std::fs::write(&file, wrong)?;
    let file = file.to_str().ok_or("path")?;
    let grade = |lang: &str| {
        sandboxed(dir.path())
            .args(["--lang", lang, "grade", "compute_advantage", "--file", file])
            .env("NO_COLOR", "1")
            .output()
    };
    let (en, zh) = (grade("en")?, grade("zh")?);
    assert_eq!(
        en.status.code(),
        Some(1),
        "{}",
        String::from_utf8_lossy(&en.stderr)
    );
    assert_eq!(zh.status.code(), en.status.code());
    let (en, zh) = (String::from_utf8(en.stdout)?, String::from_utf8(zh.stdout)?);
    assert!(
        en.contains("hint:") && en.contains("checks passed: not yet"),
        "{en}"
    );
    let hints: toml::Table = std::fs::read_to_string(lesson.join("exercise.zh.toml"))?.parse()?;
    let hint = hints
        .get("exercise")
        .and_then(toml::Value::as_array)
        .and_then(|all| {
            all.iter()
                .find(|e| e.get("name").and_then(toml::Value::as_str) == Some("compute_advantage"))
        })
        .and_then(|e| e.get("mistakes")?.get("no_recursion")?.as_str())
        .ok_or("no Chinese hint for no_recursion")?;
    assert!(zh.contains("提示：") && zh.contains(hint), "{zh}");
    assert!(
        zh.contains("✗ 负的 TD 误差") && zh.contains("项检查通过"),
        "{zh}"
    );
    assert!(
        !zh.contains("hint:") && !zh.contains("checks passed"),
        "{zh}"
    );
    // The same checks and lines, only the words differ.
    assert_eq!(en.lines().count(), zh.lines().count(), "{en}\n{zh}");
    assert_eq!(en.matches('✗').count(), zh.matches('✗').count());
    Ok(())
}

/// A missing argument is named, and a negative count is refused by name.
#[test]
fn a_missing_argument_is_named_and_a_negative_count_refused() -> TestResult {
    for cmd in ["show", "reset", "play", "replay"] {
        let out = run(&[cmd])?;
        let err = String::from_utf8(out.stderr)?;
        assert_eq!(out.status.code(), Some(2), "{cmd}: {err}");
        assert_eq!(err.trim_end().lines().count(), 1, "{cmd}: {err}");
        let named = err
            .split_once("not provided:")
            .map(|(_, rest)| rest.trim_start())
            .unwrap_or_default();
        assert!(
            named.starts_with('<') || named.starts_with("--"),
            "{cmd}: the missing argument is not named: {err}"
        );
    }
    // Every whole-number flag refuses a negative value by name (not as an unknown `-5`).
    for (args, says) in [
        (&["train", "--episodes", "-5"][..], "at least 1"),
        (&["train", "--epochs", "-5"], "0 or more"),
        (&["train", "--critic-epochs", "-5"], "0 or more"),
        (&["train", "--hidden-dim", "-5"], "0 or more"),
        (
            &[
                "train",
                "--objective",
                "line-search",
                "--ls-backtracks",
                "-5",
            ],
            "0 or more",
        ),
        (&["cartpole", "--resets", "-5"], "0 or more"),
        (&["pendulum", "--resets", "-5"], "0 or more"),
        (&["show", "td-target", "--step", "-5"], "at least 1"),
    ] {
        let out = run(args)?;
        let err = String::from_utf8(out.stderr)?;
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(
            err.contains("'-5'") && err.contains(says) && !err.contains("unexpected argument"),
            "{args:?}: the value is not refused by name: {err}"
        );
    }
    Ok(())
}

/// A SIGTERM ends `ppo-tutor` whole. Without `RAYON_NUM_THREADS` it runs
/// itself again with one candle thread; that run now replaces the process (same PID)
/// instead of being a child that outlived its parent.
#[cfg(target_os = "linux")]
#[test]
fn sigterm_leaves_no_process_behind() -> TestResult {
    let mut child = english()
        .env_remove("RAYON_NUM_THREADS")
        .args(["train", "--episodes", "100000", "--quiet"])
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .spawn()?;
    let pid = child.id();
    // Wait until the process runs with one candle thread (the re-run has happened).
    let environ = format!("/proc/{pid}/environ");
    let started = std::time::Instant::now();
    while !std::fs::read(&environ)
        .unwrap_or_default()
        .split(|b| *b == 0)
        .any(|v| v == b"RAYON_NUM_THREADS=1")
    {
        if started.elapsed() > std::time::Duration::from_secs(10) {
            let _ = child.kill();
            return Err("ppo-tutor never ran with RAYON_NUM_THREADS=1".into());
        }
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
    let children =
        std::fs::read_to_string(format!("/proc/{pid}/task/{pid}/children")).unwrap_or_default();
    let term = Command::new("kill")
        .args(["-TERM", &pid.to_string()])
        .status()?;
    assert!(term.success());
    let _ = child.wait()?;
    assert!(
        children.trim().is_empty(),
        "ppo-tutor ran its work in child processes {children}, which a SIGTERM leaves behind"
    );
    Ok(())
}

/// Output paths are checked before training starts (a 100000-episode run would take
/// minutes), a path that is not a regular file is never replaced, and the error names the
/// path given, never a temporary file's.
#[test]
fn bad_output_paths_are_refused_before_training() -> TestResult {
    let dir = tempfile::tempdir()?;
    let d = dir.path();
    let folder = d.join("a-folder");
    std::fs::create_dir(&folder)?;
    let mut cases: Vec<(&str, std::path::PathBuf, &str)> = vec![
        ("--plot", d.join("out.xyz"), "FILE.png / FILE.svg"),
        ("--plot", d.join("out"), "FILE.png / FILE.svg"),
        ("--plot", d.join("no/such/dir/out.png"), "does not exist"),
        (
            "--save",
            d.join("no/such/agent.safetensors"),
            "does not exist",
        ),
        ("--save", folder.clone(), "not a regular file"),
        ("--save", d.join("agent.bin"), "use FILE.safetensors"),
        ("--json", d.join("no/such/run.json"), "does not exist"),
    ];
    // A folder that takes no new file, even for root.
    #[cfg(target_os = "linux")]
    for (flag, file) in [
        ("--save", "/proc/x.safetensors"),
        ("--json", "/proc/x.json"),
        ("--plot", "/proc/x.svg"),
    ] {
        cases.push((flag, file.into(), "cannot write a file in /proc"));
    }
    for (flag, path, want) in cases {
        let path = path.to_str().ok_or("path")?;
        for command in [
            &["train", "--episodes", "100000"][..],
            &["lab", "eps", "--episodes", "100000"],
        ] {
            if command[0] == "lab" && flag == "--save" {
                continue;
            }
            let mut args = command.to_vec();
            args.extend(["--quiet", flag, path]);
            let out = run(&args)?;
            let err = String::from_utf8(out.stderr)?;
            assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
            assert!(
                err.contains(want)
                    && err.contains(path)
                    && !err.replace(&d.display().to_string(), "").contains(".tmp"),
                "{args:?}: {err}"
            );
            assert!(
                out.stdout.is_empty(),
                "{args:?}: refused only after training: {}",
                String::from_utf8_lossy(&out.stdout)
            );
        }
    }
    assert!(folder.is_dir(), "the folder given to --save was replaced");
    Ok(())
}

/// What `train` writes (the checkpoint, the JSON, the figure) gets the permissions of any
/// new file (0o644 under the usual umask 022; checkpoints were 0o600), and nothing else is
/// left in the folder.
#[cfg(unix)]
#[test]
fn outputs_have_the_usual_permissions() -> TestResult {
    use std::os::unix::fs::PermissionsExt as _;
    let dir = tempfile::tempdir()?;
    let d = dir.path();
    let reference = d.join("reference");
    std::fs::File::create(&reference)?;
    let mode = |p: &std::path::Path| std::fs::metadata(p).map(|m| m.permissions().mode() & 0o777);
    let want = mode(&reference)?;
    std::fs::remove_file(&reference)?;
    let files = [
        "agent.safetensors",
        "run.json",
        "returns.png",
        "returns.svg",
    ];
    for plot in ["returns.png", "returns.svg"] {
        let p = |name: &str| d.join(name).display().to_string();
        let out = run(&[
            "train",
            "--episodes",
            "3",
            "-q",
            "--save",
            &p("agent.safetensors"),
            "--json",
            &p("run.json"),
            "--plot",
            &p(plot),
        ])?;
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
    }
    for name in files {
        assert_eq!(
            mode(&d.join(name))?,
            want,
            "{name}: mode {:o}",
            mode(&d.join(name))?
        );
    }
    assert_eq!(std::fs::read_dir(d)?.count(), files.len());
    Ok(())
}

/// An error that names a file names it once (`loading the agent: FILE: ...`, not
/// `loading the agent from FILE: FILE: ...`), and `--delay-ms -5` says what a delay is.
#[test]
fn errors_name_a_file_once_and_a_negative_delay_is_explained() -> TestResult {
    let dir = tempfile::tempdir()?;
    let missing = dir.path().join("nope.safetensors");
    let missing = missing.to_str().ok_or("path")?;
    for args in [
        &["play", "--load", missing][..],
        &["play", "--load", missing, "--env", "Pendulum-v1"],
        &["replay", missing],
    ] {
        let out = run(args)?;
        let err = String::from_utf8(out.stderr)?;
        assert_eq!(out.status.code(), Some(1), "{args:?}: {err}");
        assert_eq!(err.matches(missing).count(), 1, "{args:?}: {err}");
        assert_eq!(err.lines().count(), 1, "{args:?}: {err}");
    }
    for delay in ["-5", "1.5"] {
        let out = run(&["play", "--load", missing, "--delay-ms", delay])?;
        let err = String::from_utf8(out.stderr)?;
        assert_eq!(out.status.code(), Some(2), "{err}");
        assert!(
            err.contains("'--delay-ms <DELAY_MS>'")
                && err.contains(&format!(
                    "expected a whole number of milliseconds, 0 or more, got '{delay}'"
                )),
            "{err}"
        );
    }
    Ok(())
}

/// Runs `ppo-tutor ARGS` in a terminal with `env`, presses Ctrl-C once `ready` is on the
/// screen, and returns the exit code and the screen.
#[cfg(unix)]
fn ctrl_c_in_a_terminal(
    args: &[&std::ffi::OsStr],
    env: &[(&str, &str)],
    ready: &str,
) -> Result<(u32, String), Box<dyn std::error::Error>> {
    let run = common::in_terminal(args, env, (30, 220), (ready, b"\x03"))?;
    Ok((run.status.exit_code(), run.screen))
}

/// Ctrl-C in a terminal while `train` draws its bars: the run stops at the end of the
/// episode under way, says after how many episodes and that nothing was saved, names the
/// outputs it did not write, and exits with 130; the files are not there.
#[cfg(unix)]
#[test]
fn ctrl_c_says_where_training_stopped_and_that_nothing_was_saved() -> TestResult {
    let dir = tempfile::tempdir()?;
    let agent = dir.path().join("agent.safetensors");
    let json = dir.path().join("run.json");
    // Pendulum-v1's episodes all take 200 steps: 5000 of them run for seconds after the
    // first bar appears.
    let args: Vec<&std::ffi::OsStr> = ["train", "--env", "Pendulum-v1", "--episodes", "5000"]
        .iter()
        .map(std::ffi::OsStr::new)
        .chain([
            "--save".as_ref(),
            agent.as_os_str(),
            "--json".as_ref(),
            json.as_os_str(),
        ])
        .collect();
    let (code, text) = ctrl_c_in_a_terminal(&args, &[("PPO_TUTOR_LANG", "en")], "Iteration 0")?;
    assert_eq!(code, 130, "{text}");
    // (The terminal may echo ^C before it.)
    let line = text
        .lines()
        .find_map(|l| l.find("stopped by Ctrl-C after ").map(|at| &l[at..]))
        .ok_or_else(|| format!("no message: {text}"))?;
    let done: usize = line
        .trim_start_matches("stopped by Ctrl-C after ")
        .split(' ')
        .next()
        .and_then(|n| n.parse().ok())
        .ok_or_else(|| format!("no episode count: {line}"))?;
    assert!((1..5000).contains(&done), "{line}");
    let (agent, json) = (agent.display(), json.display());
    assert!(
        line.contains(&format!(
            "of 5000 episodes; nothing was saved (--json {json}, --save {agent} not written)"
        )),
        "{line}"
    );
    assert_eq!(
        std::fs::read_dir(dir.path())?.count(),
        0,
        "a file was written"
    );
    Ok(())
}

/// Ctrl-C during `train --seeds`, whose seeds run on worker threads: the same message, in
/// the language asked for, and exit 130.
#[cfg(unix)]
#[test]
fn ctrl_c_stops_several_seeds_in_the_language_asked_for() -> TestResult {
    let args: Vec<&std::ffi::OsStr> = [
        "train",
        "--env",
        "Pendulum-v1",
        "--episodes",
        "5000",
        "--seeds",
        "0-1",
    ]
    .iter()
    .map(std::ffi::OsStr::new)
    .collect();
    let (code, text) = ctrl_c_in_a_terminal(&args, &[("PPO_TUTOR_LANG", "zh")], "所有随机种子")?;
    assert_eq!(code, 130, "{text}");
    assert!(
        text.contains("已按 Ctrl-C 中止：训练了 ")
            && text.contains("（共 10000 个）后停止；没有保存任何内容"),
        "{text}"
    );
    Ok(())
}

/// Grading the candle exercise when its file is missing announces no
/// candle build (nothing is built: the file is reported missing), in either language; and
/// `--time-limit 0` (an exercise that could never run) is refused by name.
#[test]
fn a_missing_candle_file_builds_nothing_and_time_limit_0_is_refused() -> TestResult {
    let dir = tempfile::tempdir()?;
    for lang in ["en", "zh"] {
        let out = sandboxed(dir.path())
            .args(["--lang", lang, "grade", "ppo_losses"])
            .current_dir(dir.path())
            .output()?;
        let err = String::from_utf8(out.stderr)?;
        assert_eq!(out.status.code(), Some(1), "{lang}: {err}");
        assert!(
            !err.contains("Compiling candle") && !err.contains("编译 candle"),
            "{lang}: a build is announced for a missing file: {err}"
        );
        assert!(
            err.contains("exercise_candle.rs"),
            "{lang}: the missing file is not named: {err}"
        );
        assert!(
            !dir.path().join("cache").join("ppo_losses").exists(),
            "{lang}: a grading project was set up for a missing file"
        );
    }
    for cmd in ["grade", "watch"] {
        let out = run(&[cmd, "compute_advantage", "--time-limit", "0"])?;
        let err = String::from_utf8(out.stderr)?;
        assert_eq!(out.status.code(), Some(2), "{cmd}: {err}");
        assert!(
            err.contains("--time-limit") && err.contains("at least 1"),
            "{cmd}: --time-limit 0 is not refused by name: {err}"
        );
    }
    Ok(())
}

/// `grade` with no name prints a score table whose columns line up on screen in both
/// languages (measured in display columns: a Chinese character takes two), without building
/// anything for starters that are still `todo!()` (the candle one included); `grade NAME
/// --file` of a file that does not exist says so and to check the path, not to reset the
/// lesson's file; and `grade --help` says where the cache is.
#[test]
fn the_score_table_lines_up_and_a_missing_file_is_named() -> TestResult {
    use unicode_width::UnicodeWidthStr;
    let dir = tempfile::tempdir()?;
    let ppo = |lang: &str, args: &[&str]| {
        sandboxed(dir.path())
            .args(["--lang", lang])
            .args(args)
            .current_dir(dir.path())
            .output()
    };
    assert_eq!(ppo("en", &["init"])?.status.code(), Some(0));
    for (lang, head) in [("en", "file"), ("zh", "文件")] {
        let out = ppo(lang, &["grade"])?;
        let table = String::from_utf8(out.stdout)?;
        assert_eq!(out.status.code(), Some(1), "{table}");
        let rows: Vec<&str> = table.lines().take_while(|l| !l.contains("score")).collect();
        let rows: Vec<&str> = rows
            .into_iter()
            .take_while(|l| !l.starts_with("得分"))
            .collect();
        // The column of the file and of the result, on screen, in the header and each row.
        let columns = |row: &str, file: &str| -> Option<(usize, usize)> {
            let at = row.find(file)?;
            let after = at + row[at..].find(' ')?;
            let result = after + row[after..].find(|c: char| c != ' ')?;
            Some((row[..at].width(), row[..result].width()))
        };
        let header = columns(rows[0], head).ok_or("no header")?;
        assert_eq!(
            rows.len(),
            ppo_tutor::grade::exercises().len() + 1,
            "{table}"
        );
        for row in &rows[1..] {
            assert_eq!(columns(row, "lessons/"), Some(header), "{lang}:\n{table}");
            assert!(row.contains("todo!()"), "{lang}: {row}");
        }
    }
    assert!(!dir.path().join("cache").exists(), "starters were built");

    for (lang, says) in [
        ("en", "does not exist: check the path"),
        ("zh", "不存在：请检查路径"),
    ] {
        let out = ppo(lang, &["grade", "reverse_kl", "--file", "/nonexistent.rs"])?;
        let err = String::from_utf8(out.stderr)?;
        assert_eq!(out.status.code(), Some(1), "{err}");
        assert!(
            err.contains("/nonexistent.rs") && err.contains(says),
            "{lang}: {err}"
        );
        assert!(!err.contains("reset"), "{lang}: {err}");
    }
    // The lesson's own file missing: reset writes it, --file grades another.
    std::fs::remove_file(dir.path().join("lessons/13-clip-lab/exercise.rs"))?;
    let err = String::from_utf8(ppo("en", &["grade", "reverse_kl"])?.stderr)?;
    assert!(
        err.contains("ppo-tutor reset reverse_kl") && err.contains("--file PATH"),
        "{err}"
    );
    for (lang, says) in [
        ("en", "PPO_TUTOR_GRADE_CACHE"),
        ("zh", "缓存在 $PPO_TUTOR_GRADE_CACHE"),
    ] {
        let help = String::from_utf8(ppo(lang, &["grade", "--help"])?.stdout)?;
        assert!(
            help.contains(says) && help.contains("ppo-tutor-grade"),
            "{lang}: {help}"
        );
    }
    Ok(())
}

/// `reset` of one exercise in a file that holds others restores only that
/// function, keeps the others' work, and keeps the old file as `.bak`, saying where.
#[test]
fn reset_restores_one_function_and_keeps_a_backup() -> TestResult {
    let dir = tempfile::tempdir()?;
    let reset = |name: &str| {
        sandboxed(dir.path())
            .args(["--lang", "en", "reset", name])
            .current_dir(dir.path())
            .output()
    };
    let out = reset("gae_rollout")?;
    assert_eq!(out.status.code(), Some(0), "{out:?}");
    let file = dir.path().join("lessons/16-beyond-the-seed/exercise.rs");
    let starter = std::fs::read_to_string(&file)?;
    // The learner's work in two of the file's functions.
    let mut mine = String::new();
    let mut rest = starter.as_str();
    for (name, marker) in [
        (
            "pub fn td_target_truncation(",
            "unimplemented!(\"mine: td_target_truncation\")",
        ),
        (
            "pub fn gae_rollout(",
            "unimplemented!(\"mine: gae_rollout\")",
        ),
    ] {
        let at = rest.find(name).ok_or(name)?;
        let todo = at + rest[at..].find("todo!()").ok_or("no todo!()")?;
        mine.push_str(&rest[..todo]);
        mine.push_str(marker);
        rest = &rest[todo + "todo!()".len()..];
    }
    mine.push_str(rest);
    std::fs::write(&file, &mine)?;

    let out = reset("gae_rollout")?;
    let said = String::from_utf8(out.stdout)?;
    assert_eq!(out.status.code(), Some(0), "{said}");
    let now = std::fs::read_to_string(&file)?;
    assert!(
        now.contains("mine: td_target_truncation"),
        "the other exercise's work was lost"
    );
    assert!(
        !now.contains("mine: gae_rollout"),
        "gae_rollout was not reset"
    );
    assert_eq!(
        now.matches("todo!()").count(),
        starter.matches("todo!()").count() - 1
    );
    let backup = dir
        .path()
        .join("lessons/16-beyond-the-seed/exercise.rs.bak");
    assert_eq!(std::fs::read_to_string(&backup)?, mine);
    assert!(
        said.contains("exercise.rs.bak") && said.contains("other exercises are kept"),
        "{said}"
    );
    Ok(())
}

/// `init DIR` writes every starter so the exercises can be done outside
/// the clone (keeping files already there), `watch` with no name skips missing files, and a
/// pass shows the embedded reference solution where no solution file exists.
#[test]
fn init_writes_every_starter_outside_the_clone() -> TestResult {
    let dir = tempfile::tempdir()?;
    let course = dir.path().join("course");
    let ppo = |args: &[&str], cwd: &std::path::Path| {
        sandboxed(dir.path())
            .args(["--lang", "en"])
            .args(args)
            .current_dir(cwd)
            .output()
    };
    let out = ppo(&["init", "course"], dir.path())?;
    let said = String::from_utf8(out.stdout)?;
    assert_eq!(out.status.code(), Some(0), "{said}");
    let repo = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut starters = 0;
    for lesson in std::fs::read_dir(repo.join("lessons"))? {
        let lesson = lesson?.path();
        for file in ["exercise.rs", "exercise_candle.rs"] {
            if lesson.join(file).exists() {
                let name = lesson.file_name().ok_or("no name")?;
                let written = course.join("lessons").join(name).join(file);
                assert_eq!(
                    std::fs::read_to_string(&written)?,
                    std::fs::read_to_string(lesson.join(file))?,
                    "{}",
                    written.display()
                );
                starters += 1;
            }
        }
    }
    assert!(
        said.contains(&format!("{starters} starters written, 0 kept")),
        "{said}"
    );
    // A second init keeps the learner's files.
    let td = course.join("lessons/08-gae/exercise.rs");
    let solution = std::fs::read_to_string(repo.join("lessons/08-gae/solution.rs"))?;
    std::fs::write(&td, &solution)?;
    let said = String::from_utf8(ppo(&["init", "course"], dir.path())?.stdout)?;
    assert!(
        said.contains(&format!("0 starters written, {starters} kept")),
        "{said}"
    );
    assert_eq!(std::fs::read_to_string(&td)?, solution);
    // Graded from there: a pass shows the reference itself (no solution.rs outside the clone).
    let out = ppo(&["grade", "compute_advantage"], &course)?;
    let said = String::from_utf8(out.stdout)?;
    assert_eq!(out.status.code(), Some(0), "{said}");
    assert!(
        said.contains("The reference solution:") && said.contains("pub fn compute_advantage("),
        "{said}"
    );
    // `init` into a file is a usage error.
    std::fs::write(dir.path().join("a-file"), "")?;
    let out = ppo(&["init", "a-file"], dir.path())?;
    assert_eq!(out.status.code(), Some(2), "{out:?}");
    Ok(())
}
