//! Statistics over seeds that a sceptic accepts: the interquartile mean, a seeded percentile
//! bootstrap interval, and the paired comparison of two settings run on the same seeds.
//!
//! A PPO score is one number per seed, and seeds differ a lot, so a claim "A beats B" is a
//! claim about a handful of noisy numbers. The rules the course follows (Agarwal et al.,
//! *Deep RL at the Edge of the Statistical Precipice*, NeurIPS 2021, whose library `rliable`
//! these estimates are checked against in `tests/fixtures/rliable_scores.json`):
//!
//! ```text
//! mean        = (1/n) Σ_i x_i
//! IQM         = mean of the middle half: sort x, drop ⌊n/4⌋ from each end
//!               (scipy's trim_mean(x, 0.25), rliable's aggregate_iqm)
//! bootstrap   = draw n seeds with replacement, reps times; the statistic of each draw
//! interval    = the (1−c)/2 and (1+c)/2 percentiles of the draws (c = 0.95),
//!               numpy's linear interpolation between order statistics
//! paired d_i  = arm_i − baseline_i on the same seed i: the bootstrap draws seeds, so a
//!               seed's two runs stay together and what the seeds share cancels
//! verdict     = higher / lower only when the interval of mean(d) excludes 0,
//!               otherwise "no difference shown at n seeds"
//! ```
//!
//! The draws come from a seeded PCG64, so every figure is reproducible.
//!
//! ```
//! use ppo_rl::stats::{Bootstrap, Verdict, iqm};
//!
//! assert_eq!(iqm(&[1.0, 2.0, 3.0, 4.0, 100.0]), Some(3.0)); // drops 1 and 100
//! let boot = Bootstrap::default();
//! let base = [480.0, 490.0, 500.0, 470.0, 495.0];
//! let arm = [470.0, 481.0, 489.0, 462.0, 486.0]; // 8 to 11 lower on every seed
//! let paired = boot.paired(&arm, &base)?;
//! assert_eq!(paired.verdict(), Verdict::Lower);
//! assert!(paired.ci.high < 0.0);
//! # Ok::<(), ppo_rl::stats::StatsError>(())
//! ```

use crate::env::seeding::NumpyRng;
use crate::tr;

/// Why a statistic could not be computed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum StatsError {
    /// Fewer values than the statistic needs.
    #[error("{}", tr!(
        "{n} score(s): an interval needs at least {needed}; run more seeds",
        "只有 {n} 个分数：区间至少需要 {needed} 个；请多跑几个随机种子"
    ))]
    TooFew {
        /// How many values there were.
        n: usize,
        /// How many it needs.
        needed: usize,
    },
    /// A paired comparison of two lists of different lengths.
    #[error("{}", tr!(
        "a paired comparison needs one score per seed in both settings: the arm has {arm}, \
         the baseline {baseline}; run both on the same seeds",
        "配对比较需要两种设置在每个随机种子上各有一个分数：实验组有 {arm} 个，基线有 {baseline} 个；\
         请在相同的随机种子上运行两者"
    ))]
    Unpaired {
        /// The arm's number of scores.
        arm: usize,
        /// The baseline's.
        baseline: usize,
    },
    /// A score that is NaN or infinite.
    #[error("{}", tr!(
        "score {index} is {value}: every score must be a finite number",
        "第 {index} 个分数是 {value}：每个分数都必须是有限数"
    ))]
    NonFinite {
        /// Its position (from 0).
        index: usize,
        /// The value.
        value: f64,
    },
    /// Settings of the bootstrap out of range.
    #[error("{}", tr!(
        "bootstrap settings: {what}",
        "自助法的设置：{what}"
    ))]
    Settings {
        /// What is wrong and the range it needs.
        what: String,
    },
}

/// The mean of `xs`; `None` when empty.
#[must_use]
pub fn mean(xs: &[f64]) -> Option<f64> {
    (!xs.is_empty()).then(|| xs.iter().sum::<f64>() / xs.len() as f64)
}

/// The interquartile mean: the mean of `xs` sorted with `⌊n/4⌋` values dropped from each
/// end (scipy's `trim_mean(xs, 0.25)`, rliable's `aggregate_iqm`); `None` when empty or when
/// a value is NaN.
#[must_use]
pub fn iqm(xs: &[f64]) -> Option<f64> {
    if xs.iter().any(|x| x.is_nan()) {
        return None;
    }
    let mut sorted = xs.to_vec();
    sorted.sort_by(f64::total_cmp);
    iqm_sorted(&sorted)
}

fn iqm_sorted(sorted: &[f64]) -> Option<f64> {
    let cut = sorted.len() / 4;
    mean(&sorted[cut..sorted.len() - cut])
}

/// A two-sided interval `[low, high]`.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Interval {
    /// The lower end.
    pub low: f64,
    /// The upper end.
    pub high: f64,
}

impl Interval {
    /// Whether 0 lies outside the interval (its ends included in it).
    #[must_use]
    pub fn excludes_zero(&self) -> bool {
        self.low > 0.0 || self.high < 0.0
    }

