//! The course's content check: every lesson parses, references real code and live
//! values, and the headless commands print it.

use std::collections::BTreeSet;
use std::process::Command;

use ppo_tutor::lesson::{AgentKind, Course, VIEWS, anchor, live};

type TestResult = Result<(), Box<dyn std::error::Error>>;

#[test]
fn the_course_is_complete_and_consistent() -> TestResult {
    let course = Course::embedded()?;
    assert_eq!(course.lessons.len(), 18, "the outline has 18 lessons");
    let orders: Vec<u32> = course.lessons.iter().map(|l| l.order).collect();
    assert_eq!(orders, (1..=18).collect::<Vec<_>>());
    // A course's order: the environment and the loop before the networks, the derivation
    // before the mechanics, the lab after them, the recap of settings near the end.
    let ids: Vec<&str> = course.lessons.iter().map(|l| l.id.as_str()).collect();
    assert_eq!(
        ids,
        [
            "what-is-ppo",
            "cartpole",
            "episode-loop",
            "policy-gradient",
            "networks",
            "adam",
            "td-target",
            "gae",
            "ratio",
            "trust-region",
            "clipping",
            "losses",
            "clip-lab",
            "training",
            "hyperparameters",
            "beyond-the-seed",
            "continuous-actions",
            "pendulum"
        ]
    );
    // The last two lessons run the book's PPOContinuous on Pendulum, the rest CartPole.
    for l in &course.lessons {
        let pendulum = ["continuous-actions", "pendulum"].contains(&l.id.as_str());
        assert_eq!(l.env == AgentKind::Pendulum, pendulum, "{}: env", l.id);
    }
    let unique: BTreeSet<&str> = ids.iter().copied().collect();
    assert_eq!(unique.len(), course.lessons.len(), "ids are unique");
    for l in &course.lessons {
        assert!(
            !l.title.is_empty() && !l.summary.is_empty(),
            "{}: title and summary",
            l.id
        );
        assert!(l.steps.len() >= 3, "{}: at least three steps", l.id);
        for (i, s) in l.steps.iter().enumerate() {
            assert!(
                s.body.split_whitespace().count() >= 40,
                "{} step {}: body too short",
                l.id,
                i + 1
            );
            if !s.code.is_empty() {
                assert!(
                    anchor::find(&s.code).is_some(),
                    "{} step {}: anchor {}",
                    l.id,
                    i + 1,
                    s.code
                );
            }
            for name in &s.show {
                assert!(
                    live::is_known(name) || VIEWS.contains(&name.as_str()),
                    "{}: {name}",
                    l.id
                );
            }
        }
    }
    Ok(())
}

#[test]
fn anchors_are_unique_and_the_required_ones_exist() {
    let all = anchor::all();
    let unique: BTreeSet<&String> = all.iter().collect();
    assert_eq!(
        unique.len(),
        all.len(),
        "an anchor is defined twice: {all:?}"
    );
    for name in [
        "physics",
        "termination",
        "reset_seed",
        "env_step",
        "hyper",
        "td_target",
        "compute_advantage",
        "ratio",
        "surrogate",
        "actor_loss",
        "critic_loss",
        "moving_average",
    ] {
        assert!(anchor::find(name).is_some(), "missing anchor {name}");
    }
}

#[test]
fn a_broken_lesson_is_reported_with_its_folder_and_step() {
    let text = "+++\nid = \"x\"\ntitle = \"X\"\n[[steps]]\ntitle = \"A\"\ncode = \"no_such_anchor\"\n+++\n## A\nbody\n";
    let err = ppo_tutor::lesson::loader::parse_lesson("01-x", text)
        .err()
        .map(|e| e.to_string())
        .unwrap_or_default();
    assert!(
        err.contains("lessons/01-x") && err.contains("step 1") && err.contains("no_such_anchor"),
        "{err}"
    );
    let err = ppo_tutor::lesson::loader::parse_lesson("01-y", text)
        .err()
        .map(|e| e.to_string())
        .unwrap_or_default();
    assert!(err.contains("slug"), "{err}");
    let mismatch = "+++\nid = \"x\"\ntitle = \"X\"\n[[steps]]\ntitle = \"A\"\n+++\n## B\nbody\n";
    let err = ppo_tutor::lesson::loader::parse_lesson("01-x", mismatch)
        .err()
        .map(|e| e.to_string())
        .unwrap_or_default();
    assert!(err.contains("heading"), "{err}");
}

