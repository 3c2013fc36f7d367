//! Grading in place (what a notebook cell does) gives the same verdicts, hints and messages
//! as `ppo-tutor grade` on a file: the reference solutions pass, and wrong answers fail
//! with the same diagnosis and the same report text (but for the name of the graded code).

use std::path::Path;
use std::sync::Arc;
use std::time::Duration;

use ppo_tutor::grade::exercises::ppo_losses::{self, protocol::LossesFn};
use ppo_tutor::grade::{self, CheckStatus, GradeOptions, Problem, Report, exercises, in_process};

#[allow(unused, clippy::all, clippy::pedantic)]
#[path = "../lessons/03-episode-loop/solution.rs"]
mod sol03;
#[allow(unused, clippy::all, clippy::pedantic)]
#[path = "../lessons/07-td-target/solution.rs"]
mod sol07;
#[allow(unused, clippy::all, clippy::pedantic)]
#[path = "../lessons/08-gae/solution.rs"]
mod sol08;
#[allow(unused, clippy::all, clippy::pedantic)]
#[path = "../lessons/09-ratio/solution.rs"]
mod sol09;
#[allow(unused, clippy::all, clippy::pedantic)]
#[path = "../lessons/11-clipping/solution.rs"]
mod sol10;
#[allow(unused, clippy::all, clippy::pedantic)]
#[path = "../lessons/10-trust-region/solution.rs"]
mod sol10_trust_region;
#[allow(unused, clippy::all, clippy::pedantic)]
#[path = "../lessons/12-losses/solution.rs"]
mod sol11;
#[allow(unused, clippy::all, clippy::pedantic)]
#[path = "../lessons/12-losses/solution_candle.rs"]
mod sol11_candle;
#[allow(unused, clippy::all, clippy::pedantic)]
#[path = "../lessons/13-clip-lab/solution.rs"]
mod sol12;
#[allow(unused, clippy::all, clippy::pedantic)]
#[path = "../lessons/16-beyond-the-seed/solution.rs"]
mod sol15;
#[allow(unused, clippy::all, clippy::pedantic)]
#[path = "../lessons/17-continuous-actions/solution.rs"]
mod sol16;
#[allow(unused, clippy::all, clippy::pedantic)]
#[path = "../lessons/12-losses/exercise_candle.rs"]
mod starter11_candle;

#[allow(unused, clippy::all, clippy::pedantic)]
#[path = "wrong_answers/ppo_losses/critic_sum.rs"]
mod w_losses_critic_sum;
#[allow(unused, clippy::all, clippy::pedantic)]
#[path = "wrong_answers/ppo_losses/no_minus_sign.rs"]
mod w_losses_no_minus_sign;
#[allow(unused, clippy::all, clippy::pedantic)]
#[path = "wrong_answers/ppo_losses/ratio_detached.rs"]
mod w_losses_ratio_detached;

/// One catalogued wrong answer per plain exercise: its module, from
/// `tests/wrong_answers/<exercise>/<mistake>.rs`.
macro_rules! wrong_answers {
    ($($module:ident = $path:literal;)+) => {
        $(
            #[allow(unused, clippy::all, clippy::pedantic)]
            #[path = $path]
            mod $module;
        )+
    };
}

wrong_answers! {
    w_sample_action = "wrong_answers/sample_action/swapped_actions.rs";
    w_n_step_target = "wrong_answers/n_step_target/crosses_episode_end.rs";
    w_advantage = "wrong_answers/compute_advantage/forwards.rs";
    w_importance = "wrong_answers/importance_weighted_mean/inverted_ratio.rs";
    w_categorical_kl = "wrong_answers/categorical_kl/old_masked_nan.rs";
    w_zero_gradient_rows = "wrong_answers/zero_gradient_rows/sides_swapped.rs";
    w_clipped_value_loss = "wrong_answers/clipped_value_loss/min_instead_of_max.rs";
    w_reverse_kl = "wrong_answers/reverse_kl/forward_direction.rs";
    w_kl_early_stop = "wrong_answers/kl_early_stop/k3_estimator.rs";
    w_td_target_truncation = "wrong_answers/td_target_truncation/stops_at_truncation.rs";
    w_gae_rollout = "wrong_answers/gae_rollout/resets_only_on_termination.rs";
    w_diag_gaussian = "wrong_answers/diag_gaussian_log_prob/mean_over_dims.rs";
}

type TestResult = Result<(), Box<dyn std::error::Error>>;

