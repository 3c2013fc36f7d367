//! What the command line prints for a Chinese user, enumerated: for every leaf
//! subcommand of [`Cli`] a successful run and the error paths the English tests of this
//! binary exercise (bad values, refusals, missing and unreadable files), each run with
//! `--lang zh`, and every line it prints checked for English words
//! ([`english_words`]) outside code spans, identifiers, units and the reviewed names of
//! [`ppo_tutor::i18n::ALLOWED_WORDS`].
//!
//! The words the program's own identifiers allow are read from the program, not typed here
//! ([`allowed`]): subcommand names, argument ids, flags and possible values (walking
//! [`Cli::command`]), exercise names, lesson ids and the live values the lessons show, the
//! words of the code the lessons show (their Python and Rust without comments, and the code
//! spans of every `lesson.zh.md`: `show` prints a span without its backticks; for the runs
//! of `lessons` and `show` only), the lab's experiment names,
//! the checkpoints' algorithm names, and the files this test makes. Besides: what the user
//! typed, quoted back as typed (`'abc' 无效`); one-letter words, which are mathematical
//! variables (`s`, `t`, `x`, `‖g‖`), never English on their own, and `dt`, the time step
//! of the Pendulum lesson's formulas (written there as plain text, not as code); and
//! Gymnasium's observation name `theta`, a column of the CartPole and Pendulum tables (its
//! neighbours `x_dot`, `theta_dot` are identifiers by their underscore).
//!
//! Not checked, on purpose:
//! - machine output: `--json` on stdout and the JSON, SVG and safetensors files written
//!   (their keys are the fixtures' and Gymnasium's, not sentences); a run with `--json` on
//!   stdout has only its stderr checked;
//! - code: `show` prints the seed's PyTorch and the crate's Rust under `## …（PyTorch）` and
//!   `## ppo-rl (…)` or `## ppo-engine (…)`; those blocks run to the next `## ` section or step header and are
//!   dropped before checking ([`strip_code`]). A line that is a command to type (`cargo …`,
//!   `ppo-tutor …` alone on its line) is code too;
//! - drawings: the canvas of a terminal plot, right of its axis `|` (its markers `o`, `*`,
//!   `:`); the axis labels left of it are checked.
//!
//! `grade` prints a grader report (checks, failing input, hints): its run is checked like the
//! others, but the English in grader reports belongs to the grader crate (`ppo-grade`'s
//! `report.rs`), not to the command line.

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use std::process::Command;

use clap::CommandFactory as _;
use ppo_tutor::cli::Cli;
use ppo_tutor::cli::help_zh::identifiers;
use ppo_tutor::i18n::english_words;

use crate::common::with_env;

type TestResult = Result<(), Box<dyn std::error::Error>>;

/// Leaf subcommands no test runs, and why.
const NOT_RUN: &[(&str, &str)] = &[
    (
        "dev notebook-code",
        "rewrites tests/notebook_code/ in the checkout the binary was built from",
    ),
    (
        "dev notebook-markdown",
        "rewrites the notebooks' markdown cells in the checkout the binary was built from",
    ),
    (
        "dev screenshots",
        "redraws assets/screens/*.png in the checkout the binary was built from \
         (tests/cli/screenshots.rs draws the same pictures without writing them)",
    ),
    #[cfg(feature = "notebook-runner")]
    (
        "dev notebooks",
        "with the notebook runner built in (the full tier) it executes every notebook on \
         evcxr and rewrites them in the checkout",
    ),
];

/// Leaf subcommands that cannot succeed in a test's build, and why (their error is run).
#[cfg(not(feature = "notebook-runner"))]
const NO_SUCCESS: &[(&str, &str)] = &[(
    "dev notebooks",
    "needs the notebook-runner feature (evcxr): the default build says how to run it, exit 2",
)];
/// Leaf subcommands that cannot succeed in a test's build (none with the runner built in).
#[cfg(feature = "notebook-runner")]
const NO_SUCCESS: &[(&str, &str)] = &[];

/// What of a run's output is read.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Read {
    /// stdout and stderr.
    Both,
    /// stderr only: stdout is JSON.
    Stderr,
    /// both, without the code blocks `show` prints ([`strip_code`]).
    WithoutCode,
}

