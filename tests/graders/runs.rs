//! How the grader runs a learner's file: what the learner's code prints is shown beside its
//! case and never taken for an answer, processes it starts end with the grading, a function
//! still the starter's `todo!()` is reported before anything is built, and the cache keeps
//! only a few builds per exercise.

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use ppo_tutor::grade::{self, CheckStatus, GradeOptions, GradeProgress, Problem, Report};
use ppo_tutor::i18n::Lang;

use super::{ROOT, TestResult, english_in_chinese};

/// Options with a fresh cache folder of their own (so what is built there can be counted).
fn fresh(cache: &Path, limit: Duration) -> GradeOptions {
    GradeOptions {
        time_limit: limit,
        cache_dir: cache.to_path_buf(),
    }
}

/// `text` with `lines` put at the start of function `name`'s body.
fn with_prints(text: &str, name: &str, lines: &str) -> Result<String, Box<dyn std::error::Error>> {
    let at = text.find(&format!("pub fn {name}")).ok_or("no function")?;
    let open = at + text[at..].find('{').ok_or("no body")? + 1;
    Ok(format!("{}\n{lines}{}", &text[..open], &text[open..]))
}

/// The reverse_kl reference, printing on stdout (with and without a newline), on stderr,
/// and through `dbg!`.
fn printing_solution() -> Result<String, Box<dyn std::error::Error>> {
    let solution =
        std::fs::read_to_string(Path::new(ROOT).join("lessons/13-clip-lab/solution.rs"))?;
    with_prints(
        &solution,
        "reverse_kl",
        "    println!(\"rows: {}\", old_log_probs.len());\n    print!(\"no newline\");\n    \
         eprintln!(\"on stderr\");\n    dbg!(log_probs.len());\n",
    )
}

#[test]
fn printing_answers_still_pass_and_their_lines_are_shown_beside_the_case() -> TestResult {
    let cache = tempfile::tempdir()?;
    let exercise = grade::find("reverse_kl")?;
    let report = exercise.grade_source(
        &printing_solution()?,
        "printing.rs",
        &fresh(cache.path(), Duration::from_secs(10)),
    )?;
    let en = {
        let _en = Lang::En.scoped();
        report.render()
    };
    assert!(report.passed(), "{en}");
    for check in &report.checks {
        assert!(check.status == CheckStatus::Passed, "{en}");
        let lines = &check.printed.lines;
        // stdout's lines (the open one ended by the harness), then stderr's with dbg!'s,
        // which names the learner's file as graded.
        assert_eq!(lines.len(), 4, "{en}");
        assert!(lines[0].starts_with("rows: "), "{lines:?}");
        assert_eq!(lines[1], "no newline");
        assert_eq!(lines[2], "on stderr");
        assert!(lines[3].starts_with("[printing.rs:"), "{lines:?}");
        assert_eq!(check.printed.more, 0);
        assert_eq!(check.printed.other_cases, check.cases - 1, "{en}");
    }
    assert!(
        en.contains("      printed:  rows: 24\n                no newline\n"),
        "{en}"
    );
    assert!(en.contains("… 99 other cases printed too"), "{en}");
    let zh = {
        let _zh = Lang::Zh.scoped();
        report.render()
    };
    assert!(zh.contains("      输出：    rows: 24\n"), "{zh}");
    assert!(zh.contains("……另有 99 个用例也有输出"), "{zh}");
    let english = english_in_chinese(&report, exercise);
    assert!(english.is_empty(), "{english:#?}");
    Ok(())
}