    /// `high − low`.
    #[must_use]
    pub fn width(&self) -> f64 {
        self.high - self.low
    }
}

/// A point estimate with its bootstrap interval.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Estimate {
    /// The statistic on the scores themselves.
    pub point: f64,
    /// Its percentile bootstrap interval.
    pub ci: Interval,
    /// How many scores (seeds).
    pub n: usize,
}

/// What a paired comparison shows.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Verdict {
    /// The interval of the mean difference lies above 0.
    Higher,
    /// It lies below 0.
    Lower,
    /// It contains 0: no difference shown at this number of seeds.
    NotShown,
}

/// Two settings compared seed by seed: `d_i = arm_i − baseline_i`.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Paired {
    /// The per-seed differences, in the seeds' order.
    pub differences: Vec<f64>,
    /// Their mean.
    pub mean_difference: f64,
    /// The bootstrap interval of the mean difference.
    pub ci: Interval,
}

impl Paired {
    /// How many seeds were paired.
    #[must_use]
    pub fn n(&self) -> usize {
        self.differences.len()
    }

    /// Higher or lower only where the interval excludes 0.
    #[must_use]
    pub fn verdict(&self) -> Verdict {
        if self.ci.low > 0.0 {
            Verdict::Higher
        } else if self.ci.high < 0.0 {
            Verdict::Lower
        } else {
            Verdict::NotShown
        }
    }
}

/// The percentile bootstrap's settings: how many draws, the interval's coverage, the seed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bootstrap {
    /// Bootstrap replications (rliable's default, 50 000).
    pub reps: usize,
    /// The interval's coverage, in (0, 1) (0.95).
    pub confidence: f64,
    /// The seed of the draws (0).
    pub seed: u64,
}

impl Default for Bootstrap {
    fn default() -> Self {
        Self {
            reps: 50_000,
            confidence: 0.95,
            seed: 0,
        }
    }
}

impl Bootstrap {
    /// The mean of `scores` with its interval.
    ///
    /// # Errors
    /// [`StatsError`] for fewer than 2 scores, a non-finite one, or settings out of range.
    pub fn mean(&self, scores: &[f64]) -> Result<Estimate, StatsError> {
        self.estimate(scores, |s| s.iter().sum::<f64>() / s.len() as f64)
    }

    /// The interquartile mean of `scores` with its interval.
    ///
    /// # Errors
    /// As [`Self::mean`].
    pub fn iqm(&self, scores: &[f64]) -> Result<Estimate, StatsError> {
        self.estimate(scores, |s| {
            let mut sorted = s.to_vec();
            sorted.sort_by(f64::total_cmp);
            iqm_sorted(&sorted).unwrap_or(f64::NAN)
        })
    }

    /// `arm` against `baseline`, seed by seed: the mean of the differences and its interval.
    ///
    /// # Errors
    /// [`StatsError::Unpaired`] when the lengths differ; otherwise as [`Self::mean`].
    pub fn paired(&self, arm: &[f64], baseline: &[f64]) -> Result<Paired, StatsError> {
        if arm.len() != baseline.len() {
            return Err(StatsError::Unpaired {
                arm: arm.len(),
                baseline: baseline.len(),
            });
        }
        let differences: Vec<f64> = arm.iter().zip(baseline).map(|(a, b)| a - b).collect();
        let Estimate { point, ci, .. } = self.mean(&differences)?;
        Ok(Paired {
            differences,
            mean_difference: point,
            ci,
        })
    }

    fn check(&self, scores: &[f64]) -> Result<(), StatsError> {
        if self.reps < 2 {
            return Err(StatsError::Settings {
                what: tr!(
                    "reps = {}: at least 2 draws",
                    "reps = {}：至少抽 2 次",
                    self.reps
                ),
            });
        }
        if !(self.confidence > 0.0 && self.confidence < 1.0) {
            return Err(StatsError::Settings {
                what: tr!(
                    "confidence = {}: a number strictly between 0 and 1",
                    "confidence = {}：必须严格介于 0 与 1 之间",
                    self.confidence
                ),
            });
        }
        if scores.len() < 2 {
            return Err(StatsError::TooFew {
                n: scores.len(),
                needed: 2,
            });
        }
        if let Some((index, &value)) = scores.iter().enumerate().find(|(_, x)| !x.is_finite()) {
            return Err(StatsError::NonFinite { index, value });
        }
        Ok(())
    }

    fn estimate(
        &self,
        scores: &[f64],
        statistic: impl Fn(&[f64]) -> f64,
    ) -> Result<Estimate, StatsError> {
        self.check(scores)?;
        let n = scores.len();
        let mut rng = NumpyRng::from_seed(self.seed);
        let mut draw = vec![0.0; n];
        let mut stats = Vec::with_capacity(self.reps);
        for _ in 0..self.reps {
            for slot in &mut draw {
                *slot = scores[below(&mut rng, n)];
            }
            stats.push(statistic(&draw));
        }
        stats.sort_by(f64::total_cmp);
        let tail = (1.0 - self.confidence) / 2.0;
        Ok(Estimate {
            point: statistic(scores),
            ci: Interval {
                low: percentile(&stats, tail),
                high: percentile(&stats, 1.0 - tail),
            },
            n,
        })
    }
}