/// One invocation: the leaf subcommand, its arguments after it, the exit code it must give.
struct Case {
    leaf: &'static str,
    args: Vec<String>,
    code: i32,
    read: Read,
    cwd: Option<PathBuf>,
    env: Vec<(&'static str, String)>,
}

impl Case {
    fn new(leaf: &'static str, args: &[&str], code: i32) -> Self {
        Self {
            leaf,
            args: args.iter().map(ToString::to_string).collect(),
            code,
            read: Read::Both,
            cwd: None,
            env: Vec::new(),
        }
    }

    fn read(mut self, read: Read) -> Self {
        self.read = read;
        self
    }

    fn cwd(mut self, dir: &Path) -> Self {
        self.cwd = Some(dir.to_path_buf());
        self
    }

    fn env(mut self, key: &'static str, value: &Path) -> Self {
        self.env.push((key, value.display().to_string()));
        self
    }

    /// The command line after `ppo-tutor --lang zh`.
    fn line(&self) -> Vec<String> {
        let mut line: Vec<String> = self.leaf.split(' ').map(ToString::to_string).collect();
        line.extend(self.args.iter().cloned());
        line
    }
}

/// Every leaf subcommand of `cmd`, as its path (`train`, `dev notebooks`).
fn leaves(cmd: &clap::Command, prefix: &str, out: &mut Vec<String>) {
    for sub in cmd.get_subcommands() {
        let path = if prefix.is_empty() {
            sub.get_name().to_string()
        } else {
            format!("{prefix} {}", sub.get_name())
        };
        if sub.get_subcommands().next().is_none() {
            out.push(path);
        } else {
            leaves(sub, &path, out);
        }
    }
}

/// The words the program's own names allow (see the module doc), plus `files`, the names of
/// the files and folders this test made.
fn allowed(files: &[&str]) -> Result<BTreeSet<String>, Box<dyn std::error::Error>> {
    let mut allowed = BTreeSet::new();
    identifiers(&Cli::command(), &mut allowed);
    allowed.extend(
        ppo_tutor::grade::exercise_names()
            .into_iter()
            .map(ToString::to_string),
    );
    let course = ppo_tutor::lesson::Course::embedded()?;
    for lesson in &course.lessons {
        allowed.insert(lesson.id.clone());
        for step in &lesson.steps {
            allowed.extend(step.show.iter().cloned());
        }
    }
    allowed.extend(ppo_tutor::lesson::VIEWS.iter().map(ToString::to_string));
    allowed.extend(
        ppo_tutor::ppo::lab::Experiment::ALL
            .iter()
            .map(|e| e.name().to_string()),
    );
    for agent in ppo_tutor::run::AgentKind::ALL {
        allowed.insert(agent.checkpoint().algorithm.to_string());
    }
    allowed.extend(files.iter().map(ToString::to_string));
    // Mathematical variables: one letter, alone or as a norm.
    for c in ('a'..='z').chain('A'..='Z') {
        allowed.insert(c.to_string());
        allowed.insert(format!("‖{c}‖"));
    }
    allowed.extend(["dt", "theta"].map(String::from));
    Ok(allowed)
}

/// The words of the code the course shows, which `lessons` and `show` print as plain text
/// (titles such as `PolicyNet 与 ValueNet`, code spans without their backticks): the
/// steps' Python and Rust without comments, and the code spans of the Chinese lessons.
/// Only those two commands' runs allow them (spans hold words like `not` and `or`).
fn course_code_words() -> Result<BTreeSet<String>, Box<dyn std::error::Error>> {
    let course = ppo_tutor::lesson::Course::embedded()?;
    let mut allowed = BTreeSet::new();
    for lesson in &course.lessons {
        for step in &lesson.steps {
            allowed.extend(code_words(&without_comments(&step.python)));
            allowed.extend(code_words(&without_comments(&step.code)));
        }
    }
    let lessons = Path::new(env!("CARGO_MANIFEST_DIR")).join("lessons");
    for folder in std::fs::read_dir(lessons)? {
        let file = folder?.path().join("lesson.zh.md");
        if let Ok(text) = std::fs::read_to_string(&file) {
            for span in text.split('`').skip(1).step_by(2) {
                allowed.extend(code_words(span));
            }
        }
    }
    Ok(allowed)
}

/// `code` without its comments (from `//` or `#` to the end of a line): their English
/// words are prose, not code.
fn without_comments(code: &str) -> String {
    code.lines()
        .map(|line| {
            let end = [line.find("//"), line.find('#')]
                .into_iter()
                .flatten()
                .min()
                .unwrap_or(line.len());
            &line[..end]
        })
        .collect::<Vec<_>>()
        .join("\n")
}

/// The words of a piece of code: its runs of letters, digits and `_`.
fn code_words(code: &str) -> impl Iterator<Item = String> + '_ {
    code.split(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
        .filter(|w| !w.is_empty())
        .map(ToString::to_string)
}

/// `text` without the code blocks `show` prints: from a `## …（PyTorch）` or
/// `## ppo-rl (…)` or `## ppo-engine (…)` heading to the next `## ` section or step header (`# title — 第 n/m
/// 节`; a Python comment `# …` inside the code does not end the block).
fn strip_code(text: &str) -> String {
    let mut out = String::new();
    let mut in_code = false;
    for line in text.lines() {
        let section = line.starts_with("## ") || (line.starts_with("# ") && line.contains(" — "));
        if section {
            in_code = line.starts_with("## ppo-rl (")
                || line.starts_with("## ppo-engine (")
                || line.contains("（PyTorch）");
            if in_code {
                continue;
            }
        }
        if !in_code {
            out.push_str(line);
            out.push('\n');
        }
    }
    out
}

/// `text` without terminal escape sequences (`\x1b[3A`, colours).
fn strip_escapes(text: &str) -> String {
    let mut out = String::new();
    let mut chars = text.chars().peekable();
    while let Some(c) = chars.next() {
        if c == '\x1b' && chars.peek() == Some(&'[') {
            for d in chars.by_ref() {
                if d.is_ascii_alphabetic() {
                    break;
                }
            }
        } else {
            out.push(c);
        }
    }
    out
}

/// The file `starter` of `lesson` with the body of `function` (its first `todo!()`) replaced.
fn with_body(
    lesson: &str,
    starter: &str,
    function: &str,
    body: &str,
) -> Result<String, Box<dyn std::error::Error>> {
    let repo = Path::new(env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(repo.join("lessons").join(lesson).join(starter))?;
    let at = text
        .find(&format!("pub fn {function}("))
        .ok_or("no such function")?;
    let todo = at + text[at..].find("todo!()").ok_or("no todo!()")?;
    Ok(format!(
        "{}{body}{}",
        &text[..todo],
        &text[todo + "todo!()".len()..]
    ))
}

/// A CartPole checkpoint with one tensor of the wrong shape, one with a tensor missing, and a
/// file that is not a checkpoint.
fn bad_checkpoints(dir: &Path) -> Result<[PathBuf; 3], Box<dyn std::error::Error>> {
    let mut tensors = crate::common::cartpole_tensors_with_a_wrong_shape()?;
    let shape = dir.join("shape.safetensors");
    candle_core::safetensors::save(&tensors, &shape)?;
    tensors.remove("actor.fc2.bias");
    let missing = dir.join("missing.safetensors");
    candle_core::safetensors::save(&tensors, &missing)?;
    let garbage = dir.join("garbage.safetensors");
    std::fs::write(&garbage, "not a checkpoint")?;
    Ok([shape, missing, garbage])
}

/// Replay files: a case without `batch.rewards`, a bias of the wrong length, and a file
/// that is not JSON.
fn bad_replays(dir: &Path) -> Result<[PathBuf; 3], Box<dyn std::error::Error>> {
    let fixture = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/fixtures/ppo_update_pytorch.json"
    );
    let mut missing: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(fixture)?)?;
    let mut shape = missing.clone();
    missing["cases"][1]["batch"]
        .as_object_mut()
        .ok_or("no batch")?
        .remove("rewards");
    shape["cases"][0]["weights_before"]["actor.fc2.bias"] = serde_json::json!([0.0, 0.0, 0.0]);
    let paths = [
        dir.join("missing.json"),
        dir.join("shape.json"),
        dir.join("broken.json"),
    ];
    std::fs::write(&paths[0], missing.to_string())?;
    std::fs::write(&paths[1], shape.to_string())?;
    std::fs::write(&paths[2], "{\"cases\": [")?;
    Ok(paths)
}