#[test]
fn a_wrong_answer_that_prints_names_its_mistake_and_shows_the_failing_case_s_lines() -> TestResult {
    let cache = tempfile::tempdir()?;
    let opts = fresh(cache.path(), Duration::from_secs(10));
    for (name, id) in [
        ("compute_advantage", "forwards"),
        ("reverse_kl", "no_correction"),
    ] {
        let wrong = Path::new(ROOT).join(format!("tests/wrong_answers/{name}/{id}.rs"));
        // Many lines per case: a few are shown, the rest counted.
        let text = with_prints(
            &std::fs::read_to_string(wrong)?,
            name,
            "    for i in 0..8 { println!(\"line {i}\"); }\n    eprintln!(\"{}\", \"x\".repeat(300));\n",
        )?;
        let report = grade::find(name)?.grade_source(&text, "wrong.rs", &opts)?;
        let en = {
            let _en = Lang::En.scoped();
            report.render()
        };
        assert_eq!(report.mistake.as_deref(), Some(id), "{en}");
        let failed = report
            .checks
            .iter()
            .find(|c| matches!(c.status, CheckStatus::Failed(_)))
            .ok_or("nothing failed")?;
        let CheckStatus::Failed(failure) = &failed.status else {
            return Err("not a failure".into());
        };
        assert_eq!(failure.problem, Problem::Wrong, "{en}");
        assert_eq!(failed.printed.lines.len(), 5, "{en}");
        assert_eq!(
            failed.printed.more, 4,
            "8 lines and one on stderr, 5 shown: {en}"
        );
        assert_eq!(
            failed.printed.other_cases, 0,
            "the failing case's own lines: {en}"
        );
        assert!(en.contains("… 4 more lines"), "{en}");
        // The printed block sits between the failure's values and its hint.
        let printed = en.find("printed:  line 0").ok_or("no printed block")?;
        assert!(
            en[..printed].contains("got:") && en[printed..].contains("hint:"),
            "{en}"
        );
        let english = english_in_chinese(&report, grade::find(name)?);
        assert!(english.is_empty(), "{name}/{id}: {english:#?}");
    }
    // A line that does not fit is cut.
    let report = grade::find("reverse_kl")?.grade_source(
        &with_prints(
            &printing_solution()?,
            "reverse_kl",
            "    println!(\"{}\", \"y\".repeat(500));\n",
        )?,
        "long.rs",
        &opts,
    )?;
    let long = &report.checks[0].printed.lines[0];
    assert!(long.ends_with('…') && long.chars().count() <= 101, "{long}");
    Ok(())
}

/// Whether process `pid` has ended (gone, or a zombie no one reaps: in a container the
/// first process may not).
#[cfg(target_os = "linux")]
fn ended(pid: u32) -> bool {
    std::fs::read_to_string(format!("/proc/{pid}/stat")).map_or(true, |stat| {
        stat.rsplit_once(") ")
            .is_some_and(|(_, rest)| rest.starts_with('Z') || rest.starts_with('X'))
    })
}

#[cfg(target_os = "linux")]
#[test]
fn processes_the_learner_starts_end_with_the_grading() -> TestResult {
    let dir = tempfile::tempdir()?;
    let pid_file = dir.path().join("child.pid");
    let learner = format!(
        "pub fn reverse_kl(old_log_probs: &[f32], log_probs: &[f32]) -> f32 {{\n    \
         let child = std::process::Command::new(\"sleep\").arg(\"300\").spawn().unwrap();\n    \
         std::fs::write({pid_file:?}, child.id().to_string()).unwrap();\n    \
         loop {{ std::hint::spin_loop(); }}\n}}\n"
    );
    let report = grade::find("reverse_kl")?.grade_source(
        &learner,
        "spawns.rs",
        &fresh(&dir.path().join("cache"), Duration::from_secs(2)),
    )?;
    assert_eq!(
        report.first_failure().map(|f| &f.problem),
        Some(&Problem::TimedOut(2)),
        "{}",
        report.render()
    );
    let pid: u32 = std::fs::read_to_string(&pid_file)?.trim().parse()?;
    // SIGKILL is delivered at once; the wait only covers the kernel's bookkeeping.
    let until = Instant::now() + Duration::from_secs(10);
    while !ended(pid) && Instant::now() < until {
        std::thread::sleep(Duration::from_millis(50));
    }
    assert!(
        ended(pid),
        "the learner's `sleep 300` (pid {pid}) outlived the grading"
    );
    Ok(())
}

/// The build folders in `cache` whose names start with `prefix`.
fn builds(cache: &Path, prefix: &str) -> Result<Vec<PathBuf>, std::io::Error> {
    let mut found = Vec::new();
    for e in std::fs::read_dir(cache)? {
        let e = e?;
        if e.file_name().to_string_lossy().starts_with(prefix) {
            found.push(e.path());
        }
    }
    Ok(found)
}

