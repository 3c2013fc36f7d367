//! The numbers the lessons quote, computed here. Each test runs the experiment a lesson
//! describes and checks that the lesson's sentence states its result, so a change to the
//! PPO or to the text that makes a claim false fails.
//!
//! The three long multi-seed tests (the clip lab's experiments, about 60 s; the entropy and
//! gradient-clipping switches over five seeds, about 40 s; Pendulum's seed 2 beside the
//! others, about 15 s) run in the full tier only: `cargo test --features full-tests`.

use ppo_tutor::i18n::{Lang, t};
use ppo_tutor::plot::smoothed_returns;
use ppo_tutor::ppo::lab::{self, ArmResult, Experiment, LabResult, paired_words};
use ppo_tutor::ppo::seeds::{SeedRun, mean_std, train_seeds};
use ppo_tutor::ppo::{PpoConfig, Trainer, UpdateTrace};
use ppo_tutor::stats::{Bootstrap, Paired};

type TestResult = Result<(), Box<dyn std::error::Error>>;

const LOSSES: &str = include_str!("../lessons/12-losses/lesson.md");
const TRAINING: &str = include_str!("../lessons/14-training/lesson.md");
const TRUST_REGION: &str = include_str!("../lessons/10-trust-region/lesson.md");
const TRUST_REGION_ZH: &str = include_str!("../lessons/10-trust-region/lesson.zh.md");

/// `text` with every run of whitespace one space (lessons wrap lines anywhere).
fn flat(text: &str) -> String {
    text.split_whitespace().collect::<Vec<_>>().join(" ")
}

fn says(lesson: &str, file: &str, claim: &str) {
    assert!(
        flat(lesson).contains(claim),
        "{file} should say {claim:?} (the figure the experiment gives)"
    );
}

/// [`says`] for several claims at once, naming every one the lesson does not state.
fn says_all(lesson: &str, file: &str, claims: &[String]) {
    let text = flat(lesson);
    let missing: Vec<&String> = claims
        .iter()
        .filter(|c| !text.contains(c.as_str()))
        .collect();
    assert!(
        missing.is_empty(),
        "{file} should say each of {missing:#?} (the figures the experiment gives)"
    );
}

fn percent(part: usize, whole: usize) -> String {
    format!("{:.0}%", 100.0 * part as f64 / whole as f64)
}

/// What the lessons count over the first `EPISODES` episodes of seeds 0–4.
#[derive(Debug, Default)]
struct Updates {
    updates: usize,
    /// Updates whose critic loss rose from one epoch to the next at least once.
    critic_rose: usize,
    /// Updates whose last epoch's critic loss is below the first's.
    critic_ended_lower: usize,
    /// Updates whose last epoch left a ratio outside [1 − ε, 1 + ε].
    ratio_outside: usize,
    /// Rows outside the band after the last epoch, and all rows.
    rows_outside: usize,
    rows: usize,
    /// The largest |r − 1| after a last epoch.
    farthest: f32,
    /// The mean over seeds of the mean return of the last 50 episodes.
    late_return: f64,
}

const SEEDS: u64 = 5;
const EPISODES: usize = 150;

fn count(config: &PpoConfig) -> Result<Updates, Box<dyn std::error::Error>> {
    let eps = config.eps as f32;
    let mut u = Updates::default();
    for seed in 0..SEEDS {
        let mut trainer = Trainer::new(
            PpoConfig {
                num_episodes: EPISODES,
                ..config.clone()
            },
            seed,
        )?;
        while let Some(report) = trainer.next_episode()? {
            let epochs = &report.trace.epochs;
            let (Some(first), Some(last)) = (epochs.first(), epochs.last()) else {
                continue;
            };
            u.updates += 1;
            if epochs
                .windows(2)
                .any(|w| w[1].critic_loss > w[0].critic_loss)
            {
                u.critic_rose += 1;
            }
            if last.critic_loss < first.critic_loss {
                u.critic_ended_lower += 1;
            }
            let outside = last
                .ratio
                .iter()
                .filter(|r| (**r - 1.0).abs() > eps)
                .count();
            u.ratio_outside += usize::from(outside > 0);
            u.rows_outside += outside;
            u.rows += last.ratio.len();
            for r in &last.ratio {
                u.farthest = u.farthest.max((r - 1.0).abs());
            }
        }
        u.late_return += trainer.summary().mean_last(50) / SEEDS as f64;
    }
    Ok(u)
}

/// Lesson 12: the critic loss zigzags over the ten epochs at critic_lr 1e-2 though it ends
/// lower; at 1e-3 it rises less often and the returns climb more slowly. And the clip does
/// not bound the ratio: last epochs leave ratios outside the band.
#[test]
fn the_losses_lesson_states_what_the_runs_show() -> TestResult {
    let fast = count(&PpoConfig::default())?;
    let slow = count(&PpoConfig {
        critic_lr: 1e-3,
        ..PpoConfig::default()
    })?;
    let n = fast.updates;
    assert_eq!(n, SEEDS as usize * EPISODES);
    assert_eq!(slow.updates, n);
    let file = "lessons/12-losses/lesson.md";
    says(
        LOSSES,
        file,
        &format!("first {EPISODES} episodes of seeds 0–4 ({n} updates)"),
    );
    says(
        LOSSES,
        file,
        &format!(
            "in {} updates ({}), although the tenth epoch still ended below the first in {} ({})",
            fast.critic_rose,
            percent(fast.critic_rose, n),
            fast.critic_ended_lower,
            percent(fast.critic_ended_lower, n)
        ),
    );
    assert!(slow.critic_rose < fast.critic_rose, "{slow:?} vs {fast:?}");
    says(
        LOSSES,
        file,
        &format!(
            "rarer, {} of {n} updates ({})",
            slow.critic_rose,
            percent(slow.critic_rose, n)
        ),
    );
    assert!(slow.late_return < fast.late_return, "{slow:?} vs {fast:?}");
    says(
        LOSSES,
        file,
        &format!(
            "drops from {:.0} to {:.0}",
            fast.late_return, slow.late_return
        ),
    );
    says(
        LOSSES,
        file,
        &format!(
            "in {} of {n} updates ({}), {:.1}% of all rows, and the farthest ratio was {:.2} away from 1",
            fast.ratio_outside,
            percent(fast.ratio_outside, n),
            100.0 * fast.rows_outside as f64 / fast.rows as f64,
            fast.farthest
        ),
    );
    Ok(())
}

/// Lesson 11: min(surr1, surr2) picks surr2 exactly on the rows whose ratio left the band
/// in the direction the advantage favours; rows that left it the other way keep surr1
/// (so counting rows where surr1 ≠ surr2 overcounts).
#[test]
fn min_picks_surr2_only_where_the_advantage_favours_the_move() -> TestResult {
    let config = PpoConfig::default();
    let eps = config.eps as f32;
    let mut trainer = Trainer::new(config, 0)?;
    let mut kept_surr1 = 0;
    for _ in 0..30 {
        let Some(report) = trainer.next_episode()? else {
            break;
        };
        let trace: &UpdateTrace = &report.trace;
        for epoch in &trace.epochs {
            let picked_surr2 = epoch
                .surr1
                .iter()
                .zip(&epoch.surr2)
                .filter(|(s1, s2)| s2 < s1)
                .count();
            let favoured = epoch
                .ratio
                .iter()
                .zip(&trace.advantage)
                .filter(|(r, a)| (**a > 0.0 && **r > 1.0 + eps) || (**a < 0.0 && **r < 1.0 - eps))
                .count();
            assert_eq!(picked_surr2, favoured);
            kept_surr1 += epoch
                .surr1
                .iter()
                .zip(&epoch.surr2)
                .filter(|(s1, s2)| s1 < s2)
                .count();
        }
    }
    assert!(kept_surr1 > 0, "no row left the band against its advantage");
    Ok(())
}

/// Lesson 8 quotes the λ-return's horizon 1/(1 − γλ) for the seed's settings twice, with one
/// value; lesson 11 says a row below the band was made at least ε less likely.
#[test]
fn the_gae_and_clipping_lessons_quote_their_settings_one_way() -> TestResult {
    let config = PpoConfig::default();
    let gae = flat(include_str!("../lessons/08-gae/lesson.md"));
    let horizon = format!(
        "1/(1 − γλ) ≈ {:.1} steps",
        1.0 / (1.0 - config.gamma * config.lmbda)
    );
    let quoted = gae.matches("1/(1 − γλ) ≈").count();
    assert_eq!(quoted, 2, "lesson 8 quotes the horizon twice");
    assert_eq!(
        gae.matches(&horizon).count(),
        quoted,
        "lessons/08-gae/lesson.md should write every 1/(1 − γλ) as {horizon:?}"
    );
    says(
        include_str!("../lessons/11-clipping/lesson.md"),
        "lessons/11-clipping/lesson.md",
        &format!(
            "has been made at least {:.0}% less likely already",
            100.0 * config.eps
        ),
    );
    Ok(())
}

/// Lesson 3's `sample_action` spec (the starter's doc comment) states what the reference does
/// at its edges: no action of probability 0 while `u` is below the sum, and the last action,
/// whatever its probability, when rounding leaves the sum below `u`.
#[test]
fn the_sample_action_spec_states_what_the_reference_does() -> TestResult {
    use ppo_tutor::grade::solutions::episode_loop::sample_action;
    assert_eq!(
        sample_action(&[0.0, 1.0], 0.0),
        1,
        "u on a zero-width piece"
    );
    assert_eq!(
        sample_action(&[0.5, 0.0, 0.5], 0.5),
        2,
        "u on a zero-width piece"
    );
    let short = [0.6_f32, 0.399_99, 0.0];
    let u = 0.999_995_f32;
    assert!(short.iter().sum::<f32>() < u);
    assert_eq!(
        sample_action(&short, u),
        2,
        "past the sum: the last action, of probability 0"
    );
    let doc: Vec<&str> = include_str!("../lessons/03-episode-loop/exercise.rs")
        .lines()
        .filter_map(|line| line.trim_start().strip_prefix("///"))
        .collect();
    let doc = doc.join(" ");
    for claim in [
        "while `u` is below the probabilities' sum, an action of probability 0 is never returned",
        "return the last action, whatever its probability",
    ] {
        says(&doc, "lessons/03-episode-loop/exercise.rs", claim);
    }
    Ok(())
}

/// Lesson 13's reference solution, `reverse_kl` among them.
#[allow(unused, clippy::all, clippy::pedantic)]
#[path = "../lessons/13-clip-lab/solution.rs"]
mod clip_lab_solution;

/// The learner-like wrong `reverse_kl`s of the catalogue whose hints say what they average
/// to, and the reference.
#[allow(clippy::all, clippy::pedantic)]
mod reverse_kl {
    pub(crate) use super::clip_lab_solution as right;
    pub mod forward_direction {
        include!("wrong_answers/reverse_kl/forward_direction.rs");
    }
    pub mod no_correction {
        include!("wrong_answers/reverse_kl/no_correction.rs");
    }
    pub mod unweighted_log_ratio {
        include!("wrong_answers/reverse_kl/unweighted_log_ratio.rs");
    }
    pub mod correction_sign_flipped {
        include!("wrong_answers/reverse_kl/correction_sign_flipped.rs");
    }
}

