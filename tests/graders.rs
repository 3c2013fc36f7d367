//! The graders: every reference solution passes, every shipped starter fails, and every
//! typical wrong answer in `tests/wrong_answers/<exercise>/<mistake>.rs` fails with the hint
//! that names its mistake. Plus the grader's robustness (compile errors, a wrong signature,
//! panics, endless loops) and the `grade` / `reset` commands.
//!
//! Each wrong answer is written the way a learner would write it (loops, indexing), not
//! copied from the grader's compact variants, so a diagnosis that only matches its own
//! code would fail here.

use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::mpsc;
use std::time::Duration;

use ppo_tutor::grade::prose::Prose;
use ppo_tutor::grade::{self, Backend, CheckStatus, Exercise, GradeOptions, Problem, Report};
use ppo_tutor::i18n::Lang;

type TestResult = Result<(), Box<dyn std::error::Error>>;

/// Prints, processes the learner starts, the untouched starter and the cache.
#[path = "graders/runs.rs"]
mod runs;

const ROOT: &str = env!("CARGO_MANIFEST_DIR");

fn opts() -> GradeOptions {
    GradeOptions::default()
}

/// The grading cache of the candle exercise, shared by every test (and `ppo-tutor`
/// process) that grades `ppo_losses`, so candle is compiled for it once per target folder
/// (it lives in `target/tmp`). Measured on 2 cores: the first build of candle-core and
/// candle-nn in release takes about 1 min 50 s; each learner file after it about 2 s to
/// compile and link, and its grading about 3 s (training included). This test target
/// takes about 2.5 min cold and 50 s warm (it took seconds before the candle exercise).
fn candle_cache() -> PathBuf {
    Path::new(env!("CARGO_TARGET_TMPDIR")).join("grade-cache")
}

fn candle_opts(limit: Duration) -> GradeOptions {
    GradeOptions {
        time_limit: limit,
        cache_dir: candle_cache(),
    }
}

fn grade_file(name: &str, path: &Path) -> Result<Report, Box<dyn std::error::Error>> {
    Ok(grade::grade(name, Some(path), &opts())?)
}

fn grade_text(
    name: &str,
    text: &str,
    limit: Duration,
) -> Result<Report, Box<dyn std::error::Error>> {
    let options = GradeOptions {
        time_limit: limit,
        ..opts()
    };
    Ok(grade::find(name)?.grade_source(text, "learner_test.rs", &options)?)
}

/// The English words of `report` read in Chinese (none on a Chinese screen outside
/// code). Code is: the exercise's identifiers (every word of its signature, so its
/// parameters), file paths, code spans, and what the learner's toolchain printed (the
/// compiler's errors under a failed build, a panic's own message) or their code printed
/// (the lines under `输出：`).
fn english_in_chinese(report: &Report, exercise: &dyn Exercise) -> Vec<String> {
    let text = {
        let _zh = Lang::Zh.scoped();
        report.render()
    };
    // `true`, `false` and `inf` are values (`dones = [false, true, …]`, `[inf, inf]`).
    let allowed: std::collections::BTreeSet<String> = exercise
        .signature()
        .split(|c: char| !(c.is_alphanumeric() || c == '_'))
        .chain(["true", "false", "inf"])
        .filter(|w| !w.is_empty())
        .map(str::to_string)
        .collect();
    let printed: std::collections::BTreeSet<&str> = report
        .checks
        .iter()
        .flat_map(|c| c.printed.lines.iter().map(String::as_str))
        .collect();
    let ours = match &report.compile_error {
        // The summary line only: below it is rustc's output.
        Some(_) => text.lines().take(2).collect::<Vec<_>>(),
        None => text
            .lines()
            .filter(|l| !l.trim_start().starts_with("异常："))
            .filter(|l| !printed.contains(l.trim_start().trim_start_matches("输出：").trim()))
            .collect(),
    };
    ours.iter()
        .flat_map(|line| {
            ppo_tutor::i18n::english_words(line, &allowed)
                .into_iter()
                .map(move |w| format!("{w:?} in {line:?}"))
        })
        .collect()
}

/// The plain-Rust exercises of the registry (the candle one has a test of its own).
fn plain() -> impl Iterator<Item = &'static dyn Exercise> {
    grade::exercises()
        .iter()
        .copied()
        .filter(|e| e.meta().backend == Backend::Rustc)
}

#[test]
fn every_reference_solution_passes() -> TestResult {
    for exercise in plain() {
        let path = Path::new(ROOT).join(exercise.solution_path());
        let report = grade_file(exercise.name(), &path)?;
        assert!(report.passed(), "{}", report.render());
        assert!(grade::solution(exercise.name()).is_some());
    }
    Ok(())
}

#[test]
fn every_shipped_starter_fails() -> TestResult {
    for exercise in plain() {
        let path = Path::new(ROOT).join(exercise.starter_path());
        let report = grade_file(exercise.name(), &path)?;
        assert!(!report.passed(), "{}", report.render());
        assert_eq!(
            report.summary(),
            "not started (todo!() left)",
            "{}",
            exercise.name()
        );
        let text = report.render();
        assert!(text.contains("todo!() is still there"), "{text}");
        let english = english_in_chinese(&report, exercise);
        assert!(english.is_empty(), "{}: {english:#?}", exercise.name());
        let (rel, embedded) = grade::starter(exercise.name()).ok_or("no embedded starter")?;
        assert_eq!(
            std::fs::read_to_string(Path::new(ROOT).join(rel))?,
            embedded
        );
    }
    Ok(())
}