#[test]
fn details_and_lab_steps_are_checked_where_they_are_written() -> TestResult {
    use ppo_tutor::lesson::loader::parse_lesson;
    let err_of = |text: &str| {
        parse_lesson("02-x", text)
            .err()
            .map(|e| e.to_string())
            .unwrap_or_default()
    };
    let head = "+++\nid = \"x\"\ntitle = \"X\"\n[[steps]]\ntitle = \"A\"\n";
    let unclosed = format!("{head}+++\n## A\nbody\n<details><summary>S</summary>\nmore\n");
    let err = err_of(&unclosed);
    assert!(
        err.contains("lessons/02-x") && err.contains("step 1") && err.contains("not closed"),
        "{err}"
    );
    let bad_lab = format!("{head}lab = \"clipping\"\nshow = [\"lab\"]\n+++\n## A\nbody\n");
    let err = err_of(&bad_lab);
    assert!(err.contains("lab experiment 'clipping'"), "{err}");
    let lab_unshown = format!("{head}lab = \"eps\"\n+++\n## A\nbody\n");
    assert!(err_of(&lab_unshown).contains("must show \"lab\""));
    let shown_alone = format!("{head}show = [\"lab\"]\n+++\n## A\nbody\n");
    assert!(err_of(&shown_alone).contains("must show \"lab\""));
    let good = format!(
        "{head}lab = \"eps\"\nshow = [\"lab\"]\n+++\n## A\nbody\n<details><summary>S</summary>\n\nmore\n\n</details>\n"
    );
    let lesson = parse_lesson("02-x", &good).map_err(|e| e.to_string());
    assert_eq!(
        lesson.map(|l| l.steps[0].lab.map(|e| e.name())),
        Ok(Some("eps"))
    );
    // A prediction asks about the step's experiment and hides what the run found.
    let lab = "lab = \"eps\"\nshow = [\"lab\"]\n";
    let unknown = format!("{head}{lab}predict = \"ends_best\"\n+++\n## A\nbody\n");
    assert!(
        err_of(&unknown).contains("prediction"),
        "{}",
        err_of(&unknown)
    );
    let no_lab = format!("{head}predict = \"ends_highest\"\n+++\n## A\nbody\n");
    assert!(err_of(&no_lab).contains("add `lab"), "{}", err_of(&no_lab));
    let unhidden = format!("{head}{lab}predict = \"ends_highest\"\n+++\n## A\nbody\n");
    assert!(
        err_of(&unhidden).contains("<!-- after the run -->"),
        "{}",
        err_of(&unhidden)
    );
    let stray = format!("{head}+++\n## A\nbody\n<!-- after the run -->\nfound\n");
    assert!(
        err_of(&stray).contains("only such a step"),
        "{}",
        err_of(&stray)
    );
    let hidden = format!(
        "{head}{lab}predict = \"ends_lowest\"\n+++\n## A\nbefore\n<!-- after the run -->\nfound\n"
    );
    let step = parse_lesson("02-x", &hidden)
        .map_err(|e| e.to_string())?
        .steps[0]
        .clone();
    assert_eq!(
        step.parts(ppo_tutor::lesson::face::Face::Terminal),
        ("before\n".to_string(), Some("found".to_string()))
    );
    assert_eq!(
        step.text(ppo_tutor::lesson::face::Face::Terminal),
        "before\nfound"
    );
    Ok(())
}

/// Every experiment of the course asks for a prediction before it runs, and no figure of
/// what its seeds showed stands before that point, in either language or face.
#[test]
fn every_experiment_is_predicted_before_its_results_show() -> TestResult {
    use ppo_tutor::i18n::Lang;
    use ppo_tutor::lesson::face::Face;
    for lang in [Lang::En, Lang::Zh] {
        let course = Course::embedded_in(lang)?;
        let mut asked = 0;
        for lesson in &course.lessons {
            for step in lesson.steps.iter().filter(|s| s.lab.is_some()) {
                let place = format!("{lang:?} lesson {} '{}'", lesson.order, step.title);
                assert!(step.predict.is_some(), "{place}: no prediction");
                for face in Face::ALL {
                    let (before, after) = step.parts(face);
                    assert!(
                        after.is_some_and(|a| a.contains('±')),
                        "{place}: no results after the line"
                    );
                    for figure in ["±", "495.5", "488.3"] {
                        assert!(
                            !before.contains(figure),
                            "{place} ({face:?}): '{figure}' before the prediction"
                        );
                    }
                }
                asked += 1;
            }
        }
        assert_eq!(
            asked, 10,
            "{lang:?}: the ten experiments of lessons 4, 10, 13 and 15"
        );
    }
    Ok(())
}