/// Lesson 13's `reverse_kl`: over actions drawn from π_old, the answer averages to
/// KL(π_θ ‖ π_old) and no row of it is negative; the hints say what each catalogued wrong
/// estimator averages to instead (approx_kl's term to the other direction, log r alone to
/// −KL(π_old ‖ π_θ)) or where it goes negative (r·log r alone, the flipped correction). Exact
/// means under π_old for (π_old, π_θ) over two actions, each term computed row by row by the
/// learner's code.
#[test]
fn the_reverse_kl_estimators_average_to_what_their_hints_say() -> TestResult {
    type Estimator = fn(&[f32], &[f32]) -> f32;
    // The mean under π_old of an estimator on one row.
    let under_old = |f: Estimator, old: &[f64], new: &[f64]| -> f64 {
        old.iter()
            .zip(new)
            .map(|(&p, &q)| p * f64::from(f(&[p.ln() as f32], &[q.ln() as f32])))
            .sum()
    };
    let kl = |p: &[f64], q: &[f64]| -> f64 { p.iter().zip(q).map(|(a, b)| a * (a / b).ln()).sum() };
    let close = |got: f64, want: f64| (got - want).abs() < 1e-5 + 1e-4 * want.abs();
    for (old, new) in [
        ([0.95, 0.05], [0.5, 0.5]),
        ([0.5, 0.5], [0.48, 0.52]),
        ([0.3, 0.7], [0.8, 0.2]),
    ] {
        let (reverse, forward) = (kl(&new, &old), kl(&old, &new));
        let means = [
            (
                "the answer",
                under_old(reverse_kl::right::reverse_kl, &old, &new),
                reverse,
            ),
            (
                "r·log r alone",
                under_old(reverse_kl::no_correction::reverse_kl, &old, &new),
                reverse,
            ),
            (
                "the flipped correction",
                under_old(reverse_kl::correction_sign_flipped::reverse_kl, &old, &new),
                reverse,
            ),
            (
                "approx_kl's term",
                under_old(reverse_kl::forward_direction::reverse_kl, &old, &new),
                forward,
            ),
            (
                "log r alone",
                under_old(reverse_kl::unweighted_log_ratio::reverse_kl, &old, &new),
                -forward,
            ),
        ];
        for (what, got, want) in means {
            assert!(
                close(got, want),
                "{what} over {old:?} → {new:?}: {got} vs {want}"
            );
        }
    }
    // The two directions part on a large move: approx_kl's term is not the answer.
    let (old, far) = ([0.95, 0.05], [0.5, 0.5]);
    let (reverse, forward) = (kl(&far, &old), kl(&old, &far));
    assert!(
        (forward - reverse).abs() > 0.2 * reverse,
        "{forward} vs {reverse}"
    );
    // Row by row: the answer is 0 at r = 1 and positive elsewhere; r·log r alone and the
    // flipped correction go negative where the action became less likely (r < 1).
    let row = |f: Estimator, x: f32| f(&[-1.0], &[-1.0 + x]);
    assert_eq!(row(reverse_kl::right::reverse_kl, 0.0), 0.0);
    for x in [-3.0, -1.0, -0.5, -0.1, 0.1, 0.5, 1.0] {
        assert!(row(reverse_kl::right::reverse_kl, x) > 0.0, "log r = {x}");
    }
    for x in [-1.0, -0.5, -0.1] {
        let alone = row(reverse_kl::no_correction::reverse_kl, x);
        let flipped = row(reverse_kl::correction_sign_flipped::reverse_kl, x);
        assert!(
            flipped < alone && alone < 0.0,
            "log r = {x}: {flipped}, {alone}"
        );
    }
    let toml = include_str!("../lessons/13-clip-lab/exercise.toml");
    let file = "lessons/13-clip-lab/exercise.toml";
    for claim in [
        "r·log r is unbiased: its mean over π_old's actions is KL(π_θ ‖ π_old). But a row whose action became less likely (r < 1) gives a negative term",
        "over π_old's actions log r averages to −KL(π_old ‖ π_θ), which is never positive",
        "This is approx_kl, (r − 1) − log r, the estimate of KL(π_old ‖ π_θ)",
        "where r < 1, r·log r and r − 1 are both negative, and adding them makes the row more negative",
        "r·log r − (r − 1) is 0 at r = 1 and positive everywhere else",
    ] {
        says(toml, file, claim);
    }
    Ok(())
}

/// The seed's settings over seeds 0–4, 500 episodes each, trained once for every test that
/// needs them.
fn default_runs() -> Result<&'static [SeedRun], String> {
    static RUNS: std::sync::OnceLock<Result<Vec<SeedRun>, String>> = std::sync::OnceLock::new();
    RUNS.get_or_init(|| five_seeds(&PpoConfig::default()))
        .as_deref()
        .map_err(Clone::clone)
}

fn five_seeds(config: &PpoConfig) -> Result<Vec<SeedRun>, String> {
    first_seeds(config, SEEDS)
}

/// Seeds `0..n` of `config` (its `num_episodes` each), two runs at a time.
fn first_seeds(config: &PpoConfig, n: u64) -> Result<Vec<SeedRun>, String> {
    let seeds: Vec<u64> = (0..n).collect();
    train_seeds(config, &seeds, 2, |_, _| {}).map_err(|e| e.to_string())
}

/// The episodes of a run from its first 500-step episode on (none if it never reaches 500).
fn after_first_500(run: &SeedRun) -> &[f64] {
    let returns = &run.summary.returns;
    let first = returns
        .iter()
        .position(|&x| x >= 500.0)
        .unwrap_or(returns.len());
    &returns[first..]
}

/// Each run's episodes with a return below 250 after its first 500.
fn late_falls_of(runs: &[SeedRun]) -> Vec<usize> {
    runs.iter()
        .map(|r| after_first_500(r).iter().filter(|&&x| x < 250.0).count())
        .collect()
}

/// Episodes with a return below 250 after each run's first 500, over all runs.
fn late_falls(runs: &[SeedRun]) -> usize {
    late_falls_of(runs).iter().sum()
}

/// Lessons 14 and 16: the truncation fix (and advantage normalisation, and both) against
/// the seed's rule over the same seeds 0–4, 500 episodes each: the runs are identical until
/// their first 500-step episode; after it, how many episodes stay at 500 and how many fall
/// below 250. About 15 runs on the plain path, a few seconds.
#[test]
fn the_truncation_fix_is_measured_over_the_same_seeds() -> TestResult {
    let seed = default_runs()?;
    let fixed = five_seeds(&PpoConfig {
        bootstrap_on_truncation: true,
        ..PpoConfig::default()
    })?;
    let normalised = five_seeds(&PpoConfig {
        normalize_advantage: true,
        ..PpoConfig::default()
    })?;
    let both = five_seeds(&PpoConfig {
        bootstrap_on_truncation: true,
        normalize_advantage: true,
        ..PpoConfig::default()
    })?;
    // No target differs before the first truncated episode, so neither does the run.
    for (a, b) in seed.iter().zip(&fixed) {
        let (ra, rb) = (&a.summary.returns, &b.summary.returns);
        let first = ra.len() - after_first_500(a).len();
        assert!(first < ra.len(), "seed {} reaches 500", a.seed);
        assert_eq!(ra[..=first], rb[..=first], "seed {}", a.seed);
    }
    let at_500 = |runs: &[SeedRun]| -> (usize, usize) {
        runs.iter().fold((0, 0), |(n, all), r| {
            let after = after_first_500(r);
            (
                n + after.iter().filter(|&&x| x >= 500.0).count(),
                all + after.len(),
            )
        })
    };
    let fewer_than_seed = |runs: &[SeedRun]| {
        late_falls_of(runs)
            .iter()
            .zip(late_falls_of(seed))
            .filter(|(a, b)| **a < *b)
            .count()
    };
    let ((seed_at, seed_all), (fixed_at, fixed_all)) = (at_500(seed), at_500(&fixed));
    assert_eq!(seed_all, fixed_all);
    let (seed_falls, fixed_falls) = (late_falls(seed), late_falls(&fixed));
    eprintln!(
        "late falls: seed {:?}, fixed {:?}, normalised {:?}, both {:?}; at 500: {seed_at} and \
         {fixed_at} of {seed_all}",
        late_falls_of(seed),
        late_falls_of(&fixed),
        late_falls_of(&normalised),
        late_falls_of(&both)
    );
    let fewer = fewer_than_seed(&fixed);
    says(
        include_str!("../lessons/16-beyond-the-seed/lesson.md"),
        "lessons/16-beyond-the-seed/lesson.md",
        &format!(
            "After it, {fixed_at} of the {seed_all} episodes reach 500, against {seed_at} with the \
             seed's `done`, and {fixed_falls} fall below 250, against {seed_falls}: fewer falls on \
             {fewer} of the 5 seeds, more on {}",
            SEEDS as usize - fewer
        ),
    );
    let file = "lessons/14-training/lesson.md";
    says(
        TRAINING,
        file,
        &format!("go from {seed_falls} to {fixed_falls}"),
    );
    assert_eq!(
        fewer_than_seed(&both),
        SEEDS as usize,
        "both: fewer on every seed"
    );
    let (norm_falls, both_falls) = (late_falls(&normalised), late_falls(&both));
    assert!(both_falls < norm_falls && norm_falls < fixed_falls);
    says(
        TRAINING,
        file,
        &format!(
            "takes them to {norm_falls}, and both fixes together to {both_falls}, fewer on every seed"
        ),
    );
    // Falls still happen with both: every seed's moving average (as lesson 14 counts its
    // falls) dips below 450 after its first 500.
    let dips = both
        .iter()
        .filter(|r| {
            let returns = &r.summary.returns;
            let first = returns.len() - after_first_500(r).len();
            smoothed_returns(returns)[first..]
                .iter()
                .any(|&m| m < 450.0)
        })
        .count();
    assert_eq!(dips, SEEDS as usize, "with both fixes");
    says(
        TRAINING,
        file,
        "though every seed's moving average still dips below 450",
    );
    Ok(())
}

/// Lesson 14: over seeds 0–4, neither the entropy bonus nor gradient-norm clipping helps the
/// seed's update on CartPole.
#[test]
#[cfg_attr(
    not(feature = "full-tests"),
    ignore = "full tier (cargo test --features full-tests): 15 runs of 500 episodes, about 40 s"
)]
fn the_beyond_lesson_states_what_the_switches_do_over_five_seeds() -> TestResult {
    let entropy = five_seeds(&PpoConfig {
        entropy_coef: 0.01,
        ..PpoConfig::default()
    })?;
    let clipped = five_seeds(&PpoConfig {
        max_grad_norm: Some(0.5),
        ..PpoConfig::default()
    })?;
    let runs = [default_runs()?, &entropy[..], &clipped[..]];
    let summary: Vec<String> = runs
        .iter()
        .map(|r| {
            let ends: Vec<f64> = r.iter().map(|s| s.summary.mean_last(50)).collect();
            let (m, s) = mean_std(&ends);
            format!("{m:.1} ± {s:.1}")
        })
        .collect();
    let lesson = include_str!("../lessons/16-beyond-the-seed/lesson.md");
    let file = "lessons/16-beyond-the-seed/lesson.md";
    says(
        lesson,
        file,
        &format!(
            "{} with neither, {} with the entropy bonus and {} with gradient clipping",
            summary[0], summary[1], summary[2]
        ),
    );
    says(
        lesson,
        file,
        &format!(
            "the late falls remain: {}, {} and {} episodes below 250",
            late_falls(runs[0]),
            late_falls(runs[1]),
            late_falls(runs[2])
        ),
    );
    Ok(())
}

/// Lesson 14, step 3: how fast five seeds learn, and their falls after first reaching 500
/// (the seed's settings, seeds 0–4, 500 episodes each, the cached default runs).
#[test]
fn the_training_lesson_states_what_five_seeds_show() -> TestResult {
    let runs = default_runs()?;
    let (mut first_500, mut reached_450, mut fell_to, mut ends) = (vec![], vec![], vec![], vec![]);
    let mut fell = 0;
    for run in runs {
        let returns = &run.summary.returns;
        let smooth = smoothed_returns(returns);
        let first = returns
            .iter()
            .position(|&r| r >= 500.0)
            .ok_or("a seed never reached 500")?;
        first_500.push(first + 1);
        let at_450 = smooth
            .iter()
            .position(|&m| m >= 450.0)
            .ok_or("a seed never reached 450")?;
        reached_450.push(at_450 + 1);
        let lowest_after = smooth[first..]
            .iter()
            .copied()
            .fold(f64::INFINITY, f64::min);
        if lowest_after < 450.0 {
            fell += 1;
            fell_to.push(lowest_after);
        }
        ends.push(run.summary.mean_last(50));
    }
    let range = |v: &[usize]| (v.iter().min().copied(), v.iter().max().copied());
    let (lo, hi) = range(&first_500);
    let (lo450, hi450) = range(&reached_450);
    let low = |v: &[f64]| v.iter().copied().fold(f64::INFINITY, f64::min);
    let high = |v: &[f64]| v.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let file = "lessons/14-training/lesson.md";
    says(
        TRAINING,
        file,
        &format!(
            "between episodes {} and {}, but its moving average first reached 450 only between episodes {} and {}",
            lo.unwrap_or(0),
            hi.unwrap_or(0),
            lo450.unwrap_or(0),
            hi450.unwrap_or(0)
        ),
    );
    says(
        TRAINING,
        file,
        &format!(
            "{fell} of the {SEEDS} seeds later fell back, to between {:.0} and {:.0}",
            low(&fell_to),
            high(&fell_to)
        ),
    );
    says(
        TRAINING,
        file,
        &format!(
            "a mean return of {:.1} to {:.1} over their last 50 episodes",
            low(&ends),
            high(&ends)
        ),
    );
    // The seed with the earliest first 500 is the last whose moving average reaches 450.
    let earliest = (0..runs.len())
        .min_by_key(|&i| first_500[i])
        .ok_or("no runs")?;
    assert_eq!(
        Some(reached_450[earliest]),
        hi450,
        "the earliest first 500 (seed {}) is not the last to reach 450: {reached_450:?}",
        runs[earliest].seed
    );
    says(
        TRAINING,
        file,
        &format!(
            "seed {} played the earliest 500 of the five, at episode {}, yet its moving average was the last to reach 450, at episode {}",
            runs[earliest].seed, first_500[earliest], reached_450[earliest]
        ),
    );
    // Step 4's question states seeds 0–4's late falls before the learner trains seeds 5–9.
    says(
        TRAINING,
        file,
        &format!("Seeds 0–4 have {} such episodes", late_falls(runs)),
    );
    Ok(())
}