#[test]
fn the_cache_keeps_only_the_latest_few_builds_of_an_exercise() -> TestResult {
    let cache = tempfile::tempdir()?;
    let opts = fresh(cache.path(), Duration::from_secs(10));
    let exercise = grade::find("reverse_kl")?;
    let solution =
        std::fs::read_to_string(Path::new(ROOT).join("lessons/13-clip-lab/solution.rs"))?;
    let versions = grade::build::KEEP + 4;
    for v in 0..versions {
        // A new version of the file each time (a comment is enough to make a new build),
        // and one that does not compile among them.
        let text = if v == 2 {
            format!("{solution}\n// version {v}\nfn broken() -> u32 {{ \"no\" }}\n")
        } else {
            format!("{solution}\n// version {v}\n")
        };
        let report = exercise.grade_source(&text, "version.rs", &opts)?;
        assert_eq!(report.passed(), v != 2, "{}", report.render());
        let kept = builds(cache.path(), "reverse_kl-")?;
        assert!(
            kept.len() <= grade::build::KEEP,
            "after {} versions the cache holds {} builds: {kept:?}",
            v + 1,
            kept.len()
        );
    }
    // The newest build is among those kept: grading it again builds nothing.
    let before = builds(cache.path(), "reverse_kl-")?;
    let text = format!("{solution}\n// version {}\n", versions - 1);
    let mut built = false;
    let report = exercise.grade_source_with_progress(&text, "version.rs", &opts, &mut |p| {
        built |= matches!(p, GradeProgress::Building { .. });
    })?;
    assert!(report.passed() && !built, "{}", report.render());
    assert_eq!(builds(cache.path(), "reverse_kl-")?.len(), before.len());
    Ok(())
}

#[test]
fn an_untouched_starter_is_not_started_before_any_build() -> TestResult {
    let cache = tempfile::tempdir()?;
    let opts = fresh(cache.path(), Duration::from_secs(10));
    for exercise in grade::exercises() {
        let starter = std::fs::read_to_string(Path::new(ROOT).join(exercise.starter_path()))?;
        let mut said = Vec::new();
        let report = exercise.grade_source_with_progress(
            &starter,
            &exercise.starter_path(),
            &opts,
            &mut |p| said.push(p.clone()),
        )?;
        let text = report.render();
        assert!(said.is_empty(), "{}: {said:?}", exercise.name());
        assert_eq!(report.summary(), "not started (todo!() left)", "{text}");
        assert!(report.not_started.is_some() && !report.passed(), "{text}");
        assert!(text.contains("todo!() is still there"), "{text}");
        assert!(
            report
                .checks
                .iter()
                .all(|c| matches!(c.status, CheckStatus::NotRun(_))),
            "{text}"
        );
        let english = english_in_chinese(&report, *exercise);
        assert!(english.is_empty(), "{}: {english:#?}", exercise.name());
    }
    let built: Vec<_> = std::fs::read_dir(cache.path())?.collect();
    assert!(built.is_empty(), "starters were built: {built:?}");

    // In a file of two exercises, the one begun is graded and the other is not started.
    let lesson = Path::new(ROOT).join("lessons/13-clip-lab");
    let starter = std::fs::read_to_string(lesson.join("exercise.rs"))?;
    let solution = std::fs::read_to_string(lesson.join("solution.rs"))?;
    let begun = ppo_tutor::grade::reset::splice_function(&starter, &solution, "reverse_kl")
        .ok_or("reverse_kl not spliced")?;
    let report = grade::find("reverse_kl")?.grade_source(&begun, "both.rs", &opts)?;
    assert!(report.passed(), "{}", report.render());
    let report = grade::find("kl_early_stop")?.grade_source(&begun, "both.rs", &opts)?;
    assert!(report.not_started.is_some(), "{}", report.render());
    // The line of the todo!() that is left.
    let line = begun
        .lines()
        .position(|l| l.trim() == "todo!()")
        .ok_or("no todo")?
        + 1;
    assert_eq!(report.not_started, Some(line));
    assert!(report.render().contains(&format!("(line {line})")));
    Ok(())
}

#[test]
fn a_build_is_announced_then_the_checks() -> TestResult {
    let cache = tempfile::tempdir()?;
    let opts = fresh(cache.path(), Duration::from_secs(10));
    let mut said: Vec<GradeProgress> = Vec::new();
    let report: Report = grade::find("reverse_kl")?.grade_source_with_progress(
        &printing_solution()?,
        "printing.rs",
        &opts,
        &mut |p| said.push(p.clone()),
    )?;
    assert!(report.passed(), "{}", report.render());
    assert!(
        matches!(
            said.as_slice(),
            [
                GradeProgress::Building {
                    first_time: false,
                    ..
                },
                GradeProgress::Checking
            ]
        ),
        "{said:?}"
    );
    // Each step reads in both languages.
    for p in &said {
        let text = p.text();
        assert!(!text.in_lang(Lang::En).is_empty());
        assert!(
            text.in_lang(Lang::Zh).chars().any(ppo_tutor::i18n::is_cjk),
            "{p:?}"
        );
    }
    Ok(())
}