#[test]
fn face_passages_are_checked_where_they_are_written() {
    use ppo_tutor::lesson::loader::parse_lesson;
    let err_of = |body: &str| {
        let text = format!(
            "+++\nid = \"x\"\ntitle = \"X\"\n[[steps]]\ntitle = \"A\"\n[[steps]]\ntitle = \"B\"\n+++\n## A\nfine\n## B\n{body}\n"
        );
        parse_lesson("03-x", &text)
            .err()
            .map(|e| e.to_string())
            .unwrap_or_default()
    };
    for (body, says) in [
        ("Run it<app> with x.", "not closed"),
        ("<notebook>\nRun the next cell.\n", "not closed"),
        ("a <app>b <app>c</app></app>", "inside"),
        ("a</notebook>", "closes no"),
        ("<app>a</notebook>", "closes no"),
        // A details block cut in two by a passage is malformed in one face.
        (
            "<app>\n<details><summary>S</summary>\n</app>\nx\n</details>",
            "closes no block",
        ),
    ] {
        let err = err_of(body);
        assert!(
            err.contains("lessons/03-x/lesson.md") && err.contains("step 2") && err.contains(says),
            "{body:?}: {err}"
        );
    }
    assert_eq!(
        err_of("Run it<app> with `x`</app><notebook> below</notebook>."),
        ""
    );
}

/// What a step says in a notebook fits a notebook: nothing about panels, the sandbox, keys
/// to press or text beside it; and the terminal's text says nothing about cells. A single
/// character in backticks is a key, unless the step's seed Python names a variable so (the
/// peer program's dict `d`).
#[test]
fn each_face_speaks_of_what_it_has() -> TestResult {
    use ppo_tutor::lesson::face::Face;
    let course = Course::embedded()?;
    let mut problems = Vec::new();
    for l in &course.lessons {
        for (i, s) in l.steps.iter().enumerate() {
            let at = format!("lessons/{:02}-{}/lesson.md, step {}", l.order, l.id, i + 1);
            let notebook = s.text(Face::Notebook);
            for word in app_only(&notebook, &s.python) {
                problems.push(format!("{at}, notebook face: {word}"));
            }
            let terminal = s.text(Face::Terminal);
            for word in words(&terminal) {
                if ["notebook", "notebooks", "cell", "cells", "jupyter"].contains(&word.as_str()) {
                    problems.push(format!("{at}, terminal face: '{word}'"));
                }
            }
        }
    }
    assert!(
        problems.is_empty(),
        "wrap app-only text in <app>...</app> and give the notebook its own words in \
         <notebook>...</notebook> (crates/ppo-engine/src/lesson/face.rs):\n{}",
        problems.join("\n")
    );
    Ok(())
}

/// The lower-case words of `text` (letters and digits).
fn words(text: &str) -> Vec<String> {
    text.split(|c: char| !c.is_alphanumeric())
        .filter(|w| !w.is_empty())
        .map(str::to_lowercase)
        .collect()
}

/// The app-only words and key instructions in `text`, a step's notebook face; `python` is
/// the step's seed code, whose one-letter names may appear in backticks.
fn app_only(text: &str, python: &str) -> Vec<String> {
    let mut found = Vec::new();
    for word in words(text) {
        if [
            "panel", "panels", "sandbox", "press", "presses", "pressed", "pressing",
        ]
        .contains(&word.as_str())
        {
            found.push(format!("'{word}'"));
        }
    }
    let lower = text.to_lowercase();
    for phrase in [
        "beside this text",
        "on screen",
        "in the app",
        "the app shows",
        "the tutor shows",
        "(enter)",
        "(esc)",
    ] {
        if lower.contains(phrase) {
            found.push(format!("'{phrase}'"));
        }
    }
    let names: Vec<&str> = python
        .split(|c: char| !(c.is_alphanumeric() || c == '_'))
        .collect();
    let chars: Vec<char> = text.chars().collect();
    for w in chars.windows(3) {
        // `x`: one character in backticks, not a name from the seed's code.
        if w[0] == '`'
            && w[2] == '`'
            && w[1].is_ascii_graphic()
            && w[1] != '`'
            && !names.contains(&w[1].to_string().as_str())
        {
            found.push(format!("the key `{}`", w[1]));
        }
    }
    for w in chars.windows(4) {
        // " (s)": one key in parentheses after a space, as keys are written; a function's
        // argument, V(s), has no space, and a symbol, gamma (γ), is not a key.
        if w[0].is_whitespace() && w[1] == '(' && w[3] == ')' && w[2].is_ascii_graphic() {
            found.push(format!("the key ({})", w[2]));
        }
    }
    found
}