/// Lesson 14, step 4: the same setting on seeds 5–9 beside seeds 0–4. Two draws of five
/// seeds differ in their late falls by more than the truncation fix changes them, and by
/// less than half of what both fixes do.
#[test]
#[cfg_attr(
    not(feature = "full-tests"),
    ignore = "full tier (cargo test --features full-tests): 15 runs of 500 episodes, about 40 s"
)]
fn the_training_lesson_states_what_a_second_draw_of_seeds_shows() -> TestResult {
    let first = default_runs()?;
    let seeds: Vec<u64> = (SEEDS..2 * SEEDS).collect();
    let second = train_seeds(&PpoConfig::default(), &seeds, 2, |_, _| {})?;
    let fixed = five_seeds(&PpoConfig {
        bootstrap_on_truncation: true,
        ..PpoConfig::default()
    })?;
    let both = five_seeds(&PpoConfig {
        bootstrap_on_truncation: true,
        normalize_advantage: true,
        ..PpoConfig::default()
    })?;
    let end = |runs: &[SeedRun]| {
        let ends: Vec<f64> = runs.iter().map(|r| r.summary.mean_last(50)).collect();
        let (m, s) = mean_std(&ends);
        format!("{m:.1} ± {s:.1}")
    };
    let (a, b) = (late_falls(first), late_falls(&second));
    let gap = a.abs_diff(b);
    let file = "lessons/14-training/lesson.md";
    says(
        TRAINING,
        file,
        &format!(
            "Seeds 5–9 end at {} over their last 50 episodes, against {} for seeds 0–4",
            end(&second),
            end(first)
        ),
    );
    says(
        TRAINING,
        file,
        &format!(
            "{b} of their episodes fall below 250, against {a} for seeds 0–4: two draws of five \
             seeds from one and the same setting differ by {gap} falls"
        ),
    );
    // Every seed of the second draw falls back too, as step 3 counts falls.
    let fell = second
        .iter()
        .filter(|r| {
            let returns = &r.summary.returns;
            let start = returns.len() - after_first_500(r).len();
            start < returns.len()
                && smoothed_returns(returns)[start..]
                    .iter()
                    .any(|&m| m < 450.0)
        })
        .count();
    says(
        TRAINING,
        file,
        &format!("Their moving averages fell back too, {fell} of the {SEEDS}"),
    );
    // The five-seed interaction the lesson describes (the fix removes more falls with the
    // normalisation on than without): its figures, before ten seeds pair it
    // (the_fixes_and_switches_are_compared_over_ten_seeds).
    let norm = five_seeds(&PpoConfig {
        normalize_advantage: true,
        ..PpoConfig::default()
    })?;
    let (with_norm, without) = (
        late_falls(&norm) - late_falls(&both),
        a - late_falls(&fixed),
    );
    says(
        TRAINING,
        file,
        &format!(
            "the fix removes {with_norm} falls with the normalisation on ({} to {}) against \
             {without} without it",
            late_falls(&norm),
            late_falls(&both)
        ),
    );
    Ok(())
}

/// Lesson 5: a loop that ends episodes on `terminated` alone runs past CartPole-v1's time
/// limit with a policy that balances, so its return exceeds 500 (the notebook's policy).
#[test]
fn ignoring_truncation_lets_a_return_exceed_500() -> TestResult {
    use ppo_tutor::env::{CartPole, EnvId};
    let balance = |o: [f32; 4]| usize::from(0.05 * o[0] + 0.1 * o[1] + o[2] + 0.5 * o[3] > 0.0);
    for seed in 0..SEEDS {
        let mut env = CartPole::new(EnvId::CartPoleV1);
        let mut obs = env.reset(Some(seed));
        let (mut steps, mut truncated_at) = (0, None);
        while steps < 2000 {
            let step = env.step(balance(obs))?;
            steps += 1;
            obs = step.obs;
            if step.truncated && truncated_at.is_none() {
                truncated_at = Some(steps);
            }
            if step.terminated {
                break;
            }
        }
        assert_eq!(
            truncated_at,
            Some(500),
            "seed {seed}: Gymnasium truncates at 500"
        );
        assert!(steps > 500, "seed {seed}: the loop stopped at {steps}");
    }
    let lesson = include_str!("../lessons/02-cartpole/lesson.md");
    says(
        lesson,
        "lessons/02-cartpole/lesson.md",
        "its return exceeds 500",
    );
    Ok(())
}

/// Lesson 14: the policy's entropy starts near ln 2 (even odds) and falls as it grows surer
/// (seeds 0–4, the first and the last 50 of the first 150 updates).
#[test]
fn the_entropy_starts_at_even_odds_and_falls() -> TestResult {
    for seed in 0..SEEDS {
        let config = PpoConfig {
            num_episodes: EPISODES,
            ..PpoConfig::default()
        };
        let first_epochs: Vec<f32> = Trainer::new(config, seed)?
            .map(|r| r.map(|r| r.trace.epochs[0].entropy))
            .collect::<Result<_, _>>()?;
        let start = first_epochs[0];
        assert!(
            (f64::from(start) - std::f64::consts::LN_2).abs() < 0.03,
            "seed {seed}: entropy {start} at the start"
        );
        let mean = |v: &[f32]| v.iter().sum::<f32>() / v.len() as f32;
        let (early, late) = (mean(&first_epochs[..50]), mean(&first_epochs[100..]));
        assert!(late < early, "seed {seed}: {late} late vs {early} early");
    }
    let lesson = include_str!("../lessons/16-beyond-the-seed/lesson.md");
    says(
        lesson,
        "lessons/16-beyond-the-seed/lesson.md",
        "it starts near 0.69",
    );
    Ok(())
}

/// Every clip-lab experiment (lessons 4 and 13) over seeds 0–4, 500 episodes each (the lab
/// caches runs, so the base arm trains once for all five).
fn lab_runs() -> Result<Vec<LabResult>, String> {
    use Experiment::{ActorLr, Epochs, Eps, Reinforce, TargetKl};
    [Eps, Epochs, ActorLr, TargetKl, Reinforce]
        .iter()
        .map(|&e| {
            lab::run(e, &PpoConfig::default(), &[0, 1, 2, 3, 4], 2, |_, _| {})
                .map_err(|err| err.to_string())
        })
        .collect()
}

/// The number of each seed's first episode with a return of 500, counting from 1 as lesson
/// 13 and the tutor's episode counter do (one past the run's length if none).
fn first_500(arm: &ArmResult) -> Vec<usize> {
    arm.returns
        .iter()
        .map(|r| 1 + r.iter().position(|&x| x >= 500.0).unwrap_or(r.len()))
        .collect()
}

/// Lessons 4 and 13 and docs/measurements.md: what every experiment of the clip lab shows.
#[test]
#[cfg_attr(
    not(feature = "full-tests"),
    ignore = "full tier (cargo test --features full-tests): every clip-lab experiment over its seeds, about 60 s"
)]
fn the_lab_lessons_state_what_the_experiments_show() -> TestResult {
    let labs = lab_runs()?;
    let get = |e: Experiment| labs.iter().find(|l| l.experiment == e).ok_or("missing lab");
    let (eps, epochs, lr, kl, reinforce) = (
        get(Experiment::Eps)?,
        get(Experiment::Epochs)?,
        get(Experiment::ActorLr)?,
        get(Experiment::TargetKl)?,
        get(Experiment::Reinforce)?,
    );
    let lab_file = "lessons/13-clip-lab/lesson.md";
    let lab_text = include_str!("../lessons/13-clip-lab/lesson.md");
    let pg_file = "lessons/04-policy-gradient/lesson.md";
    let pg_text = include_str!("../lessons/04-policy-gradient/lesson.md");
    let measurements = include_str!("../docs/measurements.md");
    for l in [eps, epochs, lr, kl] {
        for arm in &l.arms {
            says(lab_text, lab_file, &arm.summary());
        }
    }
    for arm in &reinforce.arms {
        says(pg_text, pg_file, &arm.summary());
    }
    // The table of docs/measurements.md: every changed setting, and the base once.
    for arm in labs.iter().flat_map(|l| l.arms.iter()) {
        let (m, s) = arm.final_mean_std();
        let reach = arm
            .first_reaching(400.0)
            .map_or("never reaches 400".into(), |e| {
                format!("reaches 400 at episode {e}")
            });
        says(
            measurements,
            "docs/measurements.md",
            &format!(
                "{m:.1} ± {s:.1}, worst seed {:.1}; {reach}",
                arm.worst_final()
            ),
        );
    }

    // Experiment 1: the clip range.
    let [base, narrow, none] = &eps.arms[..] else {
        return Err("eps has three arms".into());
    };
    let (b, n, o) = (
        base.mean_updates(),
        narrow.mean_updates(),
        none.mean_updates(),
    );
    says(
        lab_text,
        lab_file,
        &format!(
            "clips {:.3} of the rows on average, against {:.3} with ε = 0.2",
            n.clip_fraction, b.clip_fraction
        ),
    );
    says(
        lab_text,
        lab_file,
        &format!(
            "largest |r − 1| averages {:.3} against {:.3}, and approx_kl {:.4} against {:.4}",
            o.max_ratio_deviation, b.max_ratio_deviation, o.approx_kl, b.approx_kl
        ),
    );
    assert!(
        first_500(narrow)
            .iter()
            .zip(first_500(base))
            .all(|(n, b)| *n > b),
        "ε = 0.05 reaches 500 later on every seed"
    );
    let top = |a: &ArmResult| a.final_mean_std();
    assert!(
        top(base).0 > top(narrow).0
            && top(base).0 > top(none).0
            && top(base).1 < top(narrow).1.min(top(none).1)
    );
    says(
        lab_text,
        lab_file,
        &format!("all five seeds end at {:.1} or above", base.worst_final()),
    );
    says(
        lab_text,
        lab_file,
        &format!(
            "the worst seed ends at {:.1} and {:.1}",
            narrow.worst_final(),
            none.worst_final()
        ),
    );

    // Experiment 2: epochs, then one network's epochs at a time.
    let [ten, one, forty, actor_one, critic_one, _long_step] = &epochs.arms[..] else {
        return Err("epochs has six arms".into());
    };
    assert_eq!(
        (
            actor_one.config.epochs_of_each(),
            critic_one.config.epochs_of_each()
        ),
        ((1, 10), (10, 1))
    );
    let (t, f) = (ten.mean_updates(), forty.mean_updates());
    assert!(one.first_reaching(400.0).is_none() && top(one).0 < top(ten).0);
    let span = |a: &ArmResult| {
        let f = first_500(a);
        (
            f.iter().copied().min().unwrap_or(0),
            f.iter().copied().max().unwrap_or(0),
        )
    };
    let (one_span, actor_one_span, critic_one_span, ten_span) =
        (span(one), span(actor_one), span(critic_one), span(ten));
    // The actor's steps are the speed: with ten actor steps every seed plays its first
    // 500-step episode sooner than with one (whatever the critic's), and ten critic steps
    // do not bring one actor step near the seed. (What in the ten steps, their reuse of the
    // episode or their length, is paired over ten seeds in
    // `the_lessons_order_only_what_ten_seeds_show`.)
    for (seed, ((a10, a1), both1)) in first_500(critic_one)
        .iter()
        .zip(first_500(actor_one))
        .zip(first_500(one))
        .enumerate()
    {
        assert!(
            *a10 < a1 && *a10 < both1,
            "seed {seed}: {a10} vs {a1}, {both1}"
        );
    }
    assert!(actor_one_span.0 > 4 * ten_span.1, "{actor_one_span:?}");
    assert!(actor_one.first_reaching(400.0).is_none());
    // The critic's reuse shows at the end: one critic step ends lower and wider.
    assert!(top(critic_one).0 < top(ten).0 && top(critic_one).1 > 10.0 * top(ten).1);
    says(
        lab_text,
        lab_file,
        &format!(
            "their first 500-step episode comes between episode {} and {}, against {} and {}",
            actor_one_span.0, actor_one_span.1, one_span.0, one_span.1
        ),
    );
    says(
        lab_text,
        lab_file,
        &format!(
            "it comes between episode {} and {}, nearer the seed's {} to {}",
            critic_one_span.0, critic_one_span.1, ten_span.0, ten_span.1
        ),
    );
    says(
        lab_text,
        lab_file,
        &format!("one of them at {:.1}", critic_one.worst_final()),
    );
    says(
        pg_text,
        pg_file,
        &format!(
            "its first 500-step episode comes between episode {} and {}. Ten critic steps with \
             one actor step change little on these five seeds (between {} and {}); ten actor \
             steps with one critic \
             step bring it to between {} and {}",
            one_span.0,
            one_span.1,
            actor_one_span.0,
            actor_one_span.1,
            critic_one_span.0,
            critic_one_span.1
        ),
    );
    assert!(forty.first_reaching(400.0) > ten.first_reaching(400.0));
    says(
        lab_text,
        lab_file,
        &format!(
            "approx_kl {:.4} against {:.4}, the largest |r − 1| {:.3} against {:.3}",
            f.approx_kl, t.approx_kl, f.max_ratio_deviation, t.max_ratio_deviation
        ),
    );

    // Experiment 3: actor_lr × 10.
    let big = &lr.arms[1];
    let u = big.mean_updates();
    let best = big.finals.iter().copied().fold(0.0, f64::max);
    assert!((best - 500.0).abs() < 1e-9, "one seed ends at 500");
    says(
        lab_text,
        lab_file,
        &format!("another at {:.1}", big.worst_final()),
    );
    says(
        lab_text,
        lab_file,
        &format!("approx_kl is {:.4}, ten times the seed's", u.approx_kl),
    );
    let times = u.approx_kl / t.approx_kl;
    assert!(
        (8.0..12.0).contains(&times),
        "ten times the seed's: {times}"
    );
    says(
        lab_text,
        lab_file,
        &format!(
            "largest |r − 1| averages {:.3}, far outside",
            u.max_ratio_deviation
        ),
    );

    // Experiment 4: target_kl.
    let (no_stop, stop) = (&kl.arms[1], &kl.arms[2]);
    let s = stop.mean_updates();
    says(
        lab_text,
        lab_file,
        &format!("updates ran {:.1} on average", s.epochs_run),
    );
    says(
        lab_text,
        lab_file,
        &format!(
            "approx_kl fell from {:.4} to {:.4}",
            no_stop.mean_updates().approx_kl,
            s.approx_kl
        ),
    );

    // Lesson 4: when each algorithm first reaches 500.
    let [ppo, rf] = &reinforce.arms[..] else {
        return Err("reinforce has two arms".into());
    };
    let ((rl, rh), (pl, ph)) = (span(rf), span(ppo));
    says(
        pg_text,
        pg_file,
        &format!("between episode {rl} and {rh} on the five seeds, PPO's between {pl} and {ph}"),
    );
    Ok(())
}