/// A uniform index in `0..n`, unbiased (Lemire's multiply-and-reject).
fn below(rng: &mut NumpyRng, n: usize) -> usize {
    let n = n as u64;
    let threshold = n.wrapping_neg() % n;
    loop {
        let m = u128::from(rng.next_u64()) * u128::from(n);
        if (m as u64) >= threshold {
            return (m >> 64) as usize;
        }
    }
}

/// numpy's `percentile(sorted, 100·q)` with linear interpolation, on sorted values.
fn percentile(sorted: &[f64], q: f64) -> f64 {
    let pos = q * (sorted.len() - 1) as f64;
    let lo = pos.floor() as usize;
    let hi = (lo + 1).min(sorted.len() - 1);
    let t = pos - lo as f64;
    let (a, b) = (sorted[lo], sorted[hi]);
    // numpy's _lerp: exact at both ends
    if t >= 0.5 {
        b - (b - a) * (1.0 - t)
    } else {
        a + (b - a) * t
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn iqm_drops_a_quarter_from_each_end_rounding_down() {
        assert_eq!(iqm(&[]), None);
        assert_eq!(iqm(&[7.0]), Some(7.0));
        assert_eq!(iqm(&[1.0, 2.0, 3.0]), Some(2.0)); // ⌊3/4⌋ = 0: the plain mean
        assert_eq!(iqm(&[10.0, 1.0, 3.0, 2.0]), Some(2.5)); // drops 1 and 10
        assert_eq!(iqm(&[1.0, f64::NAN]), None);
    }

    #[test]
    fn percentiles_interpolate_as_numpy() {
        let s = [0.0, 10.0, 20.0, 30.0];
        assert_eq!(percentile(&s, 0.0), 0.0);
        assert_eq!(percentile(&s, 1.0), 30.0);
        assert!((percentile(&s, 0.5) - 15.0).abs() < 1e-12);
        assert!((percentile(&s, 0.025) - 0.75).abs() < 1e-12);
    }

    #[test]
    fn indices_are_uniform() {
        let mut rng = NumpyRng::from_seed(3);
        let mut counts = [0_usize; 3];
        for _ in 0..30_000 {
            counts[below(&mut rng, 3)] += 1;
        }
        for c in counts {
            assert!((9_500..10_500).contains(&c), "{counts:?}");
        }
    }

    #[test]
    fn the_same_seed_gives_the_same_interval_and_another_seed_another() -> Result<(), StatsError> {
        let xs = [1.0, 5.0, 2.0, 8.0, 3.0, 9.0];
        let a = Bootstrap::default().mean(&xs)?;
        assert_eq!(a, Bootstrap::default().mean(&xs)?);
        let b = Bootstrap {
            seed: 1,
            ..Bootstrap::default()
        }
        .mean(&xs)?;
        assert_ne!(a.ci, b.ci);
        assert_eq!(a.point, b.point);
        Ok(())
    }

    #[test]
    fn a_difference_within_the_seeds_noise_is_not_shown() -> Result<(), StatsError> {
        let boot = Bootstrap::default();
        let base = [480.0, 490.0, 500.0, 470.0, 495.0];
        let arm = [490.0, 470.0, 505.0, 480.0, 480.0]; // +10, −20, +5, +10, −15
        let p = boot.paired(&arm, &base)?;
        assert_eq!(p.verdict(), Verdict::NotShown);
        assert!(!p.ci.excludes_zero());
        let all_higher: Vec<f64> = base.iter().map(|b| b + 3.0).collect();
        assert_eq!(boot.paired(&all_higher, &base)?.verdict(), Verdict::Higher);
        Ok(())
    }

    #[test]
    fn bad_input_is_refused_with_what_is_wrong() {
        let boot = Bootstrap::default();
        assert_eq!(
            boot.mean(&[1.0]),
            Err(StatsError::TooFew { n: 1, needed: 2 })
        );
        assert_eq!(
            boot.paired(&[1.0, 2.0], &[1.0]),
            Err(StatsError::Unpaired {
                arm: 2,
                baseline: 1
            })
        );
        assert!(matches!(
            boot.iqm(&[1.0, f64::INFINITY]),
            Err(StatsError::NonFinite { index: 1, .. })
        ));
        let bad = Bootstrap {
            confidence: 1.0,
            ..boot
        };
        assert!(matches!(
            bad.mean(&[1.0, 2.0]),
            Err(StatsError::Settings { .. })
        ));
        let message = StatsError::TooFew { n: 1, needed: 2 }.to_string();
        assert!(message.contains("more seeds"), "{message}");
    }
}