/// The enumerated runs, in order (later runs read what earlier ones wrote), with the files
/// they need made under `dir`.
#[allow(clippy::too_many_lines)]
fn table(dir: &Path) -> Result<Vec<Case>, Box<dyn std::error::Error>> {
    use Read::{Stderr, WithoutCode};
    let p = |name: &str| dir.join(name).display().to_string();
    let fixtures = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/fixtures");
    let [shape_cp, missing_cp, garbage_cp] = bad_checkpoints(dir)?;
    let [missing_json, shape_json, broken_json] = bad_replays(dir)?;
    std::fs::create_dir_all(dir.join("a-folder"))?;
    std::fs::write(dir.join("a-file"), "")?;
    // grade: a classic mistake and the reference, as files to grade.
    let wrong = with_body(
        "08-gae",
        "exercise.rs",
        "compute_advantage",
        "td_delta.to_vec()",
    )?;
    std::fs::write(dir.join("wrong.rs"), wrong)?;
    let repo = Path::new(env!("CARGO_MANIFEST_DIR"));
    std::fs::copy(
        repo.join("lessons/08-gae/solution.rs"),
        dir.join("right.rs"),
    )?;
    // reset: a file holding the learner's work in one exercise (kept as .bak).
    let reset_dir = dir.join("reset-work");
    let file = reset_dir.join("lessons/16-beyond-the-seed/exercise.rs");
    std::fs::create_dir_all(file.parent().ok_or("no parent")?)?;
    let mine = with_body(
        "16-beyond-the-seed",
        "exercise.rs",
        "gae_rollout",
        "unimplemented!(\"mine\")",
    )?;
    std::fs::write(&file, mine)?;
    // init: a folder with one learner's file already there (kept).
    let init_dir = dir.join("init-kept");
    std::fs::create_dir_all(init_dir.join("lessons/08-gae"))?;
    std::fs::copy(
        repo.join("lessons/08-gae/solution.rs"),
        init_dir.join("lessons/08-gae/exercise.rs"),
    )?;
    // watch: a progress file where every exercise has passed, and an empty folder.
    let all_passed = dir.join("all-passed.json");
    std::fs::write(
        &all_passed,
        serde_json::json!({
            "exercises_done": ppo_tutor::grade::exercise_names(),
            "exercise_tasks": ppo_tutor::lesson::progress::EXERCISE_TASKS,
        })
        .to_string(),
    )?;
    let empty = dir.join("empty");
    std::fs::create_dir_all(&empty)?;
    let torques = vec!["0.1"; 205].join(",");
    let falls = vec!["0"; 30].join(",");

    let (cp, pd) = (p("agent.safetensors"), p("pendulum.safetensors"));
    let mut cases = vec![
        // cartpole
        Case::new(
            "cartpole",
            &["--seed", "0", "--actions", "0,1,1", "--resets", "1"],
            0,
        ),
        Case::new("cartpole", &["--seed", "0", "--actions", &falls], 0),
        Case::new(
            "cartpole",
            &["--seed", "0", "--actions", "0,1", "--render"],
            0,
        ),
        Case::new("cartpole", &["--policy", "lean", "--json"], 0).read(Stderr),
        Case::new(
            "cartpole",
            &["--env", "CartPole-v0", "--policy", "lean", "--seed", "5"],
            0,
        ),
        Case::new("cartpole", &["--env", "CartPole-v9", "--actions", "0"], 2),
        Case::new("cartpole", &["--actions", "0,x,1"], 2),
        Case::new("cartpole", &["--actions", "0,2"], 2),
        Case::new("cartpole", &["--seed", "abc", "--actions", "0"], 2),
        Case::new("cartpole", &["--seed", "-3", "--actions", "0"], 2),
        Case::new("cartpole", &["--resets", "-1", "--actions", "0"], 2),
        Case::new("cartpole", &["--seed", "1"], 2),
        Case::new("cartpole", &["--policy", "lea"], 2),
        Case::new("cartpole", &["--json", "--json"], 2),
        // pendulum
        Case::new(
            "pendulum",
            &["--seed", "0", "--actions=-0.5,1.25,3", "--resets", "1"],
            0,
        ),
        Case::new("pendulum", &["--actions", &torques, "--json"], 0).read(Stderr),
        Case::new("pendulum", &["--actions", "0.5,x"], 2),
        Case::new("pendulum", &["--actions=1,,2"], 2),
        Case::new("pendulum", &["--actions", "NaN"], 2),
        Case::new("pendulum", &["--actions=-inf"], 2),
        Case::new("pendulum", &["--actions", "1,2,1e999"], 2),
        Case::new("pendulum", &["--seed", "3"], 2),
        // lessons, show
        Case::new("lessons", &[], 0),
        Case::new("lessons", &["extra"], 2),
        Case::new("show", &["td-target"], 0).read(WithoutCode),
        Case::new("show", &["pendulum", "--step", "1"], 0).read(WithoutCode),
        Case::new("show", &["no-such-lesson"], 2),
        Case::new("show", &["td-target", "--step", "99"], 2),
        Case::new("show", &["td-target", "--step", "x"], 2),
        Case::new("show", &["td-target", "--step", "-1"], 2),
        Case::new("show", &["td-target", "--episodes", "0"], 2),
        Case::new("show", &[], 2),
        // train
        Case::new(
            "train",
            &[
                "--episodes",
                "3",
                "--seed",
                "4",
                "--json",
                &p("run.json"),
                "--save",
                &cp,
                "--plot",
                &p("returns.svg"),
            ],
            0,
        ),
        Case::new(
            "train",
            &[
                "--episodes",
                "4",
                "--seeds",
                "0-1",
                "--json",
                &p("seeds.json"),
                "--plot",
                &p("seeds.png"),
            ],
            0,
        ),
        Case::new(
            "train",
            &[
                "-q",
                "--env",
                "Pendulum-v1",
                "--episodes",
                "1",
                "--save",
                &pd,
            ],
            0,
        ),
        Case::new(
            "train",
            &["-q", "--episodes", "2", "--objective", "penalty"],
            0,
        ),
        Case::new(
            "train",
            &["-q", "--episodes", "2", "--objective", "line-search"],
            0,
        ),
        // Titled by what trained, with the moving average's window in the plot's legend.
        Case::new("train", &["--episodes", "3", "--algorithm", "reinforce"], 0),
        Case::new(
            "train",
            &["-q", "--episodes", "2", "--no-clip", "--seeds", "0-1"],
            0,
        ),
        Case::new("train", &["--seeds", "4-1"], 2),
        Case::new("train", &["--seeds", "0-2", "--seed", "3"], 2),
        Case::new("train", &["--seeds", "0,1", "--save", "a.safetensors"], 2),
        Case::new("train", &["--algorithm", "a2c"], 2),
        Case::new("train", &["--foo"], 2),
        Case::new("train", &["--env", "Acrobot-v1"], 2),
        Case::new("train", &["--episodes", "-5"], 2),
        Case::new("train", &["--epochs", "-1"], 2),
        Case::new("train", &["--eps", "abc"], 2),
    ];
    for (flag, value) in [
        ("--eps", "0"),
        ("--gamma", "1.5"),
        ("--actor-lr", "0"),
        ("--critic-lr", "-0.1"),
        ("--episodes", "0"),
    ] {
        cases.push(Case::new("train", &[flag, value], 2));
    }
    for refused in [
        &["--kl-delta", "0.02"][..],
        &["--objective", "penalty", "--algorithm", "reinforce"],
        &["--objective", "penalty", "--no-clip"],
        &["--objective", "penalty", "--beta-init", "0"],
        &["--env", "Pendulum-v1", "--objective", "penalty"],
        &["--ls-max-step", "0.5"],
        &["--objective", "penalty", "--ls-backtracks", "3"],
        &["--objective", "line-search", "--beta-init", "2"],
        &["--objective", "line-search", "--algorithm", "reinforce"],
        &["--objective", "line-search", "--no-clip"],
        &["--objective", "line-search", "--ls-max-step", "0"],
        &["--objective", "line-search", "--ls-backtracks", "51"],
        &["--objective", "line-search", "--entropy-coef", "0.01"],
        &["--env", "Pendulum-v1", "--lmbda", "1.5"],
        &["--env", "Pendulum-v1", "--normalize-advantage"],
        &["--env", "Pendulum-v1", "--bootstrap-truncation"],
        &["--env", "Pendulum-v1", "--entropy-coef", "0.01"],
        &["--env", "Pendulum-v1", "--max-grad-norm", "0.5"],
        &["--env", "Pendulum-v1", "--target-kl", "0.02"],
        &["--env", "Pendulum-v1", "--no-clip"],
        &["--env", "Pendulum-v1", "--critic-epochs", "1"],
        &["--env", "Pendulum-v1", "--algorithm", "reinforce"],
    ] {
        let mut args = vec!["--episodes", "1"];
        args.extend_from_slice(refused);
        cases.push(Case::new("train", &args, 2));
    }
    let mut bad_outputs = vec![
        ("--plot", p("out.xyz")),
        ("--plot", p("out")),
        ("--plot", p("no/such/dir/out.png")),
        ("--save", p("no/such/agent.safetensors")),
        ("--save", p("a-folder")),
        ("--save", p("agent.bin")),
        ("--json", p("no/such/run.json")),
    ];
    // A folder that takes no new file, even for root.
    #[cfg(target_os = "linux")]
    bad_outputs.extend([
        ("--save", "/proc/x.safetensors".to_string()),
        ("--plot", "/proc/x.svg".to_string()),
    ]);
    for (flag, path) in &bad_outputs {
        cases.push(Case::new(
            "train",
            &["--episodes", "1", "-q", flag, path],
            2,
        ));
        if *flag != "--save" {
            cases.push(Case::new(
                "lab",
                &["eps", "--episodes", "1", "-q", flag, path],
                2,
            ));
        }
    }
    cases.extend([
        // lab
        Case::new("lab", &[], 0),
        Case::new(
            "lab",
            &[
                "reinforce",
                "--episodes",
                "4",
                "--seeds",
                "0-1",
                "--json",
                &p("lab.json"),
                "--plot",
                &p("lab.svg"),
            ],
            0,
        ),
        Case::new(
            "lab",
            &["proximal", "--episodes", "2", "--seeds", "0", "-q"],
            0,
        ),
        Case::new("lab", &["clip"], 2),
        Case::new("lab", &["eps", "--seeds", "2-1"], 2),
        // trust-region
        Case::new(
            "trust-region",
            &[
                "--train-episodes",
                "5",
                "--eval-episodes",
                "6",
                "--steps",
                "0,0.1,1.6",
                "--seed",
                "2",
            ],
            0,
        ),
        Case::new(
            "trust-region",
            &[
                "--train-episodes",
                "3",
                "--eval-episodes",
                "2",
                "--steps",
                "0,0.1",
                "--json",
            ],
            0,
        )
        .read(Stderr),
        Case::new("trust-region", &["--steps", "0,x"], 2),
        Case::new("trust-region", &["--eval-episodes", "1"], 2),
        Case::new("trust-region", &["--train-episodes", "0"], 2),
        // play (the checkpoints `train` wrote above)
        Case::new(
            "play",
            &["--load", &cp, "--episodes", "2", "--no-render"],
            0,
        ),
        Case::new("play", &["--load", &pd, "--no-render"], 0),
        Case::new("play", &["--load", &pd, "--env", "CartPole-v1"], 2),
        Case::new(
            "play",
            &["--load", &shape_cp.display().to_string(), "--no-render"],
            1,
        ),
        Case::new(
            "play",
            &["--load", &missing_cp.display().to_string(), "--no-render"],
            1,
        ),
        Case::new(
            "play",
            &["--load", &garbage_cp.display().to_string(), "--no-render"],
            1,
        ),
        Case::new(
            "play",
            &["--load", &p("no-such.safetensors"), "--no-render"],
            1,
        ),
        Case::new("play", &[], 2),
        Case::new("play", &["--load", &cp, "--delay-ms", "-5"], 2),
        // replay
        Case::new(
            "replay",
            &[&format!("{fixtures}/ppo_update_pytorch.json")],
            0,
        ),
        Case::new(
            "replay",
            &[&format!("{fixtures}/ppo_penalty_update_pytorch.json")],
            0,
        ),
        Case::new(
            "replay",
            &[&format!("{fixtures}/ppo_continuous_update_pytorch.json")],
            0,
        ),
        Case::new(
            "replay",
            &[&format!("{fixtures}/ppo_update_pytorch.json"), "--json"],
            0,
        )
        .read(Stderr),
        Case::new(
            "replay",
            &[&missing_json.display().to_string(), "--json"],
            1,
        ),
        Case::new("replay", &[&shape_json.display().to_string()], 1),
        Case::new("replay", &[&broken_json.display().to_string()], 1),
        Case::new("replay", &[&p("no-such.json")], 1),
        Case::new("replay", &[], 2),
        // grade (the report's own words are the grader's)
        Case::new("grade", &["compute_advantage", "--file", &p("wrong.rs")], 1).cwd(dir),
        Case::new("grade", &["compute_advantage", "--file", &p("right.rs")], 0).cwd(dir),
        Case::new("grade", &["ppo_losses"], 1).cwd(&empty),
        Case::new(
            "grade",
            &["compute_advantage", "--file", &p("no-such.rs")],
            1,
        )
        .cwd(dir),
        Case::new("grade", &[], 1).cwd(&empty),
        Case::new("grade", &["no_such_exercise"], 2),
        Case::new("grade", &["--file", &p("wrong.rs")], 2),
        Case::new("grade", &["compute_advantage", "--time-limit", "0"], 2),
        // watch
        Case::new("watch", &[], 0).env("PPO_TUTOR_STATE", &all_passed),
        Case::new("watch", &[], 1).cwd(&empty),
        Case::new("watch", &["compute_advantage"], 1).cwd(&empty),
        Case::new("watch", &["no_such_exercise"], 2),
        Case::new("watch", &["compute_advantage", "--time-limit", "0"], 2),
        // reset
        Case::new("reset", &["gae_rollout"], 0).cwd(&reset_dir),
        Case::new("reset", &["compute_advantage"], 0).cwd(&reset_dir),
        Case::new("reset", &["no_such_exercise"], 2),
        Case::new("reset", &[], 2),
        // init
        Case::new("init", &["course"], 0).cwd(dir),
        Case::new("init", &[], 0).cwd(&init_dir),
        Case::new("init", &["a-file"], 2).cwd(dir),
    ]);
    // dev (hidden): without the notebook runner it refuses and says how to run it; with it
    // (the full tier) it would execute and rewrite every notebook, so it is not run.
    #[cfg(not(feature = "notebook-runner"))]
    cases.push(Case::new("dev notebooks", &[], 2));
    Ok(cases)
}

