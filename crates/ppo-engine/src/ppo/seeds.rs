//! One configuration over several seeds, trained in parallel: the evidence one curve cannot
//! give. PPO runs differ a lot from seed to seed, so a claim about a setting is a claim
//! about its spread as well as its mean.
//!
//! [`train_seeds`] runs the seed's PPO on CartPole, [`train_continuous_seeds`] the book's
//! `PPOContinuous` on Pendulum; both go through [`SeedTrainer`], one run per seed.
//!
//! ```
//! use ppo_engine::ppo::seeds::{Band, mean_std};
//!
//! let band = Band::of(&[vec![1.0, 4.0], vec![3.0, 2.0]]);
//! assert_eq!(band.mean, [2.0, 3.0]);
//! assert_eq!((band.low[1], band.high[1]), (2.0, 4.0));
//! assert_eq!(mean_std(&[1.0, 3.0]), (2.0, 2.0_f64.sqrt()));
//! ```

use std::sync::Mutex;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

use super::PpoError;
use super::config::PpoConfig;
use super::continuous::{ContinuousEpisodeReport, ContinuousTrainer, PpoContinuousConfig};
use super::train::{EpisodeReport, TrainSummary, Trainer};

/// A training run these functions can drive over many seeds: started from a configuration
/// and a seed, stepped one episode at a time, summed up at the end. [`Trainer`] (CartPole)
/// and [`ContinuousTrainer`] (Pendulum) are two.
pub trait SeedTrainer: Sized {
    /// The hyper-parameters shared by every seed's run.
    type Config: Sync;
    /// What each episode reports.
    type Report;
    /// A fresh run of `config` from `seed`.
    ///
    /// # Errors
    /// [`PpoError::InvalidConfig`] for a hyper-parameter out of range.
    fn start(config: &Self::Config, seed: u64) -> Result<Self, PpoError>;
    /// The next episode, or `None` once the run is done.
    ///
    /// # Errors
    /// [`PpoError::Diverged`] naming the episode.
    fn episode(&mut self) -> Result<Option<Self::Report>, PpoError>;
    /// The run's returns, env steps and time so far.
    fn summary(&self) -> TrainSummary;
}

impl SeedTrainer for Trainer {
    type Config = PpoConfig;
    type Report = EpisodeReport;

    fn start(config: &PpoConfig, seed: u64) -> Result<Self, PpoError> {
        Trainer::new(config.clone(), seed)
    }

    fn episode(&mut self) -> Result<Option<EpisodeReport>, PpoError> {
        self.next_episode()
    }

    fn summary(&self) -> TrainSummary {
        Trainer::summary(self)
    }
}

impl SeedTrainer for ContinuousTrainer {
    type Config = PpoContinuousConfig;
    type Report = ContinuousEpisodeReport;

    fn start(config: &PpoContinuousConfig, seed: u64) -> Result<Self, PpoError> {
        ContinuousTrainer::new(config.clone(), seed)
    }

    fn episode(&mut self) -> Result<Option<ContinuousEpisodeReport>, PpoError> {
        self.next_episode()
    }

    fn summary(&self) -> TrainSummary {
        ContinuousTrainer::summary(self)
    }
}

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

/// Trains `config` (the seed's PPO on CartPole) once per seed of `seeds`, on up to
/// `threads` threads at once, and returns the runs in the order of `seeds`. `on_episode`
/// sees every episode of every run as it finishes (from the worker threads).
///
/// # Errors
/// The first [`SeedError`]: invalid settings (reported by each seed's trainer), or a run
/// that diverged.
pub fn train_seeds(
    config: &PpoConfig,
    seeds: &[u64],
    threads: usize,
    on_episode: impl Fn(u64, &EpisodeReport) + Sync,
) -> Result<Vec<SeedRun>, SeedError> {
    train_seeds_of::<Trainer>(config, seeds, threads, on_episode)
}