#[test]
fn the_face_check_finds_app_only_words() {
    assert!(
        app_only(
            "Run the next cell; V(s) and π(a|s) are fine, as is `d`.",
            "d = {}"
        )
        .is_empty()
    );
    for (text, word) in [
        ("The hyper panel shows it.", "'panel'"),
        ("Open the Sandbox.", "'sandbox'"),
        ("Press x here.", "'press'"),
        ("The values beside this text.", "'beside this text'"),
        ("Retrain (Enter) now.", "'(enter)'"),
        ("Open it with `s`.", "the key `s`"),
        ("Open the sandbox (s) now.", "the key (s)"),
    ] {
        assert!(app_only(text, "").contains(&word.to_string()), "{text}");
    }
    // The words around it are not the word.
    assert!(app_only("Express it; compress it; the expanel; gamma (γ).", "").is_empty());
}

#[test]
fn a_broken_exercise_file_is_reported_with_its_folder_and_key() {
    use ppo_tutor::lesson::loader::parse_exercises;
    let typo = "[[exercise]]\nname = \"f\"\nfallbak = \"a typo\"\n";
    let err = parse_exercises("07-x", typo)
        .err()
        .map(|e| e.to_string())
        .unwrap_or_default();
    assert!(
        err.contains("lessons/07-x/exercise.toml") && err.contains("fallbak"),
        "{err}"
    );
    let good = "[[exercise]]\nname = \"f\"\nfallback = \"look again\"\n\n[exercise.mistakes]\nsign = \"The sign: ...\"\n";
    let texts = parse_exercises("07-x", good).unwrap_or_default();
    assert_eq!(texts.len(), 1);
    assert_eq!(
        texts[0].mistakes.get("sign").map(String::as_str),
        Some("The sign: ...")
    );
}

/// The lessons' exercises come from their `exercise.toml`: names in the lesson's order and
/// the hints of every function, one after another.
#[test]
fn a_lesson_s_exercise_comes_from_its_exercise_file() -> Result<(), Box<dyn std::error::Error>> {
    let course = Course::embedded()?;
    let lesson = course.get("losses").ok_or("no losses lesson")?;
    let exercise = lesson.exercise.as_ref().ok_or("no exercise")?;
    assert_eq!(exercise.names(), ["clipped_value_loss", "ppo_losses"]);
    let files = ppo_tutor::lesson::loader::embedded_exercises()?;
    let (_, texts) = files
        .iter()
        .find(|(dir, _)| dir == "12-losses")
        .ok_or("no 12-losses/exercise.toml")?;
    let hints: Vec<&String> = texts.iter().flat_map(|t| &t.hints).collect();
    assert_eq!(exercise.hints.iter().collect::<Vec<_>>(), hints);
    Ok(())
}

fn run(args: &[&str]) -> std::io::Result<std::process::Output> {
    Command::new(env!("CARGO_BIN_EXE_ppo-tutor"))
        .args(args)
        .output()
}

#[test]
fn lessons_command_lists_id_tab_title_in_order() -> TestResult {
    let course = Course::embedded()?;
    let out = run(&["lessons"])?;
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout)?;
    let want: Vec<String> = course
        .lessons
        .iter()
        .map(|l| format!("{}\t{}", l.id, l.title))
        .collect();
    assert_eq!(text.lines().collect::<Vec<_>>(), want);
    Ok(())
}

/// Reads the rows printed under `## name ...` by `show`.
fn column(text: &str, name: &str) -> Vec<f64> {
    text.lines()
        .skip_while(|l| !l.starts_with(&format!("## {name} ")))
        .skip(1)
        .take_while(|l| l.starts_with("  ["))
        .filter_map(|l| l.split_whitespace().nth(1)?.parse().ok())
        .collect()
}