/// Lesson 4: on every episode of a live session, PPO's surrogate and REINFORCE's objective
/// have the same gradient at θ_old, to float rounding.
#[test]
fn the_surrogate_gradient_is_the_policy_gradient_at_theta_old() -> TestResult {
    let mut session = ppo_tutor::lesson::Session::new(PpoConfig::default(), 0)?;
    for _ in 0..20 {
        let snap = session.next_episode()?.ok_or("the run ended")?;
        let g = &snap.cartpole_update().ok_or("no gradients")?.gradients;
        assert_eq!(g.surrogate.len(), 898);
        assert!(g.max_abs() > 0.0);
        assert!(
            g.max_abs_diff() <= 1e-6 * g.max_abs(),
            "episode {}: {} vs {}",
            snap.episodes,
            g.max_abs_diff(),
            g.max_abs()
        );
    }
    says(
        include_str!("../lessons/04-policy-gradient/lesson.md"),
        "lessons/04-policy-gradient/lesson.md",
        "They agree to float rounding.",
    );
    Ok(())
}

// ---- Lessons 17 (continuous-actions) and 17 (pendulum): the book's PPOContinuous. ----

const CONTINUOUS: &str = include_str!("../lessons/17-continuous-actions/lesson.md");
const PENDULUM: &str = include_str!("../lessons/18-pendulum/lesson.md");

/// Lesson 17: how much of the last step's wrong TD error GAE carries ten steps back with the
/// book's Pendulum settings, (γλ)¹⁰.
#[test]
fn the_continuous_lesson_states_how_fast_the_truncation_error_fades() -> TestResult {
    let config = ppo_tutor::ppo::PpoContinuousConfig::default();
    let per_step = config.gamma * config.lmbda;
    says(
        CONTINUOUS,
        "lessons/17-continuous-actions/lesson.md",
        &format!(
            "with weight (γλ)^k = {per_step:.2}^k, so ten steps earlier {per_step:.2}¹⁰ ≈ {:.2} of it is left",
            per_step.powi(10)
        ),
    );
    Ok(())
}

fn pendulum_session(seed: u64) -> Result<ppo_tutor::lesson::Session, Box<dyn std::error::Error>> {
    Ok(ppo_tutor::lesson::Session::new(
        ppo_tutor::ppo::PpoContinuousConfig::default(),
        seed,
    )?)
}

fn min_max(xs: &[f32]) -> (f32, f32) {
    xs.iter()
        .fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), &x| {
            (lo.min(x), hi.max(x))
        })
}

/// The untrained policy (its first episode, played before any update) over seeds 0–4, and
/// the ratios of the first 30 updates' last epochs.
#[test]
fn the_continuous_lesson_states_what_the_first_episodes_show() -> TestResult {
    let (mut mu, mut std) = (
        (f32::INFINITY, f32::NEG_INFINITY),
        (f32::INFINITY, f32::NEG_INFINITY),
    );
    let (mut updates, mut outside) = (0, 0);
    for seed in 0..SEEDS {
        let mut session = pendulum_session(seed)?;
        for episode in 0..30 {
            let s = session.next_episode()?.ok_or("the run has 2000 episodes")?;
            let c = &s.pendulum_update().ok_or("a Pendulum snapshot")?.trace;
            if episode == 0 {
                let (lo, hi) = min_max(&c.mu);
                mu = (mu.0.min(lo), mu.1.max(hi));
                let (lo, hi) = min_max(&c.std);
                std = (std.0.min(lo), std.1.max(hi));
            }
            let last = c.last_epoch().ok_or("ten epochs")?;
            updates += 1;
            if last.ratio.iter().any(|r| !(0.8..=1.2).contains(r)) {
                outside += 1;
            }
            let first = c.epochs.first().ok_or("ten epochs")?;
            assert!(first.ratio.iter().all(|&r| r == 1.0), "epoch 1: π = π_old");
        }
    }
    eprintln!(
        "untrained μ in [{:.3}, {:.3}], σ in [{:.3}, {:.3}]; {outside} of {updates} last epochs \
         with a ratio outside [0.8, 1.2]",
        mu.0, mu.1, std.0, std.1
    );
    let file = "lessons/17-continuous-actions/lesson.md";
    assert!(mu.0 < -1.7 && mu.1 > 1.7, "μ beyond ±1.7: {mu:?}");
    says(CONTINUOUS, file, "from below −1.7 to above 1.7");
    says(
        CONTINUOUS,
        file,
        &format!("between about {:.2} and {:.2}", std.0, std.1),
    );
    says(
        CONTINUOUS,
        file,
        &format!(
            "{} of the last epochs hold a ratio outside [0.8, 1.2]",
            percent(outside, updates)
        ),
    );
    Ok(())
}

/// The mean of `r`.
fn mean(r: &[f64]) -> f64 {
    r.iter().sum::<f64>() / r.len() as f64
}

/// The first 20 episodes of seeds 0–2: the untrained policy's returns.
#[test]
fn the_pendulum_lesson_states_where_the_return_curve_starts() -> TestResult {
    for seed in 0..3 {
        let mut session = pendulum_session(seed)?;
        for _ in 0..20 {
            session.next_episode()?.ok_or("the run has 2000 episodes")?;
        }
        let first = mean(&session.snapshot().returns);
        eprintln!("seed {seed}: mean of the first 20 returns {first:.1}");
        assert!((-1500.0..=-1100.0).contains(&first), "seed {seed}: {first}");
    }
    says(
        PENDULUM,
        "lessons/18-pendulum/lesson.md",
        "first 20 episodes average between about −1100 and −1500 (seeds 0 to 2)",
    );
    Ok(())
}

/// Lesson 18 and its quiz: where the motor can hold the rod still, found with the
/// environment's own physics. From rest at θ (0 is upright), full torque against gravity
/// holds the rod where the next θ̇ does not follow gravity: within asin(0.4) of upright and of
/// hanging, and nowhere between.
#[test]
fn the_pendulum_lesson_states_where_the_motor_can_hold_the_rod() -> TestResult {
    use ppo_tutor::env::pendulum::{DEFAULT_GRAVITY, DT, MAX_TORQUE, physics};
    let accel = |theta: f64, torque: f64| physics([theta, 0.0], torque, DEFAULT_GRAVITY).0[1] / DT;
    let (motor, gravity) = (
        accel(0.0, MAX_TORQUE),
        accel(std::f64::consts::FRAC_PI_2, 0.0),
    );
    let held = |degrees: f64| {
        let theta = degrees.to_radians();
        let pull = accel(theta, 0.0).signum();
        accel(theta, -pull * MAX_TORQUE) * pull <= 0.0
    };
    // Hundredths of a degree from upright (0) to hanging (180).
    let grid: Vec<f64> = (0..=18_000).map(|i| f64::from(i) / 100.0).collect();
    let near_up = grid
        .iter()
        .take_while(|&&d| held(d))
        .last()
        .copied()
        .ok_or("not held upright")?;
    let near_down = grid
        .iter()
        .rev()
        .take_while(|&&d| held(d))
        .last()
        .copied()
        .ok_or("not held hanging")?;
    assert!(
        grid.iter()
            .all(|&d| held(d) == (d <= near_up || d >= near_down)),
        "held only near upright and near hanging"
    );
    assert!(
        (near_up - (180.0 - near_down)).abs() < 0.02,
        "{near_up} and {near_down}"
    );
    let (ratio, angle) = (motor / gravity, near_up);
    let file = "lessons/18-pendulum/lesson.md";
    says(
        PENDULUM,
        file,
        &format!(
            "only where {gravity:.0}·|sin θ| < {motor:.0}: within asin({ratio:.1}) ≈ {angle:.1}° of upright, or of hanging down"
        ),
    );
    // An eighth of a turn from upright, full torque only slows the fall.
    let eighth = accel(std::f64::consts::FRAC_PI_4, 0.0).abs();
    assert!(eighth > motor, "{eighth} against {motor}");
    says(
        PENDULUM,
        file,
        &format!("it gives {motor:.0} rad/s² against gravity's {eighth:.1}"),
    );
    says(
        include_str!("../lessons/18-pendulum/lesson.zh.md"),
        "lessons/18-pendulum/lesson.zh.md",
        &format!("它只带来 {motor:.0} rad/s² 的角加速度，而重力带来 {eighth:.1}"),
    );
    says(
        include_str!("../lessons/18-pendulum/quiz.toml"),
        "lessons/18-pendulum/quiz.toml",
        &format!(
            "15·|sin θ| < 6 only for |sin θ| < 0.4: within about {angle:.1}° of upright or of hanging"
        ),
    );
    Ok(())
}

/// The book's full run (2000 episodes) on seeds 0 and 1: the trained policy map brakes near
/// the top, pushes back toward it an eighth of a turn away (which, at full torque, only slows
/// the fall there), pumps hanging down, is mostly saturated, and its σ has shrunk.
#[test]
fn the_pendulum_lesson_states_what_a_trained_map_shows() -> TestResult {
    let file = "lessons/18-pendulum/lesson.md";
    for seed in [0, 1] {
        let mut session = pendulum_session(seed)?;
        let first = session.next_episode()?.ok_or("2000 episodes")?;
        let first_map = first.pendulum_update().ok_or("a map")?.policy_map.clone();
        while session.next_episode()?.is_some() {}
        let m = session
            .snapshot()
            .pendulum_update()
            .ok_or("a map")?
            .policy_map
            .clone();
        // Rows: θ̇ = 8, 6, ..., −8; columns: θ = −π, −3π/4, ..., π (4 is upright).
        let at = |row: usize, col: usize| m.mu[row * 9 + col];
        let mean_std = |v: &[f32]| v.iter().sum::<f32>() / v.len() as f32;
        let (before, after) = (mean_std(&first_map.std), mean_std(&m.std));
        eprintln!("seed {seed}: mean σ over the grid {before:.3} -> {after:.3}");
        for row in 0..3 {
            assert!(
                at(row, 4) < -1.5,
                "seed {seed}: brakes θ̇ > 0: {}",
                at(row, 4)
            );
            assert!(
                at(8 - row, 4) > 1.5,
                "seed {seed}: brakes θ̇ < 0: {}",
                at(8 - row, 4)
            );
        }
        assert!(
            at(4, 3) > 1.5 && at(4, 5) < -1.5,
            "seed {seed}: pushes back"
        );
        for col in [0, 8] {
            assert!(at(2, col) > 1.5 && at(6, col) < -1.5, "seed {seed}: pumps");
        }
        let saturated = m.mu.iter().filter(|v| v.abs() > 1.5).count();
        assert!(
            saturated * 2 > m.mu.len(),
            "seed {seed}: {saturated} of 81 near ±2"
        );
        assert!(
            (0.85..=1.1).contains(&before),
            "seed {seed}: about 1 at first: {before}"
        );
        says(PENDULUM, file, &format!("{after:.2} on seed {seed}"));
    }
    Ok(())
}

/// The mean of the last 100 of `returns[..n]`.
fn last_100_at(returns: &[f64], n: usize) -> f64 {
    mean(&returns[n - 100..n])
}