#[test]
fn every_reference_solution_passes_in_place() {
    let reports = [
        in_process::sample_action(sol03::sample_action),
        in_process::n_step_target(sol07::n_step_target),
        in_process::compute_advantage(sol08::compute_advantage),
        in_process::importance_weighted_mean(sol09::importance_weighted_mean),
        in_process::categorical_kl(sol10_trust_region::categorical_kl),
        in_process::zero_gradient_rows(sol10::zero_gradient_rows),
        in_process::clipped_value_loss(sol11::clipped_value_loss),
        in_process::reverse_kl(sol12::reverse_kl),
        in_process::kl_early_stop(sol12::kl_early_stop),
        in_process::td_target_truncation(sol15::td_target_truncation),
        in_process::gae_rollout(sol15::gae_rollout),
        in_process::diag_gaussian_log_prob(sol16::diag_gaussian_log_prob),
    ];
    for r in &reports {
        assert!(r.passed(), "{}", r.render());
        assert_eq!(r.file, in_process::DISPLAY);
    }
    // In Chinese every check reads in Chinese: no English word outside code and names
    // (each name is written as a pair where the check is defined).
    let _zh = ppo_tutor::i18n::Lang::Zh.scoped();
    let none = std::collections::BTreeSet::new();
    for r in &reports {
        let text = r.render();
        for line in text.lines().skip(1) {
            let english = ppo_tutor::i18n::english_words(line, &none);
            assert!(english.is_empty(), "{english:?} in {line}\n{text}");
        }
    }
}

/// The report text without its first line (which names the graded file or cell) and
/// without panic locations (a file's line; a notebook cell has none worth showing).
fn body(report: &Report) -> String {
    report
        .render()
        .lines()
        .skip(1)
        .map(|l| match l.find(" (at ") {
            Some(i) if l.contains("panicked:") => &l[..i],
            _ => l,
        })
        .collect::<Vec<_>>()
        .join("\n")
}

fn compare(name: &str, wrong: &str, in_place: &Report) -> TestResult {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/wrong_answers")
        .join(name)
        .join(format!("{wrong}.rs"));
    let from_file = grade::grade(name, Some(&path), &GradeOptions::default())?;
    assert!(!in_place.passed(), "{name}/{wrong} passed in place");
    assert_eq!(
        in_place.mistake.as_deref(),
        Some(wrong),
        "{name}/{wrong} in place:\n{}",
        in_place.render()
    );
    assert_eq!(in_place.mistake, from_file.mistake, "{name}/{wrong}");
    assert_eq!(body(in_place), body(&from_file), "{name}/{wrong}");
    Ok(())
}

#[test]
fn wrong_answers_get_the_same_diagnosis_and_messages_as_from_a_file() -> TestResult {
    use in_process as g;
    let pairs = [
        (
            "sample_action",
            "swapped_actions",
            g::sample_action(w_sample_action::sample_action),
        ),
        (
            "n_step_target",
            "crosses_episode_end",
            g::n_step_target(w_n_step_target::n_step_target),
        ),
        (
            "compute_advantage",
            "forwards",
            g::compute_advantage(w_advantage::compute_advantage),
        ),
        (
            "importance_weighted_mean",
            "inverted_ratio",
            g::importance_weighted_mean(w_importance::importance_weighted_mean),
        ),
        (
            "categorical_kl",
            "old_masked_nan",
            g::categorical_kl(w_categorical_kl::categorical_kl),
        ),
        (
            "zero_gradient_rows",
            "sides_swapped",
            g::zero_gradient_rows(w_zero_gradient_rows::zero_gradient_rows),
        ),
        (
            "clipped_value_loss",
            "min_instead_of_max",
            g::clipped_value_loss(w_clipped_value_loss::clipped_value_loss),
        ),
        (
            "reverse_kl",
            "forward_direction",
            g::reverse_kl(w_reverse_kl::reverse_kl),
        ),
        (
            "kl_early_stop",
            "k3_estimator",
            g::kl_early_stop(w_kl_early_stop::kl_early_stop),
        ),
        (
            "td_target_truncation",
            "stops_at_truncation",
            g::td_target_truncation(w_td_target_truncation::td_target_truncation),
        ),
        (
            "gae_rollout",
            "resets_only_on_termination",
            g::gae_rollout(w_gae_rollout::gae_rollout),
        ),
        (
            "diag_gaussian_log_prob",
            "mean_over_dims",
            g::diag_gaussian_log_prob(w_diag_gaussian::diag_gaussian_log_prob),
        ),
    ];
    for (name, wrong, report) in &pairs {
        compare(name, wrong, report)?;
    }
    Ok(())
}

#[test]
fn a_panic_is_reported_with_its_message_and_the_grader_goes_on() {
    fn starter(_: &[f32], _: &[f32]) -> f32 {
        todo!()
    }
    let report = in_process::reverse_kl(starter);
    assert!(!report.passed());
    let failed: Vec<_> = report
        .checks
        .iter()
        .filter_map(|c| match &c.status {
            CheckStatus::Failed(f) => Some(f),
            _ => None,
        })
        .collect();
    assert!(!failed.is_empty());
    assert!(
        matches!(&failed[0].problem, Problem::Panicked(m) if m.contains("not yet implemented")),
        "{}",
        report.render()
    );
    assert!(
        failed[0].hint.get().contains("todo!()"),
        "{}",
        failed[0].hint
    );
    // The hook that was in force before grading is back.
    let caught = std::panic::catch_unwind(|| panic!("after grading"));
    assert!(caught.is_err());
}