#[test]
fn show_prints_live_values_that_obey_the_td_target_formula() -> TestResult {
    let out = run(&["show", "td-target", "--step", "2", "--episodes", "2"])?;
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8(out.stdout)?;
    assert!(text.contains("The TD target"), "{text}");
    let (r, v, d, y) = (
        column(&text, "rewards"),
        column(&text, "next_values"),
        column(&text, "dones"),
        column(&text, "td_target"),
    );
    assert!(
        !y.is_empty() && y.len() == r.len() && y.len() == v.len() && y.len() == d.len(),
        "{text}"
    );
    for i in 0..y.len() {
        let want = r[i] + 0.98 * v[i] * (1.0 - d[i]);
        assert!((want - y[i]).abs() < 1e-5, "row {i}: {want} vs {}", y[i]);
    }
    Ok(())
}

#[test]
fn show_runs_a_pendulum_lesson_on_pendulum() -> TestResult {
    let out = run(&[
        "show",
        "continuous-actions",
        "--step",
        "1",
        "--episodes",
        "1",
    ])?;
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8(out.stdout)?;
    assert!(text.contains("## mu (200, 1) float32"), "{text}");
    let sigma = column(&text, "std");
    assert!(
        !sigma.is_empty() && sigma.iter().all(|s| *s > 0.0),
        "{text}"
    );
    Ok(())
}

#[test]
fn show_rejects_unknown_lessons_and_steps() -> TestResult {
    for args in [
        &["show", "no-such-lesson"][..],
        &["show", "gae", "--step", "99"][..],
    ] {
        let out = run(args)?;
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        let err = String::from_utf8(out.stderr)?;
        assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    }
    Ok(())
}

#[test]
fn without_a_terminal_the_tutor_says_so_in_one_line() -> TestResult {
    let out = Command::new(env!("CARGO_BIN_EXE_ppo-tutor"))
        .stdin(std::process::Stdio::null())
        .output()?;
    assert!(!out.status.success());
    let err = String::from_utf8(out.stderr)?;
    assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    assert!(
        err.contains("ppo-tutor lessons") && err.contains("ppo-tutor show"),
        "{err}"
    );
    Ok(())
}