/// `x` to one decimal with the lessons' minus sign.
fn signed(x: f64, decimals: usize) -> String {
    format!("{x:.decimals$}").replace('-', "−")
}

/// Lesson 18: seed 2, the seed that ends far behind the others at the book's 2000 episodes,
/// is late, not broken. At episode 1000 it still plays like the untrained policy while the
/// others have learned; its σ along the states it visits has not collapsed; 400 episodes
/// past the book's budget its last 100 episodes are as good as the others'. Seeds 0, 1, 3
/// and 4 train 1000 episodes, seed 2 2400 (the first 2000 are the book's run: same seed,
/// same numbers).
#[test]
#[cfg_attr(
    not(feature = "full-tests"),
    ignore = "full tier (cargo test --features full-tests): five Pendulum runs, 6400 episodes, about 10 s"
)]
fn the_pendulum_lesson_shows_the_seed_that_fell_behind() -> TestResult {
    use std::ops::ControlFlow;
    /// A run: its seed, its returns, and σ along its episodes' states, averaged over
    /// episodes 501–1000.
    struct Run {
        seed: u64,
        returns: Vec<f64>,
        sigma: f64,
    }
    const LATE: u64 = 2;
    let runs: Vec<Run> = std::thread::scope(|scope| {
        let handles: Vec<_> = (0..SEEDS)
            .map(|seed| {
                scope.spawn(move || -> Result<Run, String> {
                    let config = ppo_tutor::ppo::PpoContinuousConfig {
                        num_episodes: if seed == LATE { 2400 } else { 1000 },
                        ..Default::default()
                    };
                    // σ along each episode's states, averaged over episodes 501–1000
                    let mut sigma = Vec::new();
                    let (summary, _) = ppo_tutor::ppo::train(config, seed, |report| {
                        if (500..1000).contains(&report.episode) {
                            let std = &report.trace.std;
                            sigma.push(f64::from(std.iter().sum::<f32>()) / std.len() as f64);
                        }
                        ControlFlow::Continue(())
                    })
                    .map_err(|e| e.to_string())?;
                    Ok(Run {
                        seed,
                        returns: summary.returns,
                        sigma: mean(&sigma),
                    })
                })
            })
            .collect();
        handles
            .into_iter()
            .map(|h| h.join().map_err(|_| "a run panicked".to_string())?)
            .collect::<Result<_, String>>()
    })?;
    let (late, others): (Vec<&Run>, Vec<&Run>) = runs.iter().partition(|r| r.seed == LATE);
    let Run { returns, sigma, .. } = late.first().ok_or("seed 2")?;
    let range = |f: &dyn Fn(&Run) -> f64| {
        others
            .iter()
            .map(|r| f(r))
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), x| {
                (lo.min(x), hi.max(x))
            })
    };
    let at_1000 = last_100_at(returns, 1000);
    let others_1000 = range(&|r| last_100_at(&r.returns, 1000));
    let others_sigma = range(&|r| r.sigma);
    let (at_2000, at_2400) = (last_100_at(returns, 2000), last_100_at(returns, 2400));
    eprintln!(
        "seed 2: last-100 {at_1000:.1} at 1000 (others {others_1000:?}), {at_2000:.1} at 2000, \
         {at_2400:.1} at 2400; σ over 501–1000 {sigma:.3} (others {others_sigma:?})"
    );
    // Behind at 1000, still behind at 2000, caught up by 2400.
    assert!(at_1000 < others_1000.0 - 300.0 && at_2000 < -450.0 && at_2400 > -450.0);
    assert!(*sigma > 0.2, "σ did not collapse: {sigma}");
    let file = "lessons/18-pendulum/lesson.md";
    says(
        PENDULUM,
        file,
        &format!(
            "At episode 1000 its last 100 episodes average {}, about where the untrained policy \
             started, while the other seeds' average between {} and {}",
            signed(at_1000, 0),
            signed(others_1000.0, 0),
            signed(others_1000.1, 0)
        ),
    );
    // About where the untrained policy started: inside the first-20 range the lesson quotes
    // for seeds 0 to 2 (−1100 to −1500), give or take 50.
    assert!((-1550.0..=-1050.0).contains(&at_1000), "{at_1000}");
    says(
        PENDULUM,
        file,
        &format!(
            "last-100 mean is {} at episode 2000 and {} at episode 2400, so 400 more episodes \
             take it past −450",
            signed(at_2000, 1),
            signed(at_2400, 1)
        ),
    );
    says(
        PENDULUM,
        file,
        &format!(
            "σ along the states its episodes visited averaged {:.2}, against {:.2} to {:.2} for \
             the other seeds, the lowest of the five but far from 0",
            sigma, others_sigma.0, others_sigma.1
        ),
    );
    assert!(*sigma < others_sigma.0, "the lowest of the five");
    Ok(())
}

// ---- Lesson 15 (hyperparameters): one knob at a time, predicted before each run. ----

/// The hyper-parameter lesson's experiments over seeds 0–4, 500 episodes each, base first.
fn knob_runs() -> Result<Vec<LabResult>, String> {
    use Experiment::{CriticLr, Gamma, HiddenDim, Lmbda};
    [CriticLr, HiddenDim, Gamma, Lmbda]
        .iter()
        .map(|&e| {
            lab::run(e, &PpoConfig::default(), &[0, 1, 2, 3, 4], 2, |_, _| {})
                .map_err(|err| err.to_string())
        })
        .collect()
}

/// Weights and biases of the actor (4 → h → 2) and the critic (4 → h → 1).
fn parameters(h: usize) -> (usize, usize) {
    (4 * h + h + h * 2 + 2, 4 * h + h + h + 1)
}

/// The lowest and the highest of `v`.
fn span_of(v: &[usize]) -> (usize, usize) {
    (
        v.iter().copied().min().unwrap_or(0),
        v.iter().copied().max().unwrap_or(0),
    )
}

/// Over the last 50 episodes of seeds 0–4 with discount `gamma`: how many ended with the cart
/// past the edge of the track (|x| > 2.4), and how many episodes that is.
fn cart_exits_at_the_end(gamma: f64) -> Result<(usize, usize), Box<dyn std::error::Error>> {
    let (mut exits, mut episodes) = (0, 0);
    for seed in 0..SEEDS {
        let config = PpoConfig {
            gamma,
            ..PpoConfig::default()
        };
        let last = config.num_episodes - 50;
        let mut trainer = Trainer::new(config, seed)?;
        while let Some(report) = trainer.next_episode()? {
            if report.episode < last {
                continue;
            }
            episodes += 1;
            let ended = report.terminated.last().copied().unwrap_or(false);
            let x = report.trace.next_states.last().map_or(0.0, |s| s[0]);
            if ended && x.abs() > 2.4 {
                exits += 1;
            }
        }
    }
    Ok((exits, episodes))
}

/// Lesson 15: what changing critic_lr, hidden_dim, gamma or lmbda alone does over seeds 0–4,
/// 500 episodes each (every arm's summary, and the figures each step's folded results and
/// the quiz quote); and that each step's prediction has the answer the lesson gives.
#[test]
#[cfg_attr(
    not(feature = "full-tests"),
    ignore = "full tier (cargo test --features full-tests): four one-knob experiments over five seeds, about 40 s"
)]
fn the_hyperparameter_lesson_states_what_each_knob_does() -> TestResult {
    let labs = knob_runs()?;
    let file = "lessons/15-hyperparameters/lesson.md";
    let text = include_str!("../lessons/15-hyperparameters/lesson.md");
    let quiz_file = "lessons/15-hyperparameters/quiz.toml";
    let quiz = include_str!("../lessons/15-hyperparameters/quiz.toml");
    for l in &labs {
        for arm in &l.arms {
            says(text, file, &arm.summary());
        }
    }
    let [critic, hidden, gamma, lmbda] = &labs[..] else {
        return Err("four experiments".into());
    };
    let top = |a: &ArmResult| a.final_mean_std();
    let later =
        |a: &ArmResult, b: &ArmResult| first_500(a).iter().zip(first_500(b)).all(|(x, y)| *x > y);
    let every_reached_500 = |a: &ArmResult| a.returns.iter().all(|r| r.iter().any(|&x| x >= 500.0));
    let mean_ms = |a: &ArmResult| format!("{:.1} ± {:.1}", top(a).0, top(a).1);

    // critic_lr / 10: (b) more slowly; the actor's steps unchanged.
    let [base, slow] = &critic.arms[..] else {
        return Err("critic-lr has two arms".into());
    };
    // (Where the two end is paired over ten seeds in the_lessons_order_only_what_ten_seeds_show.)
    assert!(later(slow, base) && every_reached_500(slow));
    let (b, s) = (span_of(&first_500(base)), span_of(&first_500(slow)));
    let against = format!(
        "between episode {} and {}, against {} and {}",
        s.0, s.1, b.0, b.1
    );
    says(text, file, &against);
    says(quiz, quiz_file, &against);
    let (bu, su) = (base.mean_updates(), slow.mean_updates());
    says(
        text,
        file,
        &format!(
            "approx_kl is {:.4} against {:.4}",
            su.approx_kl, bu.approx_kl
        ),
    );
    says(
        quiz,
        quiz_file,
        &format!("approx_kl {:.4} against {:.4}", su.approx_kl, bu.approx_kl),
    );
    says(
        quiz,
        quiz_file,
        &format!("ended at {:.1} or above", slow.worst_final()),
    );
    says(
        quiz,
        quiz_file,
        &format!(
            "reached 400 at episode {} instead of {}",
            slow.first_reaching(400.0)
                .ok_or("critic_lr 1e-3 reaches 400")?,
            base.first_reaching(400.0).ok_or("the seed reaches 400")?
        ),
    );

    // hidden_dim = 16: (c) still 500, later on every seed; each update moves the policy less.
    let [wide, narrow] = &hidden.arms[..] else {
        return Err("hidden-dim has two arms".into());
    };
    let ((aw, cw), (an, cn)) = (
        parameters(wide.config.hidden_dim),
        parameters(narrow.config.hidden_dim),
    );
    says(
        text,
        file,
        &format!(
            "With 128 the actor has {aw} weights and biases and the critic {cw}; with 16 they have {an} and {cn}"
        ),
    );
    says(
        quiz,
        quiz_file,
        &format!("({an} actor parameters instead of {aw})"),
    );
    assert!(every_reached_500(narrow) && later(narrow, wide));
    let (w, n) = (span_of(&first_500(wide)), span_of(&first_500(narrow)));
    says(
        text,
        file,
        &format!(
            "between episode {} and {}, but every one later than with 128 ({} to {})",
            n.0, n.1, w.0, w.1
        ),
    );
    says(
        quiz,
        quiz_file,
        &format!(
            "(between episode {} and {}, against {} and {})",
            n.0, n.1, w.0, w.1
        ),
    );
    let (wu, nu) = (wide.mean_updates(), narrow.mean_updates());
    assert!(nu.approx_kl < 0.5 * wu.approx_kl);
    says(
        text,
        file,
        &format!(
            "approx_kl is {:.4} against {:.4}, and its largest |r − 1| {:.3} against {:.3}",
            nu.approx_kl, wu.approx_kl, nu.max_ratio_deviation, wu.max_ratio_deviation
        ),
    );
    says(
        quiz,
        quiz_file,
        &format!(
            "approx_kl {:.4} against {:.4}, the largest |r − 1| {:.3} against {:.3}",
            nu.approx_kl, wu.approx_kl, nu.max_ratio_deviation, wu.max_ratio_deviation
        ),
    );
    says(quiz, quiz_file, &format!("ended at {}", mean_ms(narrow)));

    // gamma: (b) 0.9 reaches 500 on every seed but holds it on none; 0.999 level with 0.98.
    let [seed_gamma, short, long] = &gamma.arms[..] else {
        return Err("gamma has three arms".into());
    };
    let horizon = |g: f64| format!("{:.0}", 1.0 / (1.0 - g));
    says(
        text,
        file,
        &format!(
            "γ = {}, a horizon of {} steps, and γ = {}, a horizon of {} steps",
            short.config.gamma,
            horizon(short.config.gamma),
            long.config.gamma,
            horizon(long.config.gamma)
        ),
    );
    assert!(every_reached_500(short) && short.finals.iter().all(|&f| f < 400.0));
    let sg = span_of(&first_500(short));
    says(
        text,
        file,
        &format!("the first between episode {} and {}", sg.0, sg.1),
    );
    let (reach_long, reach_seed) = (
        long.first_reaching(400.0).ok_or("γ = 0.999 reaches 400")?,
        seed_gamma
            .first_reaching(400.0)
            .ok_or("the seed reaches 400")?,
    );
    assert!(reach_long < reach_seed, "γ = 0.999 reaches 400 earlier");
    // Why 0.9 falls back: the cart runs off the track, which the seed's γ never lets happen.
    let ((exits, episodes), (seed_exits, _)) = (
        cart_exits_at_the_end(short.config.gamma)?,
        cart_exits_at_the_end(seed_gamma.config.gamma)?,
    );
    assert!(exits > 9 * episodes / 10, "{exits} of {episodes}");
    says(
        text,
        file,
        &format!(
            "{exits} of the {episodes} ended with the cart past the edge of the track (|x| > 2.4), against {seed_exits} with γ = 0.98"
        ),
    );
    says(
        text,
        file,
        &format!("(0.9^30 ≈ {:.2})", short.config.gamma.powi(30)),
    );
    says(
        quiz,
        quiz_file,
        &format!("they ended at {}", mean_ms(short)),
    );
    says(
        quiz,
        quiz_file,
        &format!(
            "γ = 0.999 ended at {}, over ten seeds not shown to differ from 0.98",
            mean_ms(long)
        ),
    );
    says(
        quiz,
        quiz_file,
        &format!("its mean curve reached 400 at episode {reach_long} against {reach_seed}"),
    );
    says(
        quiz,
        quiz_file,
        &format!(
            "({} against {} on these five)",
            mean_ms(long),
            mean_ms(seed_gamma)
        ),
    );

    // lmbda: (a) on these five seeds 0.5 ends lowest and widest, 1 costs less.
    let [seed_lmbda, half, one] = &lmbda.arms[..] else {
        return Err("lmbda has three arms".into());
    };
    assert!(top(half).0 < top(one).0 && top(one).0 < top(seed_lmbda).0);
    assert!(top(half).1 > top(one).1 && top(one).1 > top(seed_lmbda).1);
    let (hu, su) = (half.mean_updates(), seed_lmbda.mean_updates());
    let times = hu.approx_kl / su.approx_kl;
    assert!((2.5..3.5).contains(&times), "about three times: {times}");
    says(
        text,
        file,
        &format!(
            "(approx_kl {:.4} against {:.4}, clip fraction {:.3} against {:.3})",
            hu.approx_kl, su.approx_kl, hu.clip_fraction, su.clip_fraction
        ),
    );
    says(
        quiz,
        quiz_file,
        &format!("approx_kl {:.4} against {:.4}", hu.approx_kl, su.approx_kl),
    );
    // λ = 1's figures in its explanation; λ = 0.5's in its choice and its explanation.
    says(
        quiz,
        quiz_file,
        &format!("{}, worst seed {:.1}", mean_ms(one), one.worst_final()),
    );
    says(quiz, quiz_file, &format!("it ended at {}", mean_ms(half)));
    says(
        quiz,
        quiz_file,
        &format!("its worst seed ended at {:.1}", half.worst_final()),
    );
    says(quiz, quiz_file, &format!("0.95's {}", mean_ms(seed_lmbda)));
    Ok(())
}