/// Every leaf subcommand has a run in the table, and a successful one unless [`NO_SUCCESS`]
/// says why not; [`NOT_RUN`] and [`NO_SUCCESS`] name only leaves that exist.
#[test]
fn the_table_covers_every_subcommand() -> TestResult {
    let mut all = Vec::new();
    leaves(&Cli::command(), "", &mut all);
    assert!(all.contains(&"train".to_string()) && all.contains(&"dev notebooks".to_string()));
    let dir = tempfile::tempdir()?;
    let cases = table(dir.path())?;
    let mut missing = Vec::new();
    for leaf in &all {
        if NOT_RUN.iter().any(|(l, _)| l == leaf) {
            continue;
        }
        let runs: Vec<&Case> = cases.iter().filter(|c| c.leaf == leaf).collect();
        if runs.is_empty() {
            missing.push(format!("{leaf}: no run"));
        } else if !runs.iter().any(|c| c.code == 0) && !NO_SUCCESS.iter().any(|(l, _)| l == leaf) {
            missing.push(format!("{leaf}: no successful run"));
        }
    }
    for (leaf, _) in NOT_RUN.iter().chain(NO_SUCCESS) {
        if !all.iter().any(|l| l == leaf) {
            missing.push(format!("{leaf}: listed, but not a subcommand"));
        }
    }
    for case in &cases {
        if !all.iter().any(|l| l == case.leaf) {
            missing.push(format!("{}: in the table, but not a subcommand", case.leaf));
        }
    }
    assert!(
        missing.is_empty(),
        "the table of zh_output.rs: {missing:#?}"
    );
    Ok(())
}