/// [`train_seeds`] for the book's `PPOContinuous` on Pendulum-v1.
///
/// # Errors
/// As [`train_seeds`].
pub fn train_continuous_seeds(
    config: &PpoContinuousConfig,
    seeds: &[u64],
    threads: usize,
    on_episode: impl Fn(u64, &ContinuousEpisodeReport) + Sync,
) -> Result<Vec<SeedRun>, SeedError> {
    train_seeds_of::<ContinuousTrainer>(config, seeds, threads, on_episode)
}

/// [`train_seeds`] for any [`SeedTrainer`].
///
/// # Errors
/// As [`train_seeds`].
pub fn train_seeds_of<T: SeedTrainer>(
    config: &T::Config,
    seeds: &[u64],
    threads: usize,
    on_episode: impl Fn(u64, &T::Report) + Sync,
) -> Result<Vec<SeedRun>, SeedError> {
    let jobs: Vec<(&T::Config, u64)> = seeds.iter().map(|&s| (config, s)).collect();
    train_jobs_of::<T>(&jobs, threads, |i, report| on_episode(jobs[i].1, report))
}

/// Trains each `(config, seed)` of `jobs` (the seed's PPO on CartPole), on up to `threads`
/// threads at once, and returns the runs in the order of `jobs`. `on_episode` gets the
/// job's index and every episode.
///
/// # Errors
/// As [`train_seeds`].
pub fn train_jobs(
    jobs: &[(&PpoConfig, u64)],
    threads: usize,
    on_episode: impl Fn(usize, &EpisodeReport) + Sync,
) -> Result<Vec<SeedRun>, SeedError> {
    train_jobs_of::<Trainer>(jobs, threads, on_episode)
}

/// [`train_jobs`] for any [`SeedTrainer`].
///
/// # Errors
/// As [`train_seeds`].
pub fn train_jobs_of<T: SeedTrainer>(
    jobs: &[(&T::Config, u64)],
    threads: usize,
    on_episode: impl Fn(usize, &T::Report) + Sync,
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
            let run = one_seed::<T>(config, seed, &|report: &T::Report| on_episode(i, report));
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

fn one_seed<T: SeedTrainer>(
    config: &T::Config,
    seed: u64,
    on_episode: &dyn Fn(&T::Report),
) -> Result<SeedRun, SeedError> {
    let fail = |source| SeedError { seed, source };
    let mut trainer = T::start(config, seed).map_err(fail)?;
    while let Some(report) = trainer.episode().map_err(fail)? {
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
    if values.is_empty() {
        return (0.0, 0.0);
    }
    let n = values.len() as f64;
    let mean = values.iter().sum::<f64>() / n;
    if values.len() < 2 {
        return (mean, 0.0);
    }
    let var = values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0);
    (mean, var.sqrt())
}

#[cfg(test)]
mod tests {
    use super::*;

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

    /// Pendulum runs in parallel are the runs of [`crate::ppo::train_continuous`].
    #[test]
    fn continuous_runs_in_parallel_equal_runs_one_at_a_time()
    -> Result<(), Box<dyn std::error::Error>> {
        let config = PpoContinuousConfig {
            num_episodes: 2,
            ..PpoContinuousConfig::default()
        };
        let episodes = AtomicUsize::new(0);
        let runs = train_continuous_seeds(&config, &[1, 0], 2, |_, r| {
            assert_eq!(r.steps, 200);
            episodes.fetch_add(1, Ordering::Relaxed);
        })?;
        assert_eq!(episodes.into_inner(), 2 * 2);
        assert_eq!(runs.iter().map(|r| r.seed).collect::<Vec<_>>(), [1, 0]);
        for run in &runs {
            let (alone, _) = crate::ppo::train_continuous(config.clone(), run.seed, |_| {
                std::ops::ControlFlow::Continue(())
            })?;
            assert_eq!(run.summary.returns, alone.returns, "seed {}", run.seed);
            assert_eq!(run.summary.env_steps, 400);
        }
        let bad = PpoContinuousConfig {
            lmbda: 2.0,
            ..config
        };
        let err = train_continuous_seeds(&bad, &[0], 1, |_, _| {}).err();
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