/// Grades every wrong answer of `name` and checks each fails, naming its own mistake.
fn catalogue(name: &str) -> TestResult {
    let ids = grade::find(name)?.mistake_ids();
    let prose = Prose::of(name)?;
    let dir = Path::new(ROOT).join("tests/wrong_answers").join(name);
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)?
        .map(|e| e.map(|e| e.path()))
        .collect::<Result<_, _>>()?;
    files.sort();
    let stems: Vec<String> = files
        .iter()
        .filter_map(|f| Some(f.file_stem()?.to_str()?.to_string()))
        .collect();
    let mut sorted_ids = ids.clone();
    sorted_ids.sort_unstable();
    assert_eq!(
        stems, sorted_ids,
        "{name}: one wrong answer file per known mistake"
    );
    for id in ids {
        let report = grade_file(name, &dir.join(format!("{id}.rs")))?;
        let text = report.render();
        assert!(!report.passed(), "{name}/{id} passed:\n{text}");
        assert_eq!(
            report.mistake.as_deref(),
            Some(id),
            "{name}/{id}: wrong diagnosis\n{text}"
        );
        let hint = prose.mistake(id);
        assert!(text.contains(hint), "{name}/{id}: hint missing\n{text}");
        let english = english_in_chinese(&report, grade::find(name)?);
        assert!(
            english.is_empty(),
            "{name}/{id}: English in Chinese: {english:#?}"
        );
    }
    Ok(())
}

/// Every plain exercise of the registry, its wrong answers graded on two threads (CI has
/// two cores: each rustc build overlaps the other thread's runs).
#[test]
fn every_catalogued_wrong_answer_fails_naming_its_mistake() {
    let names: Vec<&str> = plain().map(|e| e.name()).collect();
    let (first, second) = names.split_at(names.len() / 2);
    let run = |names: &[&str]| -> Vec<String> {
        names
            .iter()
            .filter_map(|n| catalogue(n).err().map(|e| e.to_string()))
            .collect()
    };
    let failures: Vec<String> = std::thread::scope(|s| {
        let other = s.spawn(|| run(second));
        let mut failures = run(first);
        failures.extend(
            other
                .join()
                .unwrap_or_else(|_| vec!["a grading thread panicked".into()]),
        );
        failures
    });
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
}

/// Right answers written another way than the reference (`tests/other_solutions/
/// <exercise>/<how>.rs`: a comparison in f64, a strict test written as a distance or a
/// quotient, a sum walked by subtraction) pass: the cases on a stated boundary are exact
/// whichever way a learner computes them.
#[test]
fn right_answers_written_another_way_pass() -> TestResult {
    let answers = answers_in("tests/other_solutions")?;
    for (name, file) in &answers {
        let report = grade_file(name, file)?;
        assert!(report.passed(), "{}:\n{}", file.display(), report.render());
    }
    assert!(
        answers.len() >= 3,
        "only {} other solutions found",
        answers.len()
    );
    Ok(())
}

/// Every `<folder>/<exercise>/<file>.rs` under the repository's `folder`, as (exercise, file).
fn answers_in(folder: &str) -> Result<Vec<(String, PathBuf)>, Box<dyn std::error::Error>> {
    let mut answers = Vec::new();
    for exercise in std::fs::read_dir(Path::new(ROOT).join(folder))? {
        let exercise = exercise?.path();
        let name = exercise
            .file_name()
            .and_then(|n| n.to_str())
            .ok_or("a folder name that is not UTF-8")?
            .to_string();
        for file in std::fs::read_dir(&exercise)? {
            answers.push((name.clone(), file?.path()));
        }
    }
    answers.sort();
    Ok(answers)
}

/// Wrong answers whose mistake is not in the catalogue (`tests/uncatalogued_answers/
/// <exercise>/<what it does>.rs`, each written the way a learner would) fail without a hint
/// that names a mistake the file does not make: no diagnosis, and none of the catalogue's
/// hints in the report, only the exercise's own.
#[test]
fn a_wrong_answer_outside_the_catalogue_gets_the_exercise_hint_not_a_wrong_one() -> TestResult {
    let mut graded = 0;
    for (name, file) in answers_in("tests/uncatalogued_answers")? {
        if grade::find(&name)?.meta().backend != Backend::Rustc {
            continue; // the candle exercise's are graded in the full tier, below
        }
        let prose = Prose::of(&name)?;
        let report = grade_file(&name, &file)?;
        let text = report.render();
        assert!(!report.passed(), "{} passed:\n{text}", file.display());
        assert_eq!(
            report.mistake,
            None,
            "{}: diagnosed as a mistake it does not make\n{text}",
            file.display()
        );
        for id in grade::find(&name)?.mistake_ids() {
            assert!(
                !text.contains(prose.mistake(id)),
                "{}: the hint of {id}\n{text}",
                file.display()
            );
        }
        graded += 1;
    }
    assert!(graded >= 3, "only {graded} uncatalogued answers found");
    Ok(())
}

