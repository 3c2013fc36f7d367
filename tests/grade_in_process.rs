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
mod sol06;
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
#[path = "../lessons/10-clipping/solution.rs"]
mod sol10;
#[allow(unused, clippy::all, clippy::pedantic)]
#[path = "../lessons/11-losses/solution.rs"]
mod sol11;
#[allow(unused, clippy::all, clippy::pedantic)]
#[path = "../lessons/11-losses/solution_candle.rs"]
mod sol11_candle;
#[allow(unused, clippy::all, clippy::pedantic)]
#[path = "../lessons/13-training/solution.rs"]
mod sol12;

#[path = "../lessons/12-clip-lab/solution.rs"]
mod sol_clip_lab;

#[allow(clippy::needless_range_loop)]
#[path = "../lessons/15-beyond-the-seed/solution.rs"]
mod sol15;
#[path = "../lessons/16-continuous-actions/solution.rs"]
mod sol16;
#[allow(unused, clippy::all, clippy::pedantic)]
#[path = "../lessons/11-losses/exercise_candle.rs"]
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

#[allow(unused, clippy::all, clippy::pedantic)]
#[path = "wrong_answers/actor_loss/max_instead_of_min.rs"]
mod w_actor_loss;
#[allow(unused, clippy::all, clippy::pedantic)]
#[path = "wrong_answers/compute_advantage/forwards.rs"]
mod w_advantage;
#[allow(unused, clippy::all, clippy::pedantic)]
#[path = "wrong_answers/approx_kl/naive_estimator.rs"]
mod w_approx_kl;
#[allow(unused, clippy::all, clippy::pedantic)]
#[path = "wrong_answers/clip_fraction/bounds_not_distance.rs"]
mod w_clip_fraction;
#[allow(unused, clippy::all, clippy::pedantic)]
#[path = "wrong_answers/critic_loss/root_mean_square.rs"]
mod w_critic_loss;
#[allow(unused, clippy::all, clippy::pedantic)]
#[path = "wrong_answers/gae_rollout/resets_only_on_termination.rs"]
mod w_gae_rollout;
#[allow(unused, clippy::all, clippy::pedantic)]
#[path = "wrong_answers/gaussian_log_prob/sigma_as_variance.rs"]
mod w_gaussian_log_prob;
#[allow(unused, clippy::all, clippy::pedantic)]
#[path = "wrong_answers/log_prob_of_actions/no_log.rs"]
mod w_log_prob;
#[allow(unused, clippy::all, clippy::pedantic)]
#[path = "wrong_answers/moving_average/no_edges.rs"]
mod w_moving_average;
#[allow(unused, clippy::all, clippy::pedantic)]
#[path = "wrong_answers/normalize_advantage/biased_std.rs"]
mod w_normalize_advantage;
#[allow(unused, clippy::all, clippy::pedantic)]
#[path = "wrong_answers/ratio/no_exp.rs"]
mod w_ratio;
#[allow(unused, clippy::all, clippy::pedantic)]
#[path = "wrong_answers/sample_action/swapped_actions.rs"]
mod w_sample_action;
#[allow(unused, clippy::all, clippy::pedantic)]
#[path = "wrong_answers/td_delta/inverted.rs"]
mod w_td_delta;
#[allow(unused, clippy::all, clippy::pedantic)]
#[path = "wrong_answers/td_target/missing_done_mask.rs"]
mod w_td_target;
#[allow(unused, clippy::all, clippy::pedantic)]
#[path = "wrong_answers/td_target_truncation/stops_at_truncation.rs"]
mod w_td_target_truncation;
#[allow(unused, clippy::all, clippy::pedantic)]
#[path = "wrong_answers/zero_gradient_rows/sides_swapped.rs"]
mod w_zero_gradient_rows;

type TestResult = Result<(), Box<dyn std::error::Error>>;