/// Grading stopped within seconds, and its first failure is the time limit.
fn assert_timed_out(report: &Report, started: std::time::Instant) -> TestResult {
    assert!(started.elapsed() < Duration::from_secs(5));
    let first = report.first_failure().ok_or("no failure")?;
    assert!(
        matches!(first.problem, Problem::TimedOut(_)),
        "{}",
        report.render()
    );
    Ok(())
}

#[test]
fn a_function_that_never_returns_is_reported_after_the_time_limit() -> TestResult {
    let started = std::time::Instant::now();
    let report = exercises::reverse_kl::EXERCISE.grade_in_place_within(
        Arc::new(|_| {
            loop {
                std::thread::sleep(Duration::from_millis(50));
            }
        }),
        Duration::from_millis(300),
    );
    assert_timed_out(&report, started)?;
    assert!(
        report
            .checks
            .iter()
            .skip(1)
            .all(|c| matches!(c.status, CheckStatus::NotRun(_))),
        "{}",
        report.render()
    );
    Ok(())
}

/// The grading cache of the candle exercise, shared with `tests/graders.rs` (candle is
/// compiled for it once per target folder; a learner file then takes about 2 s to build).
fn candle_opts() -> GradeOptions {
    GradeOptions {
        cache_dir: Path::new(env!("CARGO_TARGET_TMPDIR")).join("grade-cache"),
        ..GradeOptions::default()
    }
}

/// The candle exercise graded in place and from its file give the same report text.
fn compare_candle(file: &Path, f: LossesFn, mistake: Option<&str>) -> TestResult {
    let started = std::time::Instant::now();
    let in_place = in_process::ppo_losses(f);
    let took = started.elapsed();
    let source = std::fs::read_to_string(file)?;
    let from_file =
        grade::find("ppo_losses")?.grade_source(&source, "learner.rs", &candle_opts())?;
    let name = file.display();
    eprintln!("{name}: graded in place in {:.2} s", took.as_secs_f64());
    assert!(!in_place.passed(), "{name} passed in place");
    assert_eq!(in_place.file, in_process::DISPLAY);
    assert_eq!(
        in_place.mistake.as_deref(),
        mistake,
        "{}",
        in_place.render()
    );
    assert_eq!(in_place.mistake, from_file.mistake, "{name}");
    if from_file.not_started.is_some() {
        // A file still `todo!()` is reported before it is built; in place the function
        // runs and panics with todo!()'s message: both say "not started".
        assert_eq!(in_place.summary(), from_file.summary(), "{name}");
        assert_eq!(in_place.summary(), "not started (todo!() left)", "{name}");
    } else {
        assert_eq!(body(&in_place), body(&from_file), "{name}");
    }
    Ok(())
}

/// The candle exercise: the reference passes in place (training included), the starter and
/// wrong answers get the file grader's diagnosis and text. About 4 s a grading in place
/// (3 s of it training CartPole), and 2 s more to build each file for the comparison.
#[test]
#[cfg_attr(
    not(feature = "full-tests"),
    ignore = "full tier (cargo test --features full-tests): compiles candle for the grading project, about 4 minutes cold"
)]
fn the_candle_exercise_grades_in_place_like_from_a_file() -> TestResult {
    let started = std::time::Instant::now();
    let report = in_process::ppo_losses(sol11_candle::ppo_losses);
    eprintln!(
        "solution_candle.rs: graded in place in {:.2} s",
        started.elapsed().as_secs_f64()
    );
    assert!(report.passed(), "{}", report.render());
    assert_eq!(report.checks.len(), 5, "{}", report.render());

    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let starter = root.join("lessons/12-losses/exercise_candle.rs");
    compare_candle(&starter, starter11_candle::ppo_losses, None)?;
    let wrong = root.join("tests/wrong_answers/ppo_losses");
    let answers: [(&str, LossesFn); 3] = [
        ("no_minus_sign", w_losses_no_minus_sign::ppo_losses),
        ("ratio_detached", w_losses_ratio_detached::ppo_losses),
        ("critic_sum", w_losses_critic_sum::ppo_losses),
    ];
    for (id, f) in answers {
        compare_candle(&wrong.join(format!("{id}.rs")), f, Some(id))?;
    }
    Ok(())
}

#[test]
fn a_candle_function_that_never_returns_is_reported_after_the_time_limit() -> TestResult {
    fn endless(
        _: &candle_core::Tensor,
        _: &candle_core::Tensor,
        _: &candle_core::Tensor,
        _: &candle_core::Tensor,
        _: &candle_core::Tensor,
        _: &candle_core::Tensor,
        _: f64,
    ) -> candle_core::Result<(candle_core::Tensor, candle_core::Tensor)> {
        loop {
            std::thread::sleep(Duration::from_millis(50));
        }
    }
    let started = std::time::Instant::now();
    let report = ppo_losses::in_place_within(endless, Duration::from_millis(300));
    assert_timed_out(&report, started)?;
    // The other case lists and the training are not run (the gradients check, over every
    // case, reports the first case's timeout again, as the file grader does).
    let not_run = |k: usize| matches!(report.checks[k].status, CheckStatus::NotRun(_));
    assert!(
        not_run(1) && not_run(2) && not_run(4),
        "{}",
        report.render()
    );
    Ok(())
}