/// The registry, the catalogues in `crates/ppo-grade/src/exercises/` and the prose in
/// `lessons/*/exercise.toml` agree: each exercise's mistake ids are the same on both sides,
/// every `[[exercise]]` is a registered exercise of that lesson, and the registry is in
/// course order.
#[test]
fn prose_and_catalogues_name_the_same_mistakes() -> TestResult {
    for exercise in grade::exercises() {
        let name = exercise.name();
        let prose = Prose::of(name)?;
        assert_eq!(prose.lesson, exercise.meta().lesson, "{name}");
        let mut code = exercise.mistake_ids();
        code.sort_unstable();
        let text: Vec<&str> = prose.text.mistakes.keys().map(String::as_str).collect();
        assert_eq!(
            code, text,
            "{name}: the mistake ids of crates/ppo-grade/src/exercises/{name}.rs and of \
             lessons/{}/exercise.toml differ",
            prose.lesson
        );
    }
    let prose = Prose::all()?;
    assert_eq!(
        prose.len(),
        grade::exercises().len(),
        "an [[exercise]] in lessons/*/exercise.toml is not in the registry: {:?}",
        prose.keys().collect::<Vec<_>>()
    );
    let lessons: Vec<&str> = grade::exercises().iter().map(|e| e.meta().lesson).collect();
    assert!(
        lessons.is_sorted(),
        "the registry is not in course order: {lessons:?}"
    );
    Ok(())
}

#[test]
fn every_mistake_differs_from_the_reference_somewhere() -> TestResult {
    for exercise in grade::exercises() {
        let uncaught = exercise.uncaught_mistakes()?;
        assert!(
            uncaught.is_empty(),
            "{}: {uncaught:?} never caught",
            exercise.name()
        );
    }
    Ok(())
}

/// A learner who answers every case exactly as a catalogued mistake does is diagnosed as
/// that mistake, not as another one (so every pair of mistakes is told apart by some case,
/// and the first listed of two look-alikes cannot shadow the second).
#[test]
fn every_mistake_made_alone_is_diagnosed_as_itself() -> TestResult {
    for exercise in grade::exercises() {
        let wrong = exercise.misdiagnosed_mistakes()?;
        assert!(
            wrong.is_empty(),
            "{}: (mistake, diagnosed as) {wrong:?}",
            exercise.name()
        );
    }
    Ok(())
}

#[test]
fn a_file_that_does_not_compile_shows_rustc_errors() -> TestResult {
    let report = grade_text(
        "reverse_kl",
        "pub fn reverse_kl(old_log_probs: &[f32], log_probs: &[f32]) -> f32 {\n    let x: u32 = \"no\";\n    todo!()\n}\n",
        Duration::from_secs(10),
    )?;
    let (summary, compiler) = report.compile_error.clone().ok_or("compiled")?;
    let summary = summary.in_lang(Lang::En);
    assert!(summary.contains("does not compile"), "{summary}");
    assert!(compiler.contains("error[E0308]"), "{compiler}");
    assert!(compiler.contains("learner_test.rs:2"), "{compiler}");
    assert!(!report.passed());
    assert!(report.render().contains("mismatched types"));
    let english = english_in_chinese(&report, grade::find("reverse_kl")?);
    assert!(english.is_empty(), "{english:#?}");
    Ok(())
}

#[test]
fn a_missing_or_mistyped_function_is_named() -> TestResult {
    let reverse_kl = grade::find("reverse_kl")?;
    let report = grade_text("reverse_kl", "pub fn other() {}\n", Duration::from_secs(10))?;
    assert!(english_in_chinese(&report, reverse_kl).is_empty());
    let (summary, _) = report.compile_error.ok_or("compiled")?;
    let (summary, zh) = (summary.in_lang(Lang::En), summary.in_lang(Lang::Zh));
    assert!(
        summary.contains("has no function `reverse_kl`"),
        "{summary}"
    );
    assert!(zh.contains("里没有函数 `reverse_kl`"), "{zh}");
    let report = grade_text(
        "reverse_kl",
        "pub fn reverse_kl(old: &[f64], log_probs: &[f64]) -> f64 { 0.0 }\n",
        Duration::from_secs(10),
    )?;
    assert!(english_in_chinese(&report, reverse_kl).is_empty());
    let (summary, _) = report.compile_error.ok_or("compiled")?;
    let (summary, zh) = (summary.in_lang(Lang::En), summary.in_lang(Lang::Zh));
    assert!(summary.contains("signature"), "{summary}");
    assert!(zh.contains("与练习要求的签名不符"), "{zh}");
    assert!(summary.contains("pub fn reverse_kl(old_log_probs: &[f32], log_probs: &[f32]) -> f32"));
    let report = grade_text(
        "reverse_kl",
        "fn reverse_kl(a: &[f32], b: &[f32]) -> f32 { 0.0 }\n",
        Duration::from_secs(10),
    )?;
    assert!(english_in_chinese(&report, reverse_kl).is_empty());
    let (summary, _) = report.compile_error.ok_or("compiled")?;
    let (summary, zh) = (summary.in_lang(Lang::En), summary.in_lang(Lang::Zh));
    assert!(summary.contains("private"), "{summary}");
    assert!(zh.contains("是私有的"), "{zh}");
    Ok(())
}