/// The first episode (from 0) at which the mean smoothed curve reaches `level`, as text.
fn proximal_reach(arm: &ArmResult, level: f64) -> String {
    arm.first_reaching(level)
        .map_or_else(|| "never".to_string(), |e| e.to_string())
}

/// Four ways to stay near π_old over seeds 0–4, 500 episodes each: the clip
/// (the seed), PPO-Penalty's adaptive β, the KL line search and none. Prints every figure
/// the lesson may quote (score, worst seed, when the mean curve reaches 400 and 450, late
/// falls, the per-update KL, β's range, the line search's halvings) and asserts the ones
/// that held with margin when measured.
#[test]
#[cfg_attr(
    not(feature = "full-tests"),
    ignore = "full tier (cargo test --features full-tests): four arms over five seeds, three on candle"
)]
fn proximal_arms_over_five_seeds() -> TestResult {
    let lab = lab::run(
        Experiment::Proximal,
        &PpoConfig::default(),
        &[0, 1, 2, 3, 4],
        2,
        |_, _| {},
    )?;
    for line in lab.table() {
        println!("{line}");
    }
    let falls = |arm: &ArmResult| -> Vec<usize> {
        arm.returns
            .iter()
            .map(|r| {
                let first = r.iter().position(|&x| x >= 500.0).unwrap_or(r.len());
                r[first..].iter().filter(|&&x| x < 250.0).count()
            })
            .collect()
    };
    for arm in &lab.arms {
        println!("{}", arm.summary());
        println!("{}", arm.kl_summary());
        println!(
            "  finals {:?}; mean curve reaches 400 at {}, 450 at {}; late falls {:?}",
            arm.finals
                .iter()
                .map(|f| format!("{f:.1}"))
                .collect::<Vec<_>>(),
            proximal_reach(arm, 400.0),
            proximal_reach(arm, 450.0),
            falls(arm)
        );
    }
    let [clip, penalty, search, none] = &lab.arms[..] else {
        return Err("proximal has four arms".into());
    };
    let (c, p, s, n) = (
        clip.mean_updates(),
        penalty.mean_updates(),
        search.mean_updates(),
        none.mean_updates(),
    );
    // Measured (release, 2026-12-03): final 495.5 ± 5.7 / 486.2 ± 15.1 / 457.2 ± 20.8 /
    // 453.2 ± 57.0; worst seed 488.3 / 463.9 / 422.2 / 383.0; mean curve at 400 by episode
    // 133 / 139 / 215 / 163; KL per update 0.0047 / 0.0115 / 0.0057 / 0.0123 (max 0.120 /
    // 0.511 / 0.0100 / 0.644); 2.13 halvings per update, no refused search; β from 3e-80
    // to 16. Asserted: only what holds with margin (the line search and none are too close
    // to order by score).
    // Which arm ends above which is the ten-seed test's, paired by seed with intervals
    // (`the_lessons_order_only_what_ten_seeds_show`); here, what the five seeds' lesson
    // text describes of them: the clip's the highest mean, best worst seed, and the mean
    // curve first to reach 400.
    let (mean_of, worst_of) = (|a: &ArmResult| a.final_mean_std().0, ArmResult::worst_final);
    let reach = |a: &ArmResult| a.first_reaching(400.0).unwrap_or(usize::MAX);
    for other in [penalty, search, none] {
        assert!(mean_of(clip) > mean_of(other) && worst_of(clip) > worst_of(other));
        assert!(reach(clip) <= reach(other));
    }
    // How far each update moves the policy: the line search never past δ, the two arms
    // without a hard limit (penalty, none) more than twice the clip's on average and by far
    // the largest single moves.
    let delta = search.config.kl_delta;
    assert!(s.kl_after_max <= delta * 1.02, "{}", s.kl_after_max);
    assert!(s.kl_after > 1.1 * c.kl_after && p.kl_after > 1.5 * s.kl_after);
    for u in [p, n] {
        assert!(u.kl_after > 2.0 * c.kl_after && u.kl_after_max > 10.0 * delta);
    }
    let halvings = s.ls_halvings.ok_or("no halvings")?;
    assert!((1.5..3.0).contains(&halvings), "{halvings}");
    assert_eq!(s.ls_refused, Some(0.0));
    // β collapses: the penalty spends most updates halving it towards 0
    let (lo, hi) = p.beta_range.ok_or("no β range")?;
    assert!(lo < 1e-20 && hi >= 2.0, "β from {lo:e} to {hi}");
    proximal_lesson_quotes(&lab.arms, &falls)
}

/// Lesson 10's step 7 quotes every figure of the proximal lab: each arm's score, worst
/// seed, when its mean curve reaches 400 and how far its updates moved the policy; the
/// penalty's and the clip's late falls; the line search's halvings; the range of β.
/// Each quoted as the lab computes it, in both languages.
fn proximal_lesson_quotes(
    arms: &[ArmResult],
    falls: &dyn Fn(&ArmResult) -> Vec<usize>,
) -> TestResult {
    let [clip, penalty, search, none] = arms else {
        return Err("proximal has four arms".into());
    };
    let en = "lessons/10-trust-region/lesson.md";
    let zh = "lessons/10-trust-region/lesson.zh.md";
    let score = |a: &ArmResult| {
        let (m, sd) = a.final_mean_std();
        format!("{m:.1} ± {sd:.1}")
    };
    let worst = |a: &ArmResult| format!("{:.1}", a.worst_final());
    let reach = |a: &ArmResult| proximal_reach(a, 400.0);
    let kl = |a: &ArmResult| format!("{:.4}", a.mean_updates().kl_after);
    let largest =
        |a: &ArmResult, digits: usize| format!("{:.digits$}", a.mean_updates().kl_after_max);
    let fell = |a: &ArmResult| falls(a).iter().sum::<usize>();
    let u = search.mean_updates();
    let halvings = format!("{:.1}", u.ls_halvings.ok_or("no halvings")?);
    assert_eq!(
        u.ls_refused,
        Some(0.0),
        "the lesson says no update was refused"
    );
    // β per seed: the largest it reached and the smallest it fell to, as powers of ten.
    let ranges: Vec<(f64, f64)> = penalty
        .updates
        .iter()
        .filter_map(|u| u.beta_range)
        .collect();
    let span = |f: fn(&(f64, f64)) -> f64| {
        let v: Vec<f64> = ranges.iter().map(f).collect();
        (
            v.iter().copied().fold(f64::INFINITY, f64::min),
            v.iter().copied().fold(f64::NEG_INFINITY, f64::max),
        )
    };
    let (top_lo, top_hi) = span(|r| r.1);
    let (low_lo, low_hi) = span(|r| r.0);
    let power = |x: f64| format!("1e{}", x.log10().floor());
    println!(
        "β per seed: highest {top_lo}..{top_hi}, lowest {low_lo:e}..{low_hi:e}; late falls {} / {}",
        fell(penalty),
        fell(clip)
    );
    let en_claims = [
        format!("**clip ε = 0.2**: {} (mean ± std", score(clip)),
        format!(
            "worst seed {}; the mean curve reaches 400 at episode {}",
            worst(clip),
            reach(clip)
        ),
        format!(
            "**penalty**: {}, worst {}; 400 at episode {}",
            score(penalty),
            worst(penalty),
            reach(penalty)
        ),
        format!(
            "**KL line search**: {}, worst {}; 400 at episode {}",
            score(search),
            worst(search),
            reach(search)
        ),
        format!(
            "**none**: {}, worst {}; 400 at episode {}",
            score(none),
            worst(none),
            reach(none)
        ),
        format!(
            "**clip**: mean KL per update {}, largest {}",
            kl(clip),
            largest(clip, 2)
        ),
        format!(
            "**penalty**: mean {}, largest {}",
            kl(penalty),
            largest(penalty, 2)
        ),
        format!(
            "**KL line search**: mean {}, largest {} (never above δ; {halvings} halvings per update, no update refused)",
            kl(search),
            largest(search, 4)
        ),
        format!("**none**: mean {}, largest {}", kl(none), largest(none, 2)),
        format!(
            "(largest KL {} and {} on these five seeds)",
            largest(none, 2),
            largest(penalty, 2)
        ),
        format!(
            "reached at most {top_lo:.0} to {top_hi:.0} but fell to between {} and {}",
            power(low_hi),
            power(low_lo)
        ),
        format!("(mean {})", kl(penalty)),
    ];
    let zh_claims = [
        format!("**截断 ε = 0.2**：{}（各随机种子", score(clip)),
        format!(
            "最差的随机种子 {}；平均曲线在第 {} 个回合达到 400",
            worst(clip),
            reach(clip)
        ),
        format!(
            "**惩罚**：{}，最差 {}；第 {} 个回合达到 400",
            score(penalty),
            worst(penalty),
            reach(penalty)
        ),
        format!(
            "**KL 线搜索**：{}，最差 {}；第 {} 个回合达到 400",
            score(search),
            worst(search),
            reach(search)
        ),
        format!(
            "**都不用**：{}，最差 {}；第 {} 个回合达到 400",
            score(none),
            worst(none),
            reach(none)
        ),
        format!(
            "**截断**：每次更新的平均 KL 为 {}，最大 {}",
            kl(clip),
            largest(clip, 2)
        ),
        format!(
            "**惩罚**：平均 {}，最大 {}",
            kl(penalty),
            largest(penalty, 2)
        ),
        format!(
            "**KL 线搜索**：平均 {}，最大 {}（从未超过 δ；每次更新平均减半 {halvings} 次，没有一次更新被拒绝）",
            kl(search),
            largest(search, 4)
        ),
        format!("**都不用**：平均 {}，最大 {}", kl(none), largest(none, 2)),
        format!(
            "最大 KL 分别为 {} 和 {}",
            largest(none, 2),
            largest(penalty, 2)
        ),
        format!(
            "β 的最大值只有 {top_lo:.0} 到 {top_hi:.0}，最小值却降到 {} 到 {} 之间",
            power(low_hi),
            power(low_lo)
        ),
        format!("（平均 {}）", kl(penalty)),
    ];
    says_all(TRUST_REGION, en, &en_claims);
    says_all(TRUST_REGION_ZH, zh, &zh_claims);
    Ok(())
}

// ---- Lesson 10 (trust-region): how far the surrogate's prediction holds. ----

/// Training episodes before the probe, as `ppo-tutor trust-region` by default.
const TRUST_REGION_TRAINING: usize = 40;