/// Every enumerated run, in Chinese, gives its exit code and prints no English word.
#[test]
fn every_enumerated_output_is_chinese() -> TestResult {
    let dir = tempfile::tempdir()?;
    let cases = table(dir.path())?;
    let allowed = allowed(&[
        "a-file",
        "a-folder",
        "course",
        "reset-work",
        "init-kept",
        "empty",
    ])?;
    let course_words = course_code_words()?;
    let mut failures = Vec::new();
    for case in &cases {
        let mut cmd: Command = with_env(&[("NO_COLOR", "1"), ("RAYON_NUM_THREADS", "1")]);
        cmd.env("PPO_TUTOR_STATE", dir.path().join("state.json"))
            .env("PPO_TUTOR_GRADE_CACHE", dir.path().join("cache"))
            .current_dir(case.cwd.as_deref().unwrap_or(dir.path()));
        for (key, value) in &case.env {
            cmd.env(key, value);
        }
        let line = case.line();
        let out = cmd.arg("--lang").arg("zh").args(&line).output()?;
        let (stdout, stderr) = (
            String::from_utf8_lossy(&out.stdout).into_owned(),
            String::from_utf8_lossy(&out.stderr).into_owned(),
        );
        if out.status.code() != Some(case.code) {
            failures.push(format!(
                "{line:?}: exit {:?}, expected {}\n{stdout}\n{stderr}",
                out.status.code(),
                case.code
            ));
            continue;
        }
        let read = match case.read {
            Read::Both => format!("{stdout}\n{stderr}"),
            Read::Stderr => stderr,
            Read::WithoutCode => format!("{}\n{stderr}", strip_code(&stdout)),
        };
        // What the user typed is quoted back as typed.
        let mut typed = allowed.clone();
        if matches!(case.leaf, "lessons" | "show") {
            typed.extend(course_words.iter().cloned());
        }
        for arg in &line {
            typed.insert(arg.clone());
            typed.extend(arg.split([',', '=']).map(ToString::to_string));
        }
        for text in strip_escapes(&read).lines() {
            let trimmed = text.trim_start();
            if trimmed.starts_with("cargo ") || trimmed.starts_with("ppo-tutor ") {
                continue;
            }
            // A plot's canvas: right of the axis, after a blank or numeric label.
            let text = match text.split_once('|') {
                Some((label, _))
                    if label.trim().is_empty() || label.trim().parse::<f64>().is_ok() =>
                {
                    label
                }
                _ => text,
            };
            let words = english_words(text, &typed);
            if !words.is_empty() {
                failures.push(format!("{line:?}: English {words:?} in: {text}"));
            }
        }
    }
    assert!(
        failures.is_empty(),
        "{} problems:\n{}",
        failures.len(),
        failures.join("\n")
    );
    Ok(())
}