#[test]
fn a_panic_is_reported_with_its_message_and_input() -> TestResult {
    let report = grade_text(
        "compute_advantage",
        "pub fn compute_advantage(g: f32, l: f32, d: &[f32]) -> Vec<f32> {\n    (0..=d.len()).map(|i| d[i] * g * l).collect()\n}\n",
        Duration::from_secs(10),
    )?;
    let failure = report.first_failure().ok_or("no failure")?;
    match &failure.problem {
        Problem::Panicked(m) => {
            assert!(m.contains("index out of bounds"), "{m}");
            assert!(m.contains("learner_test.rs:2"), "{m}");
        }
        other => return Err(format!("expected a panic, got {other:?}").into()),
    }
    assert!(failure.hint.get().contains("past the end"));
    assert!(!failure.input.is_empty());
    let english = english_in_chinese(&report, grade::find("compute_advantage")?);
    assert!(english.is_empty(), "{english:#?}");
    Ok(())
}

#[test]
fn an_endless_loop_is_reported_as_never_returning() -> TestResult {
    let report = grade_text(
        "reverse_kl",
        "pub fn reverse_kl(o: &[f32], l: &[f32]) -> f32 {\n    let mut i = 0;\n    while i < o.len() { if o.len() > 1 { continue; } i += 1; }\n    0.0\n}\n",
        Duration::from_secs(1),
    )?;
    let failed: Vec<&Problem> = report
        .checks
        .iter()
        .filter_map(|c| match &c.status {
            CheckStatus::Failed(f) => Some(&f.problem),
            _ => None,
        })
        .collect();
    assert_eq!(
        failed.first(),
        Some(&&Problem::TimedOut(1)),
        "{}",
        report.render()
    );
    assert!(report.render().contains("never returned within 1 s"));
    let english = english_in_chinese(&report, grade::find("reverse_kl")?);
    assert!(english.is_empty(), "{english:#?}");
    assert!(
        report
            .checks
            .iter()
            .any(|c| matches!(c.status, CheckStatus::NotRun(_)))
    );
    Ok(())
}

