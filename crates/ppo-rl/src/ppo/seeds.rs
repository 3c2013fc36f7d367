//! One configuration over several seeds, trained in parallel: the evidence one curve cannot
//! give. PPO runs differ a lot from seed to seed, so a claim about a setting is a claim
//! about its spread as well as its mean.
//!
//! [`train_seeds`] runs any agent ([`AgentConfig`]: the seed's PPO on CartPole, the book's
//! `PPOContinuous` on Pendulum, ...) once per seed, each a [`Training`].
//!
//! ```
//! use ppo_rl::ppo::seeds::{Band, mean_std};
//!
//! let band = Band::of(&[vec![1.0, 4.0], vec![3.0, 2.0]]);
//! assert_eq!(band.mean, [2.0, 3.0]);
//! assert_eq!((band.low[1], band.high[1]), (2.0, 4.0));
//! assert_eq!(mean_std(&[1.0, 3.0]), (2.0, 2.0_f64.sqrt()));
//! ```

use std::sync::Mutex;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

use super::PpoError;
use super::on_policy::{AgentConfig, OnPolicyAgent};
use super::train::{EpisodeReport, TrainSummary, Training};

/// What each episode of agent `C::Agent` reports.
pub type ReportOf<C> = EpisodeReport<<<C as AgentConfig>::Agent as OnPolicyAgent>::Trace>;

/// One seed's finished run.
#[derive(Debug, Clone)]
pub struct SeedRun {
    /// The seed (network initialisation, action sampling, first reset).
    pub seed: u64,
    /// Its returns, env steps and time.
    pub summary: TrainSummary,
}

/// A run that stopped, and the seed it stopped on.
#[derive(Debug, thiserror::Error)]
#[error("seed {seed}: {source}")]
pub struct SeedError {
    /// The seed whose run failed.
    pub seed: u64,
    /// Why.
    #[source]
    pub source: PpoError,
}

/// Trains `config` once per seed of `seeds`, on up to `threads` threads at once, and
/// returns the runs in the order of `seeds`. `on_episode` sees every episode of every run
/// as it finishes (from the worker threads).
///
/// # Errors
/// The first [`SeedError`]: invalid settings (reported by each seed's trainer), or a run
/// that diverged.
pub fn train_seeds<C: AgentConfig>(
    config: &C,
    seeds: &[u64],
    threads: usize,
    on_episode: impl Fn(u64, &ReportOf<C>) + Sync,
) -> Result<Vec<SeedRun>, SeedError> {
    let jobs: Vec<(&C, u64)> = seeds.iter().map(|&s| (config, s)).collect();
    train_jobs(&jobs, threads, |i, report| on_episode(jobs[i].1, report))
}

/// Trains each `(config, seed)` of `jobs`, on up to `threads` threads at once, and returns
/// the runs in the order of `jobs`. `on_episode` gets the job's index and every episode.
///
/// # Errors
/// As [`train_seeds`].
pub fn train_jobs<C: AgentConfig>(
    jobs: &[(&C, u64)],
    threads: usize,
    on_episode: impl Fn(usize, &ReportOf<C>) + Sync,
) -> Result<Vec<SeedRun>, SeedError> {
    let next = AtomicUsize::new(0);
    let results: Mutex<Vec<Option<Result<SeedRun, SeedError>>>> =
        Mutex::new(jobs.iter().map(|_| None).collect());
    let failed = AtomicBool::new(false);
    let work = || {
        loop {
            let i = next.fetch_add(1, Ordering::Relaxed);
            let Some(&(config, seed)) = jobs.get(i) else {
                break;
            };
            if failed.load(Ordering::Relaxed) {
                break;
            }
            let run = one_seed(config, seed, &|report: &ReportOf<C>| on_episode(i, report));
            if run.is_err() {
                failed.store(true, Ordering::Relaxed);
            }
            if let Ok(mut slots) = results.lock() {
                slots[i] = Some(run);
            }
        }
    };
    std::thread::scope(|scope| {
        for _ in 0..threads.clamp(1, jobs.len().max(1)) {
            scope.spawn(work);
        }
    });
    let slots = results
        .into_inner()
        .unwrap_or_else(|poisoned| poisoned.into_inner());
    let mut runs = Vec::with_capacity(jobs.len());
    for slot in slots {
        match slot {
            Some(run) => runs.push(run?),
            // Skipped after another seed failed: that failure is returned first.
            None => continue,
        }
    }
    Ok(runs)
}

fn one_seed<C: AgentConfig>(
    config: &C,
    seed: u64,
    on_episode: &dyn Fn(&ReportOf<C>),
) -> Result<SeedRun, SeedError> {
    let fail = |source| SeedError { seed, source };
    let mut trainer = Training::<C::Agent>::new(config.clone(), seed).map_err(fail)?;
    while let Some(report) = trainer.next_episode().map_err(fail)? {
        on_episode(&report);
    }
    Ok(SeedRun {
        seed,
        summary: trainer.summary(),
    })
}

/// Curves over seeds, episode by episode: their mean, and the lowest and highest value.
#[derive(Debug, Clone, PartialEq, Default, serde::Serialize)]
pub struct Band {
    /// The mean over seeds.
    pub mean: Vec<f64>,
    /// The minimum over seeds.
    pub low: Vec<f64>,
    /// The maximum over seeds.
    pub high: Vec<f64>,
}