/// Every lesson ends with at least three questions, and every question graded against the
/// agent asks what the lesson taught, in one of two ways:
///
/// - a fact (`Basis::Fact`): its live value is the same, within the question's tolerance,
///   in runs of three seeds after 3 and after 12 episodes;
/// - a run measure (`Basis::Run`): its value differs between those runs, by more than the
///   tolerance (a choice: the right letter differs), so no fixed answer passes; and it
///   follows from the numbers the prompt shows. The lesson's formula on the givens, as the
///   prompt prints them (rounded), lands within the tolerance of the agent's own value, in
///   every run where the question can be asked.
///
/// And every lesson has at least one question of the second kind.
#[test]
fn every_lesson_has_a_quiz_and_predictions_follow_from_the_lesson() -> TestResult {
    use ppo_tutor::lesson::RunConfig;
    use ppo_tutor::lesson::Session;
    use ppo_tutor::lesson::quiz::{Answer, Basis, QuestionKind, template};
    let course = Course::embedded()?;
    let mut runs = std::collections::BTreeMap::new();
    for env in AgentKind::ALL {
        let mut snapshots = Vec::new();
        for seed in [0, 1, 2] {
            for episodes in [3, 12] {
                snapshots.push(Session::run(RunConfig::default_for(env), seed, episodes)?);
            }
        }
        runs.insert(env, snapshots);
    }
    let (mut facts, mut run_questions) = (0, 0);
    for lesson in &course.lessons {
        assert!(
            lesson.quiz.len() >= 3,
            "{}: {} questions",
            lesson.id,
            lesson.quiz.len()
        );
        let mut depends_on_run = false;
        for (i, q) in lesson.quiz.iter().enumerate() {
            let at = format!("{} question {}", lesson.id, i + 1);
            let (measure, tolerance) = match &q.kind {
                QuestionKind::Predict {
                    measure, tolerance, ..
                } => (*measure, *tolerance),
                QuestionKind::Choice {
                    answer: Answer::Live(measure),
                    ..
                } => (*measure, 0.0),
                QuestionKind::Choice { .. } => continue,
            };
            let snapshots = &runs[&lesson.env];
            match measure.basis {
                Basis::Fact(_) => {
                    facts += 1;
                    let values: Vec<f64> = snapshots
                        .iter()
                        .map(|s| (measure.value)(s).ok_or(format!("{at}: no {}", measure.name)))
                        .collect::<Result<_, _>>()?;
                    let (lo, hi) = range(&values);
                    assert!(
                        hi - lo <= tolerance,
                        "{at}: {} varies over runs ({values:?}), more than ±{tolerance}",
                        measure.name
                    );
                }
                Basis::Run { given, from } => {
                    run_questions += 1;
                    depends_on_run = true;
                    let shown = template::names(&q.prompt);
                    let mut values = Vec::new();
                    for s in snapshots.iter().filter(|s| q.ready_in(s)) {
                        let value = (measure.value)(s).ok_or("ready, so resolved")?;
                        let mut exact = Vec::new();
                        let mut printed = Vec::new();
                        for g in given {
                            let m = ppo_tutor::lesson::quiz::measure(g).ok_or("a measure")?;
                            let v = (m.value)(s).ok_or("ready, so resolved")?;
                            let decimals = shown
                                .iter()
                                .find(|(name, _)| name == g)
                                .ok_or(format!("{at}: the prompt shows {g}"))?
                                .1;
                            exact.push(v);
                            printed.push(template::show(v, decimals).parse::<f64>()?);
                        }
                        for (how, givens, within) in [
                            ("the exact givens", &exact, tolerance / 4.0),
                            ("the givens as printed", &printed, tolerance),
                        ] {
                            let derived = from(givens);
                            assert!(
                                (derived - value).abs() <= within.max(1e-9),
                                "{at}: {} from {how} {givens:?} is {derived}, the agent's \
                                 value {value}: more than ±{within} apart",
                                measure.name
                            );
                        }
                        values.push(value);
                    }
                    assert!(
                        values.len() >= 2,
                        "{at}: {} resolves in {} of the runs",
                        measure.name,
                        values.len()
                    );
                    let (lo, hi) = range(&values);
                    assert!(
                        hi - lo > tolerance,
                        "{at}: {} is {values:?} in different runs, within ±{tolerance}: it \
                         does not depend on the run",
                        measure.name
                    );
                }
                Basis::Given => return Err(format!("{at}: graded against a given").into()),
            }
        }
        assert!(
            depends_on_run,
            "{}: no question depends on the run",
            lesson.id
        );
    }
    assert!(
        facts >= 6 && run_questions >= course.lessons.len(),
        "{facts} facts, {run_questions} run questions"
    );
    Ok(())
}

fn range(values: &[f64]) -> (f64, f64) {
    values
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), v| {
            (l.min(*v), h.max(*v))
        })
}

/// The course asks no fact twice. No two questions are graded against
/// the same measure, no two against the same fact (every ratio of epoch 1 is 1 is read by
/// several measures, and asked once), and no two choice questions have the same right
/// answer.
#[test]
fn no_fact_is_asked_twice() -> TestResult {
    use ppo_tutor::lesson::quiz::{Answer, Basis, QuestionKind};
    use std::collections::BTreeMap;
    let course = Course::embedded()?;
    let (mut measures, mut facts, mut answers) =
        (BTreeMap::new(), BTreeMap::new(), BTreeMap::new());
    let mut twice = Vec::new();
    let mut seen = |map: &mut BTreeMap<String, String>, key: String, at: &str| {
        if let Some(first) = map.insert(key.clone(), at.to_string()) {
            twice.push(format!("{first} and {at}: {key}"));
        }
    };
    for lesson in &course.lessons {
        for (i, q) in lesson.quiz.iter().enumerate() {
            let at = format!("{} question {}", lesson.id, i + 1);
            let measure = match &q.kind {
                QuestionKind::Predict { measure, .. }
                | QuestionKind::Choice {
                    answer: Answer::Live(measure),
                    ..
                } => measure,
                QuestionKind::Choice {
                    choices,
                    answer: Answer::Letter(a),
                    ..
                } => {
                    seen(&mut answers, choices[*a].trim().to_lowercase(), &at);
                    continue;
                }
            };
            seen(&mut measures, measure.name.to_string(), &at);
            if let Basis::Fact(fact) = measure.basis {
                seen(&mut facts, fact.to_string(), &at);
            }
        }
    }
    assert!(twice.is_empty(), "asked twice: {twice:#?}");
    assert!(measures.len() >= course.lessons.len(), "{measures:?}");
    Ok(())
}