fn ppo_tutor(dir: &Path, args: &[&str]) -> Result<(i32, String), Box<dyn std::error::Error>> {
    let out = Command::new(env!("CARGO_BIN_EXE_ppo-tutor"))
        // English whatever the machine's locale.
        .env("PPO_TUTOR_LANG", "en")
        .env_remove("LC_ALL")
        .env_remove("LC_MESSAGES")
        .env("LANG", "C.UTF-8")
        .args(args)
        .current_dir(dir)
        .env("PPO_TUTOR_STATE", dir.join("state.json"))
        .env("PPO_TUTOR_GRADE_CACHE", candle_cache())
        .env("NO_COLOR", "1")
        .output()?;
    let text = format!(
        "{}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    Ok((out.status.code().unwrap_or(-1), text))
}

#[test]
fn cli_grade_exit_codes_reset_and_score_table() -> TestResult {
    let dir = tempfile::tempdir()?;
    let d = dir.path();
    let wrong = Path::new(ROOT).join("tests/wrong_answers/zero_gradient_rows/sides_swapped.rs");
    let wrong = wrong.to_str().ok_or("path")?;
    let (code, text) = ppo_tutor(d, &["grade", "zero_gradient_rows", "--file", wrong])?;
    assert_eq!(code, 1, "{text}");
    assert!(text.contains("✗") && text.contains("expected:") && text.contains("got:"));
    assert!(text.contains("The two sides are swapped"));

    let (code, text) = ppo_tutor(d, &["grade", "no_such_exercise"])?;
    assert_eq!(code, 2, "{text}");
    assert_eq!(text.lines().count(), 1, "{text}");
    let (code, _) = ppo_tutor(d, &["grade", "--file", "x.rs"])?;
    assert_eq!(code, 2);
    let (code, text) = ppo_tutor(d, &["grade", "sample_action"])?;
    assert_eq!(code, 1, "{text}");
    assert!(text.contains("ppo-tutor reset sample_action"), "{text}");

    for name in grade::exercise_names() {
        let (code, text) = ppo_tutor(d, &["reset", name])?;
        assert_eq!(code, 0, "{text}");
    }
    // Grading the candle exercise's file compiles candle for its grading project (minutes,
    // cold): its own test does that, in the full tier. Here its starter, just written, is
    // taken away again, so the table shows it missing and nothing is compiled.
    let (candle, _) = grade::starter("ppo_losses").ok_or("no candle starter")?;
    std::fs::remove_file(d.join(candle))?;
    std::fs::copy(
        Path::new(ROOT).join("lessons/13-clip-lab/solution.rs"),
        d.join("lessons/13-clip-lab/exercise.rs"),
    )?;
    let (code, text) = ppo_tutor(d, &["grade", "reverse_kl"])?;
    assert_eq!(code, 0, "{text}");
    let (code, text) = ppo_tutor(d, &["grade"])?;
    assert_eq!(code, 1, "{text}");
    let score = format!("score: 2/{} exercises pass", grade::exercise_names().len());
    assert!(text.contains(&score), "{text}");
    assert!(text.contains("not started (todo!() left)"), "{text}");
    assert!(
        text.contains("missing: ppo-tutor reset ppo_losses"),
        "{text}"
    );
    let state = std::fs::read_to_string(d.join("state.json"))?;
    assert!(
        state.contains("reverse_kl") && state.contains("kl_early_stop"),
        "{state}"
    );

    // Resetting kl_early_stop keeps reverse_kl's work in the same file ...
    let (code, text) = ppo_tutor(d, &["reset", "kl_early_stop"])?;
    assert_eq!(code, 0, "{text}");
    assert!(text.contains("exercise.rs.bak"), "{text}");
    let (code, text) = ppo_tutor(d, &["grade", "reverse_kl"])?;
    assert_eq!(code, 0, "reset kl_early_stop kept reverse_kl: {text}");
    let (code, text) = ppo_tutor(d, &["grade", "kl_early_stop"])?;
    assert_eq!(code, 1, "reset restores kl_early_stop's starter: {text}");
    // ... and resetting reverse_kl, the file's only work, restores the whole starter.
    let (code, _) = ppo_tutor(d, &["reset", "reverse_kl"])?;
    assert_eq!(code, 0);
    let (code, text) = ppo_tutor(d, &["grade", "reverse_kl"])?;
    assert_eq!(code, 1, "reset restores the starter: {text}");
    Ok(())
}

#[test]
fn lessons_name_exactly_the_graded_exercises() -> TestResult {
    let course = ppo_tutor::lesson::Course::embedded()?;
    let mut named = Vec::new();
    for lesson in &course.lessons {
        let Some(exercise) = &lesson.exercise else {
            continue;
        };
        for name in exercise.names() {
            assert_eq!(
                grade::find(name)?.meta().lesson,
                format!("{:02}-{}", lesson.order, lesson.id),
                "{name}"
            );
            named.push(name.to_string());
        }
    }
    named.sort();
    let mut all: Vec<String> = grade::exercise_names()
        .iter()
        .map(|s| s.to_string())
        .collect();
    all.sort();
    assert_eq!(
        named, all,
        "every exercise appears in its lesson's exercise.toml"
    );
    Ok(())
}

fn tutor_screen(app: &ppo_tutor::tui::app::App) -> Result<String, Box<dyn std::error::Error>> {
    use ppo_tutor::tui::{theme::Theme, ui::View};
    let mut terminal = ratatui::Terminal::new(ratatui::backend::TestBackend::new(140, 60))?;
    terminal.draw(|f| {
        f.render_widget(
            &View {
                app,
                theme: Theme { color: false },
            },
            f.area(),
        );
    })?;
    Ok(terminal.backend().to_string())
}

#[test]
fn the_tutor_grades_reveals_hints_and_shows_the_solution_only_after_passing() -> TestResult {
    use ppo_tutor::lesson::{Course, Progress};
    use ppo_tutor::tui::app::{App, Overlay};
    use ppo_tutor::tui::keys::Action;

    let course = Course::embedded()?;
    let lesson = course.index_of("clip-lab").ok_or("no clip-lab lesson")?;
    let progress = Progress {
        lesson: "clip-lab".into(),
        ..Progress::default()
    };
    let mut app = App::new(course, progress, None);
    assert_eq!(app.lesson, lesson);
    assert!(tutor_screen(&app)?.contains("exercise reverse_kl, kl_early_stop: pending"));

    app.update(Action::Hint);
    assert_eq!(app.overlay, Overlay::Exercise);
    assert_eq!(app.exercise.scroll(), 0);
    assert_eq!(app.exercise.hints_shown, 1);
    let text = tutor_screen(&app)?;
    let hints = app
        .current_lesson()
        .and_then(|l| l.exercise.as_ref())
        .map_or(0, |e| e.hints.len());
    let exercises = grade::exercise_names().len();
    assert!(
        text.contains(&format!("Hints (1/{hints})"))
            && text.contains(&format!("exercises done 0/{exercises}")),
        "{text}"
    );

    app.update(Action::Grade);
    let names = app.exercise.request.take().ok_or("no grading requested")?;
    assert_eq!(names, ["reverse_kl", "kl_early_stop"]);
    assert!(app.exercise.grading);

    // The starter fails: no solution shown, nothing recorded.
    let starter = Path::new(ROOT).join("lessons/13-clip-lab/exercise.rs");
    let graded = names
        .iter()
        .map(|n| Ok((n.clone(), Ok(grade_file(n, &starter)?))))
        .collect::<Result<Vec<_>, Box<dyn std::error::Error>>>()?;
    app.on_graded(graded);
    let text = tutor_screen(&app)?;
    assert!(text.contains("todo!() is still there"), "{text}");
    assert!(!text.contains("The reference solution"), "{text}");
    assert!(!app.exercise_done());

    // The solution passes: recorded, shown, and the bar moves.
    let solution = Path::new(ROOT).join("lessons/13-clip-lab/solution.rs");
    let graded = names
        .iter()
        .map(|n| Ok((n.clone(), Ok(grade_file(n, &solution)?))))
        .collect::<Result<Vec<_>, Box<dyn std::error::Error>>>()?;
    app.on_graded(graded);
    assert!(app.exercise_done());
    assert!(app.progress.exercises_done.contains("kl_early_stop"));
    let text = tutor_screen(&app)?;
    assert!(text.contains("The reference solution"), "{text}");
    assert!(
        text.contains(&format!(
            "exercises done 2/{}",
            grade::exercise_names().len()
        )),
        "{text}"
    );

    app.update(Action::Back);
    assert_eq!(app.overlay, Overlay::None);
    assert!(tutor_screen(&app)?.contains("exercise reverse_kl, kl_early_stop: done"));
    Ok(())
}

fn grade_candle(text: &str, limit: Duration) -> Result<Report, Box<dyn std::error::Error>> {
    Ok(grade::find("ppo_losses")?.grade_source(text, "learner_candle.rs", &candle_opts(limit))?)
}

/// The candle exercise, in one test so that its grading project is built once: the
/// solution passes every check (training included), the starter is not started, every
/// catalogued wrong answer fails naming its mistake, and compile errors, returned errors,
/// non-scalar losses, panics and endless loops are reported.
#[test]
#[cfg_attr(
    not(feature = "full-tests"),
    ignore = "full tier (cargo test --features full-tests): compiles candle for the grading project, about 4 minutes cold"
)]
fn the_candle_exercise_grades_solution_starter_wrong_answers_and_failures() -> TestResult {
    use grade::exercises::ppo_losses;
    let exercise = grade::find("ppo_losses")?;
    let prose = Prose::of("ppo_losses")?;
    let ids = exercise.mistake_ids();
    let ten = Duration::from_secs(10);
    let lesson = Path::new(ROOT).join("lessons/12-losses");

    let report = grade_candle(
        &std::fs::read_to_string(lesson.join("solution_candle.rs"))?,
        ten,
    )?;
    assert!(report.passed(), "{}", report.render());
    assert_eq!(report.checks.len(), 5, "{}", report.render());
    assert_eq!(report.checks[4].name, ppo_losses::training_check_name());

    // Printing from the candle exercise (the training check asks thousands of times): it
    // still passes, and each check shows a few of the lines.
    let solution = std::fs::read_to_string(lesson.join("solution_candle.rs"))?;
    let open = solution
        .find(") -> Result<(Tensor, Tensor)> {")
        .ok_or("no signature")?
        + ") -> Result<(Tensor, Tensor)> {".len();
    let printing = format!(
        "{}\n    println!(\"batch of {{:?}}\", probs.dims());\n    dbg!(eps);{}",
        &solution[..open],
        &solution[open..]
    );
    let report = grade_candle(&printing, ten)?;
    assert!(report.passed(), "{}", report.render());
    for (i, check) in report.checks.iter().enumerate() {
        assert!(
            check
                .printed
                .lines
                .first()
                .is_some_and(|l| l.starts_with("batch of [")),
            "{}",
            report.render()
        );
        // stdout's lines come first: the training check's fill the five shown.
        assert!(
            i == 4
                || check
                    .printed
                    .lines
                    .iter()
                    .any(|l| l.starts_with("[learner_candle.rs:")),
            "{}",
            report.render()
        );
    }
    assert!(report.checks[4].printed.more > 100, "{}", report.render());

    let report = grade_candle(
        &std::fs::read_to_string(lesson.join("exercise_candle.rs"))?,
        ten,
    )?;
    assert_eq!(
        report.summary(),
        "not started (todo!() left)",
        "{}",
        report.render()
    );
    assert!(report.render().contains("todo!() is still there"));
    let (rel, embedded) = grade::starter("ppo_losses").ok_or("no embedded starter")?;
    assert_eq!(
        std::fs::read_to_string(Path::new(ROOT).join(rel))?,
        embedded
    );

    let dir = Path::new(ROOT).join("tests/wrong_answers/ppo_losses");
    let mut stems: Vec<String> = std::fs::read_dir(&dir)?
        .map(|e| {
            Ok(e?
                .path()
                .file_stem()
                .and_then(|s| s.to_str())
                .unwrap_or("")
                .to_string())
        })
        .collect::<Result<_, std::io::Error>>()?;
    stems.sort();
    let mut sorted = ids.clone();
    sorted.sort_unstable();
    assert_eq!(stems, sorted, "one wrong answer file per known mistake");
    // Two at a time (CI has 2 cores): the builds queue on cargo's lock, the runs overlap.
    let check = |id: &&str| -> Result<(), String> {
        let id = *id;
        let text =
            std::fs::read_to_string(dir.join(format!("{id}.rs"))).map_err(|e| e.to_string())?;
        let report = grade_candle(&text, ten).map_err(|e| e.to_string())?;
        let text = report.render();
        if report.passed() {
            return Err(format!("ppo_losses/{id} passed:\n{text}"));
        }
        if report.mistake.as_deref() != Some(id) {
            return Err(format!(
                "ppo_losses/{id}: wrong diagnosis {:?}\n{text}",
                report.mistake
            ));
        }
        if !text.contains(prose.mistake(id)) {
            return Err(format!("ppo_losses/{id}: hint missing\n{text}"));
        }
        let english = english_in_chinese(&report, exercise);
        if !english.is_empty() {
            return Err(format!("ppo_losses/{id}: English in Chinese: {english:#?}"));
        }
        // A loss pushing the wrong way does not learn: the training check says so.
        let learned = !matches!(
            report.checks.last().map(|c| &c.status),
            Some(CheckStatus::Failed(f)) if f.detail.in_lang(Lang::En).contains("did not learn")
        );
        if id == "no_minus_sign" && learned {
            return Err(format!(
                "ppo_losses/{id}: the training check passed\n{text}"
            ));
        }
        Ok(())
    };
    let (first, second) = ids.split_at(ids.len() / 2);
    let failures: Vec<String> = std::thread::scope(|s| {
        let other = s.spawn(|| {
            second
                .iter()
                .filter_map(|m| check(m).err())
                .collect::<Vec<_>>()
        });
        let mut failures: Vec<String> = first.iter().filter_map(|m| check(m).err()).collect();
        failures.extend(
            other
                .join()
                .unwrap_or_else(|_| vec!["a grading thread panicked".into()]),
        );
        failures
    });
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));

    // Outside the catalogue: no mistake named, and no hint that says something untrue (the
    // training check's "your losses match the seed's on every input above" after a failed
    // check: it gives that check's hint instead).
    let training_hint = prose.text("training");
    for name in ["min_of_the_means", "values_detached"] {
        let file = Path::new(ROOT).join(format!("tests/uncatalogued_answers/ppo_losses/{name}.rs"));
        let report = grade_candle(&std::fs::read_to_string(&file)?, ten)?;
        let text = report.render();
        assert!(!report.passed(), "{name} passed:\n{text}");
        assert_eq!(report.mistake, None, "{name}: diagnosed\n{text}");
        for id in &ids {
            assert!(
                !text.contains(prose.mistake(id)),
                "{name}: the hint of {id}\n{text}"
            );
        }
        assert!(
            !text.contains(training_hint),
            "{name}: the training hint\n{text}"
        );
    }

    let typo = "use candle_core::{Result, Tensor};\npub fn ppo_losses(probs: &Tensor, actions: &Tensor, old_log_probs: &Tensor, advantage: &Tensor, values: &Tensor, td_target: &Tensor, eps: f64) -> Result<(Tensor, Tensor)> {\n    let x: u32 = \"no\";\n    todo!()\n}\n";
    let report = grade_candle(typo, ten)?;
    let (summary, compiler) = report.compile_error.clone().ok_or("compiled")?;
    let summary = summary.in_lang(Lang::En);
    assert!(summary.contains("does not compile"), "{summary}");
    assert!(
        compiler.contains("error[E0308]") && compiler.contains("learner_candle.rs:3"),
        "{compiler}"
    );
    let report = grade_candle("pub fn ppo_losses(eps: f32) -> f32 { eps }\n", ten)?;
    let (summary, _) = report.compile_error.ok_or("compiled")?;
    let (summary, zh) = (summary.in_lang(Lang::En), summary.in_lang(Lang::Zh));
    assert!(zh.contains("与练习要求的签名不符"), "{zh}");
    assert!(
        summary.contains("signature") && summary.contains(&exercise.signature()),
        "{summary}"
    );

    let body = |lines: &str| {
        format!(
            "use candle_core::{{Result, Tensor}};\npub fn ppo_losses(probs: &Tensor, actions: &Tensor, old_log_probs: &Tensor, advantage: &Tensor, values: &Tensor, td_target: &Tensor, eps: f64) -> Result<(Tensor, Tensor)> {{\n{lines}\n}}\n"
        )
    };
    let report = grade_candle(
        &body("    let a = (probs - old_log_probs)?.mean_all()?;\n    Ok((a.clone(), a))"),
        ten,
    )?;
    let failure = report.first_failure().ok_or("no failure")?;
    assert!(
        matches!(&failure.problem, Problem::Error(m) if m.contains("shape mismatch")),
        "{}",
        report.render()
    );
    assert!(failure.hint.get().contains("(N, 2)"), "{}", failure.hint);
    let report = grade_candle(
        &body("    let a = (values - td_target)?.sqr()?.mean(0)?;\n    Ok((a.clone(), a))"),
        ten,
    )?;
    let failure = report.first_failure().ok_or("no failure")?;
    assert!(matches!(&failure.problem, Problem::Error(m) if m.contains("not a scalar")));
    let report = grade_candle(
        &body("    if probs.dims()[0] > 0 { loop { std::hint::spin_loop(); } }\n    todo!()"),
        Duration::from_secs(1),
    )?;
    assert_eq!(
        report.first_failure().map(|f| &f.problem),
        Some(&Problem::TimedOut(1)),
        "{}",
        report.render()
    );
    assert!(matches!(report.checks[4].status, CheckStatus::NotRun(_)));

    // The command line grades the same way (this file's program is already built).
    let state = tempfile::tempdir()?;
    let wrong = dir.join("no_minus_sign.rs");
    let (code, text) = ppo_tutor(
        state.path(),
        &[
            "grade",
            "ppo_losses",
            "--file",
            wrong.to_str().ok_or("path")?,
        ],
    )?;
    assert_eq!(code, 1, "{text}");
    assert!(
        text.contains("The actor loss without its minus sign"),
        "{text}"
    );

    // Without cargo, a clear error naming the fix (a fresh cache: nothing is built).
    let out = Command::new(env!("CARGO_BIN_EXE_ppo-tutor"))
        // English whatever the machine's locale.
        .env("PPO_TUTOR_LANG", "en")
        .env_remove("LC_ALL")
        .env_remove("LC_MESSAGES")
        .env("LANG", "C.UTF-8")
        .args([
            "grade",
            "ppo_losses",
            "--file",
            wrong.to_str().ok_or("path")?,
        ])
        .env("PPO_TUTOR_STATE", state.path().join("state.json"))
        .env("PPO_TUTOR_GRADE_CACHE", state.path().join("cache"))
        .env("CARGO", state.path().join("no-cargo-here"))
        .output()?;
    let text = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{text}");
    assert!(
        text.contains("cannot run cargo") && text.contains("set CARGO"),
        "{text}"
    );
    Ok(())
}