impl Band {
    /// The band of `curves`, as long as the shortest (empty for none).
    #[must_use]
    pub fn of(curves: &[Vec<f64>]) -> Self {
        let len = curves.iter().map(Vec::len).min().unwrap_or(0);
        let mut band = Self::default();
        for i in 0..len {
            let column = curves.iter().map(|c| c[i]);
            band.mean
                .push(column.clone().sum::<f64>() / curves.len() as f64);
            band.low.push(column.clone().fold(f64::INFINITY, f64::min));
            band.high.push(column.fold(f64::NEG_INFINITY, f64::max));
        }
        band
    }
}

/// The mean and the sample standard deviation (n − 1) of `values`; the deviation is 0 for
/// fewer than two values, and both are 0 for none.
#[must_use]
pub fn mean_std(values: &[f64]) -> (f64, f64) {
    let Some(mean) = crate::stats::mean(values) else {
        return (0.0, 0.0);
    };
    let n = values.len() as f64;
    if values.len() < 2 {
        return (mean, 0.0);
    }
    let var = values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0);
    (mean, var.sqrt())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ppo::{PpoConfig, PpoContinuousConfig};

    fn short() -> PpoConfig {
        PpoConfig {
            num_episodes: 8,
            ..PpoConfig::default()
        }
    }

    #[test]
    fn parallel_runs_equal_runs_one_at_a_time() -> Result<(), Box<dyn std::error::Error>> {
        let seeds = [3, 0, 7];
        let episodes = AtomicUsize::new(0);
        let runs = train_seeds(&short(), &seeds, 3, |_, _| {
            episodes.fetch_add(1, Ordering::Relaxed);
        })?;
        assert_eq!(episodes.into_inner(), 3 * 8);
        assert_eq!(runs.iter().map(|r| r.seed).collect::<Vec<_>>(), seeds);
        for run in &runs {
            let (alone, _) =
                crate::ppo::train(short(), run.seed, |_| std::ops::ControlFlow::Continue(()))?;
            assert_eq!(run.summary.returns, alone.returns, "seed {}", run.seed);
        }
        assert_ne!(runs[0].summary.returns, runs[1].summary.returns);
        Ok(())
    }

    /// Pendulum runs in parallel are the runs of [`crate::ppo::train`], one at a time.
    #[test]
    fn continuous_runs_in_parallel_equal_runs_one_at_a_time()
    -> Result<(), Box<dyn std::error::Error>> {
        let config = PpoContinuousConfig {
            num_episodes: 2,
            ..PpoContinuousConfig::default()
        };
        let episodes = AtomicUsize::new(0);
        let runs = train_seeds(&config, &[1, 0], 2, |_, r| {
            assert_eq!(r.steps, 200);
            episodes.fetch_add(1, Ordering::Relaxed);
        })?;
        assert_eq!(episodes.into_inner(), 2 * 2);
        assert_eq!(runs.iter().map(|r| r.seed).collect::<Vec<_>>(), [1, 0]);
        for run in &runs {
            let (alone, _) = crate::ppo::train(config.clone(), run.seed, |_| {
                std::ops::ControlFlow::Continue(())
            })?;
            assert_eq!(run.summary.returns, alone.returns, "seed {}", run.seed);
            assert_eq!(run.summary.env_steps, 400);
        }
        let bad = PpoContinuousConfig {
            lmbda: 2.0,
            ..config
        };
        let err = train_seeds(&bad, &[0], 1, |_, _| {}).err();
        assert!(err.is_some_and(|e| e.to_string().contains("lmbda")));
        Ok(())
    }

    #[test]
    fn an_invalid_setting_is_an_error_not_a_panic() {
        let bad = PpoConfig {
            eps: 2.0,
            ..short()
        };
        let err = train_seeds(&bad, &[0, 1], 2, |_, _| {}).err();
        assert!(
            err.is_some_and(|e| e.to_string().contains("eps")),
            "expected an error naming eps"
        );
    }

    #[test]
    fn the_band_holds_every_curve() {
        let curves = vec![vec![1.0, 5.0, 2.0], vec![3.0, 1.0], vec![2.0, 3.0, 9.0]];
        let band = Band::of(&curves);
        assert_eq!(band.mean.len(), 2, "as long as the shortest curve");
        for i in 0..2 {
            for c in &curves {
                assert!(band.low[i] <= c[i] && c[i] <= band.high[i]);
            }
            assert!(band.low[i] <= band.mean[i] && band.mean[i] <= band.high[i]);
        }
        assert_eq!(band.mean, [2.0, 3.0]);
    }

    #[test]
    fn mean_std_is_the_sample_deviation() {
        assert_eq!(mean_std(&[]), (0.0, 0.0));
        assert_eq!(mean_std(&[4.0]), (4.0, 0.0));
        let (m, s) = mean_std(&[2.0, 4.0, 4.0, 4.0, 5.0, 5.0, 7.0, 9.0]);
        assert!((m - 5.0).abs() < 1e-12);
        assert!((s - (32.0_f64 / 7.0).sqrt()).abs() < 1e-12);
    }
}