/// A measure that depends on the run does: over two seeds, after 3
/// and after 12 episodes, each run measure that resolves on an environment takes at least
/// two values there.
#[test]
fn run_measures_differ_between_runs() -> TestResult {
    use ppo_tutor::lesson::quiz::all_measures;
    use ppo_tutor::lesson::{RunConfig, Session};
    let mut snapshots = Vec::new();
    for env in AgentKind::ALL {
        for seed in [0, 1] {
            for episodes in [3, 12] {
                snapshots.push(Session::run(RunConfig::default_for(env), seed, episodes)?);
            }
        }
    }
    let mut checked = 0;
    for m in all_measures().filter(|m| m.depends_on_run()) {
        for env in AgentKind::ALL {
            let values: Vec<f64> = snapshots
                .iter()
                .filter(|s| s.agent() == env)
                .filter_map(|s| (m.value)(s))
                .collect();
            if values.len() < 2 {
                continue;
            }
            checked += 1;
            let (lo, hi) = range(&values);
            assert!(hi > lo, "{} is {values:?} in every {env:?} run", m.name);
        }
    }
    assert!(checked >= 17, "{checked} run measures checked");
    Ok(())
}

/// A quiz asks only what its lesson or an earlier one has taught (lesson
/// 1's asked about the clip at r = 1.35 and GAE with λ = 0). A question asks about a word
/// when its prompt or its right choice uses it; a wrong choice or an explanation may point
/// ahead. Lesson 1 names every idea in passing: the lesson in this table is the one that
/// works the idea through, where questions about it belong.
#[test]
fn no_quiz_asks_about_what_a_later_lesson_teaches() -> TestResult {
    use ppo_tutor::i18n::Lang;
    use ppo_tutor::lesson::quiz::{Answer, QuestionKind};
    // The words of an idea, in English and in the Chinese twin, and the lesson that teaches
    // it. (Not a bare ε: lesson 6's Adam has one too.)
    const TAUGHT: &[(&[&str], &str)] = &[
        (&["clip", "surr", "1 + ε", "截断"], "clipping"),
        (&["GAE", "λ", "lmbda"], "gae"),
    ];
    let (mut checked, mut early) = (0, Vec::new());
    for lang in [Lang::En, Lang::Zh] {
        let course = Course::embedded_in(lang)?;
        for (at, lesson) in course.lessons.iter().enumerate() {
            for (i, q) in lesson.quiz.iter().enumerate() {
                let mut asked = q.prompt.clone();
                // A choice the run decides asks about all of its choices.
                if let QuestionKind::Choice {
                    choices, answer, ..
                } = &q.kind
                {
                    for (k, choice) in choices.iter().enumerate() {
                        let right = match answer {
                            Answer::Letter(a) => *a == k,
                            Answer::Live(_) => true,
                        };
                        if right {
                            asked.push('\n');
                            asked.push_str(choice);
                        }
                    }
                }
                for (words, id) in TAUGHT {
                    let taught = course.index_of(id).ok_or(format!("no lesson {id}"))?;
                    if at >= taught {
                        continue;
                    }
                    checked += 1;
                    if let Some(word) = words.iter().find(|w| asked.contains(**w)) {
                        early.push(format!(
                            "{lang:?}: {} question {} asks about '{word}', which lesson {id} \
                             teaches; move the question there",
                            lesson.id,
                            i + 1
                        ));
                    }
                }
            }
        }
    }
    assert!(checked > 0);
    assert!(early.is_empty(), "{early:#?}");
    Ok(())
}