/// `grade NAME --file F` exits 0 exactly when F passes: the reference solution does, the
/// starter and a catalogued wrong answer do not.
#[test]
fn cli_grade_file_exits_zero_exactly_when_it_passes() -> TestResult {
    let dir = tempfile::tempdir()?;
    let d = dir.path();
    for exercise in plain() {
        let name = exercise.name();
        let lesson = Path::new(ROOT).join("lessons").join(exercise.meta().lesson);
        let wrong_dir = Path::new(ROOT).join("tests/wrong_answers").join(name);
        let wrong = std::fs::read_dir(&wrong_dir)?
            .filter_map(Result::ok)
            .map(|e| e.path())
            .min()
            .ok_or(format!("no wrong answer for {name}"))?;
        for (file, want) in [
            (lesson.join(exercise.meta().solution), 0),
            (lesson.join(exercise.meta().starter), 1),
            (wrong, 1),
        ] {
            let path = file.to_str().ok_or("path")?;
            let (code, text) = ppo_tutor(d, &["grade", name, "--file", path])?;
            assert_eq!(code, want, "{name} {path}: {text}");
        }
    }
    Ok(())
}

/// Reads `child`'s stdout on a thread, line by line, into a channel.
fn lines_of(
    child: &mut std::process::Child,
) -> Result<mpsc::Receiver<String>, Box<dyn std::error::Error>> {
    use std::io::BufRead;
    let stdout = child.stdout.take().ok_or("no stdout")?;
    let (tx, rx) = mpsc::channel();
    std::thread::spawn(move || {
        for line in std::io::BufReader::new(stdout)
            .lines()
            .map_while(Result::ok)
        {
            if tx.send(line).is_err() {
                return;
            }
        }
    });
    Ok(rx)
}