/// `ppo-tutor trust-region --seed SEED`: the seed's agent after 40 episodes, its latest
/// batch probed with the default settings (held-out episodes drawn from the same seed).
fn trust_region_probe(
    seed: u64,
) -> Result<ppo_tutor::ppo::trust_region::TrustRegionProbe, Box<dyn std::error::Error>> {
    use ppo_tutor::ppo::trust_region::{ProbeSettings, probe_snapshot};
    let config = PpoConfig {
        num_episodes: TRUST_REGION_TRAINING,
        ..PpoConfig::default()
    };
    let snapshot = ppo_tutor::lesson::Session::run(config.clone(), seed, TRUST_REGION_TRAINING)?;
    let settings = ProbeSettings {
        seed,
        ..ProbeSettings::default()
    };
    Ok(probe_snapshot(&snapshot, &config, &settings)?)
}

/// How many combined standard errors separate the prediction from the truth (positive:
/// the truth is below the prediction).
fn trust_region_gap(p: &ppo_tutor::ppo::trust_region::ProbePoint) -> f64 {
    (p.predicted - p.truth) / p.predicted_se.hypot(p.truth_se)
}

/// Checks one seed's probe and returns `(largest KL up to which every step agrees within
/// 2 SE, smallest KL where the truth is below the prediction by more than 3 SE)`.
fn trust_region_check(
    seed: u64,
    probe: &ppo_tutor::ppo::trust_region::TrustRegionProbe,
) -> Result<(f64, f64), String> {
    eprintln!(
        "seed {seed}: ‖g‖ = {:.4}, π_old scores {:.1} (J_γ {:.2}) over {} held-out episodes, {} states",
        probe.gradient_norm, probe.old_score, probe.old_return, probe.episodes, probe.states
    );
    eprintln!("      α    mean KL   predicted ± se     true ± se   gap/SE   score ± se");
    for p in &probe.points {
        eprintln!(
            "  {:5.3}  {:9.2e}  {:+7.3} ± {:5.3}  {:+7.3} ± {:5.3}  {:+6.1}  {:+6.1} ± {:4.1}",
            p.step,
            p.kl,
            p.predicted,
            p.predicted_se,
            p.truth,
            p.truth_se,
            if p.kl > 0.0 { trust_region_gap(p) } else { 0.0 },
            p.return_change,
            p.return_change_se
        );
    }
    let points = &probe.points;
    let zero = points.first().ok_or("no points")?;
    if (zero.kl, zero.predicted, zero.truth) != (0.0, 0.0, 0.0) {
        return Err(format!("seed {seed}: α = 0 moved something: {zero:?}"));
    }
    if let Some(w) = points.windows(2).find(|w| w[1].kl <= w[0].kl) {
        return Err(format!("seed {seed}: the KL does not grow with α: {w:?}"));
    }
    let (first, last) = (&points[1], &points[points.len() - 1]);
    // Measured (seeds 0-4): 1.0e-4 to 1.4e-3 at the smallest step, 1.1 to 6.9 at the largest.
    if !(first.kl < 3e-3 && last.kl > 0.3) {
        return Err(format!(
            "seed {seed}: the KL spans {} to {}",
            first.kl, last.kl
        ));
    }
    // Measured: 0.1 to 1.5 combined SE at the smallest step.
    if trust_region_gap(first).abs() > 2.0 {
        return Err(format!(
            "seed {seed}: prediction and truth differ at the smallest step: {first:?}"
        ));
    }
    // Measured: 4.1 (seed 4, KL 0.57) to 24 combined SE.
    for p in points.iter().filter(|p| p.kl >= 0.5) {
        if trust_region_gap(p) <= 3.0 {
            return Err(format!(
                "seed {seed}: at KL {} the truth is not below the prediction: {p:?}",
                p.kl
            ));
        }
    }
    let agree = points
        .iter()
        .skip(1)
        .take_while(|p| trust_region_gap(p).abs() <= 2.0)
        .last()
        .map_or(0.0, |p| p.kl);
    let part = points
        .iter()
        .skip(1)
        .find(|p| trust_region_gap(p) > 3.0)
        .map_or(f64::NAN, |p| p.kl);
    eprintln!(
        "seed {seed}: agree within 2 SE up to KL {agree:.2e}; truth below by > 3 SE from KL {part:.2e}"
    );
    Ok((agree, part))
}

/// Lesson 10's settings and arithmetic, in both languages: the bound's constant for the
/// seed's γ, the two-action KLs of step 3 (both directions, the small and the large change
/// with the same ratio, the taken action's term), the line search's and the penalty's
/// defaults, and the probe's steps, episodes and training.
#[test]
fn the_trust_region_lesson_quotes_its_settings_and_arithmetic() -> TestResult {
    use ppo_tutor::ppo::trust_region::ProbeSettings;
    let c = PpoConfig::default();
    let kl = |p: f64, q: f64| p * (p / q).ln() + (1.0 - p) * ((1.0 - p) / (1.0 - q)).ln();
    let steep = 4.0 * c.gamma / (1.0 - c.gamma).powi(2);
    let cap = 1.0 / (1.0 - c.gamma);
    let (big, back, small) = (kl(0.7, 0.91), kl(0.91, 0.7), kl(0.01, 0.013));
    let times = big / small;
    let taken = 0.7 * (0.7_f64 / 0.91).ln();
    assert!((0.91_f64 / 0.7 - 1.3).abs() < 1e-12 && (0.013_f64 / 0.01 - 1.3).abs() < 1e-12);
    let settings = ProbeSettings::default();
    let top = settings.steps.iter().copied().fold(f32::MIN, f32::max);
    let figures = [
        format!("4γ/(1 − γ)² is {steep:.0}"),
        format!("1/(1 − γ) = {cap:.0}"),
        format!("{big:.3} one way and {back:.3} the other"),
        format!("KL ≈ {small:.5}"),
        format!(
            "KL ≈ {big:.3}, about {:.0} times more",
            (times / 10.0).round() * 10.0
        ),
        format!("0.7 · ln(0.7 / 0.91) ≈ {}", signed(taken, 3)),
        format!("tries the length α = {} first", c.ls_max_step),
        format!(
            "at most {} times, until the mean exact KL over the batch is at most δ = {}",
            c.ls_backtracks, c.kl_delta
        ),
        format!("starts from β₀ = {} with δ = {}", c.beta_init, c.kl_delta),
        format!("from 0 up to {top}"),
        format!("averaged over {} fresh episodes", settings.episodes),
        format!("probed after {TRUST_REGION_TRAINING} training episodes"),
        format!("**clip ε = {}**: the seed", c.eps),
    ];
    says_all(TRUST_REGION, "lessons/10-trust-region/lesson.md", &figures);
    let figures_zh = [
        format!("4γ/(1 − γ)² 等于 {steep:.0}"),
        format!("1/(1 − γ) = {cap:.0}"),
        format!("一个方向是 {big:.3}，另一个方向是 {back:.3}"),
        format!("KL ≈ {small:.5}"),
        format!(
            "KL ≈ {big:.3}，大约是前者的 {:.0} 倍",
            (times / 10.0).round() * 10.0
        ),
        format!("0.7 · ln(0.7 / 0.91) ≈ {}", signed(taken, 3)),
        format!("β₀ = {}、δ = {}", c.beta_init, c.kl_delta),
        format!(
            "先试长度 α = {}，然后减半，最多 {} 次，直到批次上精确 KL 的均值不超过 δ = {}",
            c.ls_max_step, c.ls_backtracks, c.kl_delta
        ),
        format!("从 0 到 {top}"),
        format!("π_old 新采样的 {} 个回合上的平均", settings.episodes),
        format!("各训练 {TRUST_REGION_TRAINING} 个回合后探测"),
        format!("**截断 ε = {}**：原教程代码", c.eps),
    ];
    says_all(
        TRUST_REGION_ZH,
        "lessons/10-trust-region/lesson.zh.md",
        &figures_zh,
    );
    // The quiz's arithmetic: the same ratio 1.5 at two states, the bound's price of a KL of
    // δ, β's band, the line search's first try.
    let (a, b) = (kl(0.02, 0.03), kl(0.6, 0.9));
    let delta = c.kl_delta;
    let quiz = [
        format!("B: about {b:.3} against {a:.4} at A"),
        format!(
            "is {a:.4} with p = 0.02, q = 0.03, and {b:.3} with p = 0.6, q = 0.9, about {:.0} times more",
            (b / a / 10.0).round() * 10.0
        ),
        format!(
            "4γ/(1 − γ)² = 4 × {} / {:.2}² = {steep:.0}",
            c.gamma,
            1.0 - c.gamma
        ),
        format!(
            "charged {delta}·C, {:.0} times the batch's largest |Â|",
            delta * steep
        ),
        format!("δ/1.5 ≈ {:.4}", delta / 1.5),
        format!("about {:.4} to {}", delta / 1.5, 1.5 * delta),
        format!("d > 1.5·δ = {}, so β doubles", 1.5 * delta),
        format!("tries the fixed length α = {} first", c.ls_max_step),
    ];
    says_all(
        include_str!("../lessons/10-trust-region/quiz.toml"),
        "lessons/10-trust-region/quiz.toml",
        &quiz,
    );
    let quiz_zh = [
        format!("B：约 {b:.3} 对 A 的 {a:.4}"),
        format!(
            "在 p = 0.02、q = 0.03 时为 {a:.4}，在 p = 0.6、q = 0.9 时为 {b:.3}，大约是前者的 {:.0} 倍",
            (b / a / 10.0).round() * 10.0
        ),
        format!(
            "4γ/(1 − γ)² = 4 × {} / {:.2}² = {steep:.0}",
            c.gamma,
            1.0 - c.gamma
        ),
        format!("相当于这批数据最大 |Â| 的 {:.0} 倍", delta * steep),
        format!("d < δ/1.5 ≈ {:.4}", delta / 1.5),
        format!("即大约 {:.4} 到 {} 之间", delta / 1.5, 1.5 * delta),
        format!("d > 1.5·δ = {}，所以 β 加倍", 1.5 * delta),
        format!("第一次尝试固定的长度 α = {}", c.ls_max_step),
    ];
    says_all(
        include_str!("../lessons/10-trust-region/quiz.zh.toml"),
        "lessons/10-trust-region/quiz.zh.toml",
        &quiz_zh,
    );
    Ok(())
}

/// `x` to two significant figures, as lesson 10's tables write a KL (0.028, 0.060, 0.00074, 1.1).
fn two_figures(x: f64) -> String {
    let decimals = (1 - x.abs().log10().floor() as i32).max(0) as usize;
    format!("{x:.decimals$}")
}

/// `x` as lesson 10 writes a small KL in a sentence: two figures in e-notation, a trailing
/// `.0` dropped (1e-4, 1.4e-3).
fn e_figures(x: f64) -> String {
    format!("{x:.1e}").replace(".0e", "e")
}

