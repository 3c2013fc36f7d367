//! The statistics module against rliable (Agarwal et al., 2021) on recorded scores.
//!
//! Reference data: `tests/fixtures/rliable_scores.json`, made by
//! `tests/fixtures/rliable_scores.py` from the final scores of three 10-seed CartPole runs
//! (and three edge sets): rliable's mean and IQM with their 95% percentile bootstrap
//! intervals, and paired differences' mean with its interval.
//!
//! Tolerances. The point estimates are deterministic: 1e-9. The intervals are Monte-Carlo
//! estimates on two different generators (numpy's in rliable, our PCG64), 50 000 draws
//! each. The error of an empirical 2.5% quantile from R draws is about
//! `√(p(1−p)/R) / f(q)`, which for a bell-shaped bootstrap distribution of spread `s` is
//! `0.012·s`; the interval's width is about `3.9·s`, so the difference of two independent
//! estimates has a spread near `0.004 × width`. We allow `0.02 × width` (five times that;
//! the largest difference recorded was `0.0063 × width`). With eight or fewer seeds the
//! resampled statistic takes few distinct values and both generators land on the same
//! ones: there the ends agree to 1e-9.

use ppo_rl::stats::{Bootstrap, Estimate, Interval, iqm, mean};
use serde::Deserialize;

#[derive(Deserialize)]
struct Fixture {
    reps: usize,
    confidence: f64,
    sets: Vec<Set>,
    paired: Vec<PairedCase>,
}

#[derive(Deserialize)]
struct Set {
    name: String,
    scores: Vec<f64>,
    mean: f64,
    iqm: f64,
    mean_ci: [f64; 2],
    iqm_ci: [f64; 2],
}

#[derive(Deserialize)]
struct PairedCase {
    arm: String,
    baseline: String,
    differences: Vec<f64>,
    mean_difference: f64,
    ci: [f64; 2],
}

type TestResult = Result<(), Box<dyn std::error::Error>>;

fn fixture() -> Result<Fixture, Box<dyn std::error::Error>> {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../tests/fixtures/rliable_scores.json"
    );
    Ok(serde_json::from_str(&std::fs::read_to_string(path)?)?)
}

fn bootstrap(fx: &Fixture) -> Bootstrap {
    Bootstrap {
        reps: fx.reps,
        confidence: fx.confidence,
        seed: 0,
    }
}

fn close_interval(what: &str, ours: Interval, theirs: [f64; 2], few: bool) {
    let width = theirs[1] - theirs[0];
    let tol = if few { 1e-9 } else { 0.02 * width };
    for (end, a, b) in [("low", ours.low, theirs[0]), ("high", ours.high, theirs[1])] {
        assert!(
            (a - b).abs() <= tol,
            "{what}: the interval's {end} end is {a}, rliable's {b} (tolerance {tol})"
        );
    }
}

#[test]
fn mean_and_iqm_match_rliable_on_recorded_scores() -> TestResult {
    let fx = fixture()?;
    let boot = bootstrap(&fx);
    assert!(fx.sets.len() >= 6);
    for set in &fx.sets {
        let m = mean(&set.scores).ok_or("empty set")?;
        let q = iqm(&set.scores).ok_or("empty set")?;
        assert!(
            (m - set.mean).abs() < 1e-9,
            "{}: mean {m} vs {}",
            set.name,
            set.mean
        );
        assert!(
            (q - set.iqm).abs() < 1e-9,
            "{}: IQM {q} vs {}",
            set.name,
            set.iqm
        );
        let few = set.scores.len() <= 8;
        let Estimate { point, ci, n } = boot.mean(&set.scores)?;
        assert_eq!((point, n), (m, set.scores.len()));
        close_interval(&format!("{} mean", set.name), ci, set.mean_ci, few);
        let e = boot.iqm(&set.scores)?;
        assert_eq!(e.point, q);
        close_interval(&format!("{} IQM", set.name), e.ci, set.iqm_ci, few);
    }
    Ok(())
}

#[test]
fn paired_differences_match_rliable_and_keep_each_seed_together() -> TestResult {
    let fx = fixture()?;
    let boot = bootstrap(&fx);
    let scores = |name: &str| {
        fx.sets
            .iter()
            .find(|s| s.name == name)
            .map(|s| s.scores.clone())
            .ok_or(format!("no set {name}"))
    };
    for case in &fx.paired {
        let (arm, baseline) = (scores(&case.arm)?, scores(&case.baseline)?);
        let p = boot.paired(&arm, &baseline)?;
        for (a, b) in p.differences.iter().zip(&case.differences) {
            assert!((a - b).abs() < 1e-9);
        }
        assert!((p.mean_difference - case.mean_difference).abs() < 1e-9);
        close_interval(
            &format!("{} − {}", case.arm, case.baseline),
            p.ci,
            case.ci,
            case.differences.len() <= 8,
        );
        // The verdict a lesson would state is rliable's on every recorded pair.
        let verdict_theirs = case.ci[0] > 0.0 || case.ci[1] < 0.0;
        assert_eq!(p.ci.excludes_zero(), verdict_theirs, "{}", case.arm);
    }
    Ok(())
}