/// Waits until a line containing `want` arrives; returns what was read.
fn read_until(
    rx: &mpsc::Receiver<String>,
    want: &str,
) -> Result<String, Box<dyn std::error::Error>> {
    let mut seen = String::new();
    let deadline = std::time::Instant::now() + Duration::from_secs(120);
    while std::time::Instant::now() < deadline {
        if let Ok(line) = rx.recv_timeout(Duration::from_millis(200)) {
            seen.push_str(&line);
            seen.push('\n');
            if line.contains(want) {
                return Ok(seen);
            }
        }
    }
    Err(format!("'{want}' never came; read:\n{seen}").into())
}

#[test]
fn watch_regrades_on_save_and_moves_on_when_it_passes() -> TestResult {
    let dir = tempfile::tempdir()?;
    let d = dir.path();
    let (code, text) = ppo_tutor(d, &["reset", "reverse_kl"])?;
    assert_eq!(code, 0, "{text}");
    let mut child = Command::new(env!("CARGO_BIN_EXE_ppo-tutor"))
        // English whatever the machine's locale.
        .env("PPO_TUTOR_LANG", "en")
        .env_remove("LC_ALL")
        .env_remove("LC_MESSAGES")
        .env("LANG", "C.UTF-8")
        .args(["watch", "reverse_kl"])
        .current_dir(d)
        .env("PPO_TUTOR_STATE", d.join("state.json"))
        .env("RAYON_NUM_THREADS", "1")
        .env("NO_COLOR", "1")
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::null())
        .spawn()?;
    let rx = lines_of(&mut child)?;
    let result = (|| -> TestResult {
        let first = read_until(&rx, "Watching")?;
        assert!(first.contains("todo!()"), "{first}");
        // A wrong answer, saved: graded without a key press, with its hint.
        let file = d.join("lessons/13-clip-lab/exercise.rs");
        std::fs::copy(
            Path::new(ROOT).join("tests/wrong_answers/reverse_kl/forward_direction.rs"),
            &file,
        )?;
        let graded = read_until(&rx, "Watching")?;
        assert!(
            graded.contains("the direction the lesson shows"),
            "the mistake's hint: {graded}"
        );
        // The solution, saved: it passes and the next exercise is graded at once.
        std::fs::copy(
            Path::new(ROOT).join("lessons/13-clip-lab/solution.rs"),
            &file,
        )?;
        let passed = read_until(&rx, "passes. Next:")?;
        assert!(passed.contains("kl_early_stop"), "{passed}");
        let next = read_until(&rx, "passes. Next:")?;
        assert!(
            next.contains("✓ kl_early_stop passes. Next: td_target_truncation"),
            "{next}"
        );
        Ok(())
    })();
    let _ = child.kill();
    let _ = child.wait();
    result
}