/// Lesson 10 over seeds 0-4: the same three facts on every seed, where each seed's
/// prediction and truth part, and every figure the lesson's table and sentences quote of
/// these probes, in both languages.
#[test]
fn trust_region_prediction_holds_near_theta_old_over_five_seeds() -> TestResult {
    let (en, zh) = (
        "lessons/10-trust-region/lesson.md",
        "lessons/10-trust-region/lesson.zh.md",
    );
    let mut agree = Vec::new();
    let mut part = Vec::new();
    let (mut rows_en, mut rows_zh) = (Vec::new(), Vec::new());
    let (mut first_kl, mut first_gap, mut far_gap, mut old_return) =
        (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    for seed in 0..5 {
        let probe = trust_region_probe(seed)?;
        let (a, p) = trust_region_check(seed, &probe)?;
        agree.push(a);
        part.push(p);
        let (first, last) = (&probe.points[1], &probe.points[probe.points.len() - 1]);
        first_kl.push(first.kl);
        first_gap.push(trust_region_gap(first).abs());
        far_gap.extend(
            probe
                .points
                .iter()
                .filter(|p| p.kl >= 0.5)
                .map(trust_region_gap),
        );
        old_return.push(probe.old_return);
        // The table's row for this seed.
        let plus = |x: f64| {
            if x > 0.0 {
                format!("+{x:.1}")
            } else {
                signed(x, 1)
            }
        };
        let row = format!(
            "| {seed} | {} | {} | {} / {}",
            two_figures(a),
            two_figures(p),
            plus(last.predicted),
            plus(last.truth)
        );
        let kl = two_figures(last.kl);
        rows_en.push(format!("{row} (KL {kl}) |"));
        rows_zh.push(format!("{row}（KL {kl}） |"));
        if seed == 0 {
            // "its held-out prediction is negative from the first step ... and the truth agreed"
            assert!(
                probe
                    .points
                    .iter()
                    .skip(1)
                    .all(|p| p.predicted < 0.0 && p.truth < 0.0),
                "seed 0's prediction and truth are negative at every step"
            );
        }
    }
    let span = |v: &[f64]| {
        let lo = v.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = v.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        (lo, hi)
    };
    let ((a_lo, a_hi), (p_lo, p_hi)) = (span(&agree), span(&part));
    eprintln!(
        "seeds 0-4: agree up to KL {a_lo:.2e}..{a_hi:.2e}; part (> 3 SE) from KL {p_lo:.2e}..{p_hi:.2e}"
    );
    assert!(
        part.iter().all(|p| p.is_finite()),
        "every seed parts: {part:?}"
    );
    let (kl_lo, kl_hi) = span(&first_kl);
    let (_, gap_hi) = span(&first_gap);
    let (far_lo, far_hi) = span(&far_gap);
    let (j_lo, j_hi) = span(&old_return);
    eprintln!(
        "smallest step: KL {kl_lo:e}..{kl_hi:e}, gap at most {gap_hi:.2} SE; KL ≥ 0.5: {far_lo:.1}..{far_hi:.1} SE; J_γ {j_lo:.1}..{j_hi:.1}"
    );
    // "within 1.5 combined standard errors": the largest gap, rounded up to a tenth.
    let within = format!("{:.1}", (gap_hi * 10.0).ceil() / 10.0);
    let (kl_lo, kl_hi) = (e_figures(kl_lo), e_figures(kl_hi));
    let (far_lo, far_hi) = (far_lo.floor(), far_hi.round());
    let (j_lo, j_hi) = (j_lo.round(), j_hi.round());
    let (p_lo, p_hi) = (two_figures(p_lo), two_figures(p_hi));
    rows_en.extend([
        format!("At the smallest step (KL {kl_lo} to {kl_hi}) prediction and truth agree within {within} combined standard errors on every seed"),
        format!("by {far_lo} to {far_hi} standard errors"),
        format!("(J_γ of π_old is {j_lo} to {j_hi})"),
        format!("(KL {p_lo} to {p_hi})"),
    ]);
    rows_zh.extend([
        format!("在最小的一步（KL 为 {kl_lo} 到 {kl_hi}），每个随机种子上预测与真实之差都在合并标准误的 {within} 倍以内"),
        format!("差距都有 {far_lo} 到 {far_hi} 个标准误"),
        format!("（π_old 的 J_γ 为 {j_lo} 到 {j_hi}）"),
        format!("（KL 从 {p_lo} 到 {p_hi}）"),
    ]);
    says_all(TRUST_REGION, en, &rows_en);
    says_all(TRUST_REGION_ZH, zh, &rows_zh);
    Ok(())
}

/// Every experiment of the labs over ten seeds (0–9), 500 episodes each, in the current
/// language (a second call in the other language reuses the runs: the lab caches them).
fn ten_seed_labs() -> Result<Vec<LabResult>, String> {
    let seeds: Vec<u64> = (0..10).collect();
    Experiment::ALL
        .iter()
        .map(|&e| {
            lab::run(e, &PpoConfig::default(), &seeds, 2, |_, _| {}).map_err(|err| err.to_string())
        })
        .collect()
}

/// `a − b` seed by seed on numbers of the same seeds.
fn paired_numbers(a: &[f64], b: &[f64]) -> Result<Paired, String> {
    Bootstrap::default().paired(a, b).map_err(|e| e.to_string())
}

/// `arm − baseline`, seed by seed, on each seed's last-50 mean.
fn paired_finals(arm: &ArmResult, baseline: &ArmResult) -> Result<Paired, String> {
    paired_numbers(&arm.finals, &baseline.finals)
}

/// `arm − baseline`, seed by seed, on the episode of each seed's first 500-step episode.
fn paired_first_500(arm: &ArmResult, baseline: &ArmResult) -> Result<Paired, String> {
    let of = |a: &ArmResult| -> Vec<f64> { first_500(a).iter().map(|&e| e as f64).collect() };
    paired_numbers(&of(arm), &of(baseline))
}

/// How a lesson quotes a paired comparison: `LABEL: ±d [±lo, ±hi]: verdict` (as `ppo-tutor
/// lab` prints it, but for the padding).
fn paired_line(label: &str, p: &Paired) -> String {
    format!("{label}{}{}", t(": ", "："), paired_words(p))
}

/// How a lesson quotes a paired comparison of episode numbers: `LABEL: ±d [±lo, ±hi]
/// episodes: later` (or earlier, or no difference shown).
fn paired_episodes(label: &str, p: &Paired) -> String {
    use ppo_tutor::stats::Verdict;
    let verdict = match p.verdict() {
        Verdict::Higher => t("later", "更晚").to_string(),
        Verdict::Lower => t("earlier", "更早").to_string(),
        Verdict::NotShown => ppo_tutor::tr!(
            "no difference shown at {} seeds",
            "{} 个随机种子下没有显示出差异",
            p.n()
        ),
    };
    ppo_tutor::tr!(
        "{label}: {:+.1} [{:+.1}, {:+.1}] episodes: {verdict}",
        "{label}：{:+.1} [{:+.1}, {:+.1}] 个回合：{verdict}",
        p.mean_difference,
        p.ci.low,
        p.ci.high
    )
}

/// The orderings lessons 4, 10, 13 and 15 state, each from a paired comparison over ten
/// seeds whose 95% interval excludes zero (or the sentence says no difference was shown):
/// every comparison the lessons quote, in both languages.
#[test]
#[cfg_attr(
    not(feature = "full-tests"),
    ignore = "full tier (cargo test --features full-tests): every lab experiment over ten seeds, about 3 minutes"
)]
fn the_lessons_order_only_what_ten_seeds_show() -> TestResult {
    for lang in Lang::ALL {
        let _lang = lang.scoped();
        let labs = ten_seed_labs()?;
        let get = |e: Experiment| {
            labs.iter()
                .find(|l| l.experiment == e)
                .ok_or(format!("missing lab {}", e.name()))
        };
        let zh = lang == Lang::Zh;
        let read = |folder: &str| -> Result<(String, String), Box<dyn std::error::Error>> {
            let file = format!("lessons/{folder}/lesson{}.md", if zh { ".zh" } else { "" });
            let text = std::fs::read_to_string(
                std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join(&file),
            )?;
            Ok((file, text))
        };
        let mut quoted: Vec<(&str, String)> = Vec::new();
        // Every arm against its experiment's first, as the lab prints it.
        for e in Experiment::ALL {
            let l = get(e)?;
            let folder = match e {
                Experiment::Reinforce => "04-policy-gradient",
                Experiment::Proximal => "10-trust-region",
                Experiment::CriticLr
                | Experiment::HiddenDim
                | Experiment::Gamma
                | Experiment::Lmbda => "15-hyperparameters",
                _ => "13-clip-lab",
            };
            for (arm, p) in l.arms.iter().skip(1).zip(l.paired()) {
                let p = p.as_ref().ok_or("no interval")?;
                quoted.push((folder, paired_line(&arm.label, p)));
            }
        }
        // Between arms that are not the base.
        let eps = get(Experiment::Eps)?;
        let epochs = get(Experiment::Epochs)?;
        let lr = get(Experiment::ActorLr)?;
        let kl = get(Experiment::TargetKl)?;
        let proximal = get(Experiment::Proximal)?;
        let no_clip = &eps.arms[2];
        for other in [&epochs.arms[2], &lr.arms[1]] {
            let p = paired_finals(other, no_clip)?;
            quoted.push((
                "13-clip-lab",
                paired_line(&format!("{} − {}", other.label, no_clip.label), &p),
            ));
        }
        let p = paired_finals(&kl.arms[2], &kl.arms[1])?;
        quoted.push((
            "13-clip-lab",
            paired_line(&format!("{} − {}", kl.arms[2].label, kl.arms[1].label), &p),
        ));
        let p = paired_finals(&proximal.arms[1], &proximal.arms[3])?;
        quoted.push((
            "10-trust-region",
            paired_line(
                &format!("{} − {}", proximal.arms[1].label, proximal.arms[3].label),
                &p,
            ),
        ));
        // Lesson 4 quotes where ten actor steps with one critic step end.
        let pairs = epochs.paired();
        let critic_once = pairs
            .get(3)
            .and_then(|p| p.as_ref())
            .ok_or("no interval for the critic's single epoch")?;
        quoted.push((
            "04-policy-gradient",
            paired_line(&epochs.arms[4].label, critic_once),
        ));
        // The actor's reuse of an episode against its movement per episode: the first
        // 500-step episode, one long actor step against ten short ones and one short one.
        let (ten, actor_one, long_step) = (&epochs.arms[0], &epochs.arms[3], &epochs.arms[5]);
        for base in [ten, actor_one] {
            let p = paired_first_500(long_step, base)?;
            let line = paired_episodes(&format!("{} − {}", long_step.label, base.label), &p);
            quoted.push(("13-clip-lab", line.clone()));
            quoted.push(("04-policy-gradient", line));
        }
        for (folder, line) in &quoted {
            println!("{folder}: {line}");
        }
        let mut missing = Vec::new();
        for (folder, line) in &quoted {
            let (file, text) = read(folder)?;
            if !flat(&text).contains(line.as_str()) {
                missing.push(format!("{file}: {line}"));
            }
        }
        assert!(
            missing.is_empty(),
            "the lessons should quote:\n{}",
            missing.join("\n")
        );
    }
    Ok(())
}

/// Ten seeds (0–9) of `config`, 500 episodes each.
fn ten_seeds(config: &PpoConfig) -> Result<Vec<SeedRun>, String> {
    first_seeds(config, 10)
}

/// Lessons 14 and 16 over ten seeds (0–9), paired by seed: how the truncation fix and
/// advantage normalisation change the late falls (episodes below 250 after a run's first
/// 500), alone and together, and whether the fix's effect depends on the normalisation;
/// and what the entropy bonus and gradient-norm clipping do to the last-50 means.
#[test]
#[cfg_attr(
    not(feature = "full-tests"),
    ignore = "full tier (cargo test --features full-tests): six settings over ten seeds, about a minute"
)]
fn the_fixes_and_switches_are_compared_over_ten_seeds() -> TestResult {
    let with = |f: &dyn Fn(&mut PpoConfig)| {
        let mut c = PpoConfig::default();
        f(&mut c);
        ten_seeds(&c)
    };
    let seed = with(&|_| {})?;
    let fixed = with(&|c| c.bootstrap_on_truncation = true)?;
    let normalised = with(&|c| c.normalize_advantage = true)?;
    let both = with(&|c| {
        c.bootstrap_on_truncation = true;
        c.normalize_advantage = true;
    })?;
    let entropy = with(&|c| c.entropy_coef = 0.01)?;
    let clipped = with(&|c| c.max_grad_norm = Some(0.5))?;
    let falls =
        |runs: &[SeedRun]| -> Vec<f64> { late_falls_of(runs).iter().map(|&n| n as f64).collect() };
    let (s, f, n, b) = (
        falls(&seed),
        falls(&fixed),
        falls(&normalised),
        falls(&both),
    );
    // The fix's effect with the normalisation on, minus its effect without, per seed.
    let with_norm: Vec<f64> = b.iter().zip(&n).map(|(x, y)| x - y).collect();
    let without: Vec<f64> = f.iter().zip(&s).map(|(x, y)| x - y).collect();
    let sum = |v: &[f64]| v.iter().sum::<f64>();
    let finals =
        |runs: &[SeedRun]| -> Vec<f64> { runs.iter().map(|r| r.summary.mean_last(50)).collect() };
    let mut quotes14 = vec![
        format!("{} to {}", sum(&s), sum(&f)),
        format!("fix alone: {}", paired_words(&paired_numbers(&f, &s)?)),
        format!(
            "normalisation alone: {}",
            paired_words(&paired_numbers(&n, &s)?)
        ),
        format!("both: {}", paired_words(&paired_numbers(&b, &s)?)),
        format!(
            "the fix with the normalisation on, minus the fix without it: {}",
            paired_words(&paired_numbers(&with_norm, &without)?)
        ),
    ];
    let quotes16 = vec![
        format!(
            "entropy bonus: {}",
            paired_words(&paired_numbers(&finals(&entropy), &finals(&seed))?)
        ),
        format!(
            "gradient clipping: {}",
            paired_words(&paired_numbers(&finals(&clipped), &finals(&seed))?)
        ),
    ];
    println!(
        "late falls over seeds 0-9: seed {s:?} ({}), fixed {f:?} ({}), normalised {n:?} ({}), both {b:?} ({})",
        sum(&s),
        sum(&f),
        sum(&n),
        sum(&b)
    );
    quotes14.push(format!("{} to {}", sum(&n), sum(&b)));
    for q in quotes14.iter().chain(&quotes16) {
        println!("{q}");
    }
    says_all(TRAINING, "lessons/14-training/lesson.md", &quotes14);
    says_all(
        include_str!("../lessons/16-beyond-the-seed/lesson.md"),
        "lessons/16-beyond-the-seed/lesson.md",
        &quotes16,
    );
    Ok(())
}