/// Every exercise declares what it reveals, in exercise.toml only: the
/// loader refuses a missing `reveals`, a name that is not a code anchor, and a Chinese twin
/// that declares it.
#[test]
fn an_exercise_must_declare_what_it_reveals_with_real_anchors() -> TestResult {
    use ppo_tutor::lesson::loader::{check_reveals, parse_exercises};
    let error = |text: &str| {
        parse_exercises("07-x", text)
            .and_then(|t| check_reveals("07-x", &t))
            .err()
            .map(|e| e.to_string())
            .unwrap_or_default()
    };
    let missing = error("[[exercise]]\nname = \"f\"\nidea = \"i\"\nfallback = \"look again\"\n");
    assert!(
        missing.contains("lessons/07-x/exercise.toml") && missing.contains("no `reveals`"),
        "{missing}"
    );
    let unknown = error(
        "[[exercise]]\nname = \"f\"\nidea = \"i\"\nreveals = [\"no_such_anchor\"]\nfallback = \"a\"\n",
    );
    assert!(
        unknown.contains("'no_such_anchor', which is not a code anchor"),
        "{unknown}"
    );
    assert_eq!(
        error(
            "[[exercise]]\nname = \"f\"\nidea = \"i\"\nreveals = [\"td_target_formula\"]\nfallback = \"a\"\n"
        ),
        ""
    );
    assert_eq!(
        error("[[exercise]]\nname = \"f\"\nidea = \"i\"\nreveals = []\nfallback = \"a\"\n"),
        ""
    );
    // Every exercise states the idea it tests, in both languages.
    let no_idea = error("[[exercise]]\nname = \"f\"\nreveals = []\nfallback = \"a\"\n");
    assert!(no_idea.contains("has no `idea`"), "{no_idea}");
    let blank = error("[[exercise]]\nname = \"f\"\nidea = \" \"\nreveals = []\nfallback = \"a\"\n");
    assert!(blank.contains("has no `idea`"), "{blank}");
    // Every exercise of the course declares it, and the Chinese course shares the English
    // declaration.
    for lang in [ppo_tutor::i18n::Lang::En, ppo_tutor::i18n::Lang::Zh] {
        for (dir, texts) in ppo_tutor::lesson::loader::embedded_exercises_in(lang)? {
            for t in texts {
                assert!(t.reveals.is_some(), "{dir}: {} declares no reveals", t.name);
                assert!(
                    t.idea.as_deref().is_some_and(|i| !i.trim().is_empty()),
                    "{dir}: {} states no idea",
                    t.name
                );
            }
        }
    }
    for dir in ppo_tutor::lesson::files::lesson_dirs() {
        let zh = ppo_tutor::lesson::files::embedded_file(&format!("{dir}/exercise.zh.toml"));
        assert!(
            !zh.is_some_and(|t| t.contains("\nreveals")),
            "{dir}/exercise.zh.toml declares reveals"
        );
    }
    Ok(())
}

/// Lesson 9's account of a missing `.detach()` ("epoch 1 gives an actor gradient of exactly
/// 0, epoch 2 raises that error", in both languages) is what PyTorch did, as recorded by
/// `tests/fixtures/detach_pytorch.py` in `tests/fixtures/detach_pytorch.json`: with the
/// detach both epochs have a gradient, without it the first is exactly 0 and the second
/// stops with the error the lesson quotes, under the version the lesson names.
#[test]
fn lesson_9_s_detach_check_is_the_recorded_pytorch_run() -> TestResult {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let recorded: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(
        root.join("tests/fixtures/detach_pytorch.json"),
    )?)?;
    let norm = |run: &str, epoch: usize| recorded[run][epoch]["actor_grad_norm"].as_f64();
    assert!(norm("detached", 0).is_some_and(|n| n > 0.0), "{recorded}");
    assert!(norm("detached", 1).is_some_and(|n| n > 0.0), "{recorded}");
    assert_eq!(norm("not_detached", 0), Some(0.0), "{recorded}");
    let error = recorded["not_detached"][1]["error"]
        .as_str()
        .ok_or("no error recorded for the second epoch")?;
    let version = recorded["torch"].as_str().ok_or("no torch version")?;
    let minor: String = version.split('.').take(2).collect::<Vec<_>>().join(".");
    for file in ["lesson.md", "lesson.zh.md"] {
        let text = std::fs::read_to_string(root.join("lessons/09-ratio").join(file))?;
        let text = text.split_whitespace().collect::<Vec<_>>().join(" ");
        let quoted = "Trying to backward through the graph a second time";
        assert!(error.starts_with(quoted), "{error}");
        assert!(text.contains(quoted), "{file} does not quote the error");
        assert!(
            text.contains(&format!("PyTorch {minor}")),
            "{file} does not name PyTorch {minor}, the recorded version"
        );
        assert!(
            text.contains("detach_pytorch.py"),
            "{file} does not name the recording"
        );
    }
    Ok(())
}