#[test]
fn every_reference_solution_passes_in_place() {
    let reports = [
        in_process::sample_action(sol06::sample_action),
        in_process::td_target(sol07::td_target),
        in_process::td_delta(sol07::td_delta),
        in_process::compute_advantage(sol08::compute_advantage),
        in_process::log_prob_of_actions(sol09::log_prob_of_actions),
        in_process::ratio(sol09::ratio),
        in_process::actor_loss(sol10::actor_loss),
        in_process::critic_loss(sol11::critic_loss),
        in_process::moving_average(sol12::moving_average),
        in_process::zero_gradient_rows(sol10::zero_gradient_rows),
        in_process::approx_kl(sol_clip_lab::approx_kl),
        in_process::clip_fraction(sol_clip_lab::clip_fraction),
        in_process::td_target_truncation(sol15::td_target_truncation),
        in_process::gae_rollout(sol15::gae_rollout),
        in_process::normalize_advantage(sol15::normalize_advantage),
        in_process::gaussian_log_prob(sol16::gaussian_log_prob),
    ];
    for r in &reports {
        assert!(r.passed(), "{}", r.render());
        assert_eq!(r.file, in_process::DISPLAY);
    }
    // In Chinese every check is named in Chinese (the names are English data; a check
    // added or reworded without its Chinese name would show in English).
    let _zh = ppo_tutor::i18n::Lang::Zh.scoped();
    for r in &reports {
        let text = r.render();
        for line in text.lines().filter(|l| l.trim_start().starts_with('✓')) {
            assert!(
                line.chars().any(|c| ('\u{4e00}'..='\u{9fff}').contains(&c)),
                "a check without a Chinese name (add it to CHECK_NAMES in crates/ppo-grade/src/report.rs): {line}\n{text}"
            );
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
    compare(
        "sample_action",
        "swapped_actions",
        &in_process::sample_action(w_sample_action::sample_action),
    )?;
    compare(
        "td_target",
        "missing_done_mask",
        &in_process::td_target(w_td_target::td_target),
    )?;
    compare(
        "td_delta",
        "inverted",
        &in_process::td_delta(w_td_delta::td_delta),
    )?;
    compare(
        "compute_advantage",
        "forwards",
        &in_process::compute_advantage(w_advantage::compute_advantage),
    )?;
    compare(
        "log_prob_of_actions",
        "no_log",
        &in_process::log_prob_of_actions(w_log_prob::log_prob_of_actions),
    )?;
    compare("ratio", "no_exp", &in_process::ratio(w_ratio::ratio))?;
    compare(
        "actor_loss",
        "max_instead_of_min",
        &in_process::actor_loss(w_actor_loss::actor_loss),
    )?;
    compare(
        "critic_loss",
        "root_mean_square",
        &in_process::critic_loss(w_critic_loss::critic_loss),
    )?;
    compare(
        "moving_average",
        "no_edges",
        &in_process::moving_average(w_moving_average::moving_average),
    )?;
    compare(
        "zero_gradient_rows",
        "sides_swapped",
        &in_process::zero_gradient_rows(w_zero_gradient_rows::zero_gradient_rows),
    )?;
    compare(
        "approx_kl",
        "naive_estimator",
        &in_process::approx_kl(w_approx_kl::approx_kl),
    )?;
    compare(
        "clip_fraction",
        "bounds_not_distance",
        &in_process::clip_fraction(w_clip_fraction::clip_fraction),
    )?;
    compare(
        "td_target_truncation",
        "stops_at_truncation",
        &in_process::td_target_truncation(w_td_target_truncation::td_target_truncation),
    )?;
    compare(
        "gae_rollout",
        "resets_only_on_termination",
        &in_process::gae_rollout(w_gae_rollout::gae_rollout),
    )?;
    compare(
        "normalize_advantage",
        "biased_std",
        &in_process::normalize_advantage(w_normalize_advantage::normalize_advantage),
    )?;
    compare(
        "gaussian_log_prob",
        "sigma_as_variance",
        &in_process::gaussian_log_prob(w_gaussian_log_prob::gaussian_log_prob),
    )?;
    Ok(())
}

#[test]
fn a_panic_is_reported_with_its_message_and_the_grader_goes_on() {
    fn starter(_: &[f32], _: &[f32]) -> f32 {
        todo!()
    }
    let report = in_process::critic_loss(starter);
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
    assert!(failed[0].hint.contains("todo!()"), "{}", failed[0].hint);
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
    let report = exercises::critic_loss::EXERCISE.grade_in_place_within(
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
    assert_eq!(body(&in_place), body(&from_file), "{name}");
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
    let starter = root.join("lessons/11-losses/exercise_candle.rs");
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