/// The helpers the check relies on can fail: code blocks are dropped up to the next
/// section (not at a Python comment), escapes are removed, English is found.
#[test]
fn the_filters_drop_only_code() {
    let show = "# 课 — 第 1/2 节：标题\n\n正文\n\n## 原教程代码（PyTorch）\n# 注释 comment\nx = torch.clamp(a)\n\n## ppo-rl (crates/x.rs)\nfn main() {}\n## values [3]\n  [0] 1.0\n";
    let kept = strip_code(show);
    assert!(
        kept.contains("正文") && kept.contains("## values [3]"),
        "{kept}"
    );
    assert!(
        !kept.contains("clamp") && !kept.contains("comment") && !kept.contains("fn main"),
        "{kept}"
    );
    assert_eq!(strip_escapes("\x1b[10A第 1 步"), "第 1 步");
    assert_eq!(
        code_words("self.actor = PolicyNet(sd, hd)").collect::<Vec<_>>(),
        ["self", "actor", "PolicyNet", "sd", "hd"]
    );
    assert_eq!(
        without_comments("x = 1  # the rest\n/// The critic\nlet y = 2; // note"),
        "x = 1  \n\nlet y = 2; "
    );
    let none = BTreeSet::new();
    assert_eq!(
        english_words("错误：file not found", &none),
        ["file", "not", "found"]
    );
}
