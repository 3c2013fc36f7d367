//! What a lab run found: each arm's band of curves, its seeds' final scores and what its
//! updates did, and the tables and paired comparisons the lab prints from them.
//!
//! A comparison is paired: every arm ran the base's seeds, so the lab takes each seed's
//! difference `arm − base` and its bootstrap interval ([`crate::stats`]). An arm is
//! "higher" or "lower" only when that interval excludes zero; otherwise the lab says "no
//! difference shown at N seeds".

use crate::i18n::{pad_left, pad_right, t};
use crate::stats::{Bootstrap, Paired, Verdict};
use crate::tr;
use serde::Serialize;

use super::super::config::PpoConfig;
use super::super::seeds::{Band, mean_std};
use super::super::train::EpisodeReport;
use super::{Experiment, LAST};

/// What the updates of one run did, averaged over its updates (the last epoch of each).
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize)]
pub struct UpdateStats {
    /// Mean `approx_kl` of the last epoch that stepped.
    pub approx_kl: f64,
    /// Mean fraction of rows outside `[1 − ε, 1 + ε]` in the last epoch.
    pub clip_fraction: f64,
    /// Mean over updates of the largest `|r − 1|` in the last epoch.
    pub max_ratio_deviation: f64,
    /// Mean number of epochs that stepped.
    pub epochs_run: f64,
    /// Mean over updates of the exact `KL(π_old ‖ π_new)` between the actor before and after
    /// each update ([`UpdateTrace::kl_after`](super::UpdateTrace::kl_after)), the same
    /// measure for every objective: how far each update moved the policy.
    pub kl_after: f64,
    /// The largest per-update `kl_after` (over seeds: the largest of any seed).
    pub kl_after_max: f64,
    /// PPO-Penalty: the smallest and largest β any update used or left; `None` for the
    /// other objectives.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub beta_range: Option<(f64, f64)>,
    /// The KL line search: mean halvings per update; `None` for the other objectives.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub ls_halvings: Option<f64>,
    /// The KL line search: the share of updates whose every try was refused (the actor
    /// kept θ_old); `None` for the other objectives.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub ls_refused: Option<f64>,
}

#[derive(Debug, Clone, Copy, Default)]
pub(super) struct Sums {
    kl: f64,
    clip: f64,
    dev: f64,
    epochs: f64,
    updates: f64,
    kl_after: f64,
    kl_after_max: f64,
    beta: Option<(f64, f64)>,
    searches: f64,
    halvings: f64,
    refused: f64,
}

/// The range covering `range` (if any) and `lo..=hi`.
fn widen(range: Option<(f64, f64)>, lo: f64, hi: f64) -> (f64, f64) {
    range.map_or((lo, hi), |(a, b)| (a.min(lo), b.max(hi)))
}

impl Sums {
    pub(super) fn add(&mut self, report: &EpisodeReport) {
        let trace = &report.trace;
        self.updates += 1.0;
        self.epochs += trace.epochs_run() as f64;
        let kl_after = f64::from(trace.kl_after.unwrap_or(0.0));
        self.kl_after += kl_after;
        self.kl_after_max = self.kl_after_max.max(kl_after);
        if let Some(p) = trace.penalty {
            let (lo, hi) = (
                p.beta_before.min(p.beta_after),
                p.beta_before.max(p.beta_after),
            );
            self.beta = Some(widen(self.beta, lo, hi));
        }
        if let Some(s) = trace.line_search {
            self.searches += 1.0;
            self.halvings += s.halvings as f64;
            self.refused += f64::from(u8::from(s.step.is_none()));
        }
        if let Some(e) = trace.epochs.last() {
            self.kl += f64::from(e.approx_kl);
            self.clip += f64::from(e.clip_fraction);
            self.dev += e
                .ratio
                .iter()
                .map(|r| f64::from((r - 1.0).abs()))
                .fold(0.0, f64::max);
        }
    }

    pub(super) fn stats(self) -> UpdateStats {
        let n = self.updates.max(1.0);
        UpdateStats {
            approx_kl: self.kl / n,
            clip_fraction: self.clip / n,
            max_ratio_deviation: self.dev / n,
            epochs_run: self.epochs / n,
            kl_after: self.kl_after / n,
            kl_after_max: self.kl_after_max,
            beta_range: self.beta,
            ls_halvings: (self.searches > 0.0).then(|| self.halvings / self.searches),
            ls_refused: (self.searches > 0.0).then(|| self.refused / self.searches),
        }
    }
}

/// One arm's outcome over the seeds.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ArmResult {
    /// The arm's label.
    pub label: String,
    /// Its configuration.
    pub config: PpoConfig,
    /// Each seed's returns, in the order of the seeds.
    pub returns: Vec<Vec<f64>>,
    /// The band of the seeds' smoothed curves (moving average, window 9).
    pub band: Band,
    /// Each seed's mean of its last [`LAST`] returns.
    pub finals: Vec<f64>,
    /// Each seed's update statistics.
    pub updates: Vec<UpdateStats>,
}

impl ArmResult {
    /// The mean and sample std of [`Self::finals`].
    #[must_use]
    pub fn final_mean_std(&self) -> (f64, f64) {
        mean_std(&self.finals)
    }

    /// The update statistics averaged over seeds.
    #[must_use]
    pub fn mean_updates(&self) -> UpdateStats {
        let n = self.updates.len().max(1) as f64;
        let sum = |f: fn(&UpdateStats) -> f64| self.updates.iter().map(f).sum::<f64>() / n;
        let some = |f: fn(&UpdateStats) -> Option<f64>| {
            let xs: Vec<f64> = self.updates.iter().filter_map(f).collect();
            (!xs.is_empty()).then(|| xs.iter().sum::<f64>() / xs.len() as f64)
        };
        UpdateStats {
            approx_kl: sum(|u| u.approx_kl),
            clip_fraction: sum(|u| u.clip_fraction),
            max_ratio_deviation: sum(|u| u.max_ratio_deviation),
            epochs_run: sum(|u| u.epochs_run),
            kl_after: sum(|u| u.kl_after),
            kl_after_max: self
                .updates
                .iter()
                .map(|u| u.kl_after_max)
                .fold(0.0, f64::max),
            beta_range: self
                .updates
                .iter()
                .filter_map(|u| u.beta_range)
                .fold(None, |r, (lo, hi)| Some(widen(r, lo, hi))),
            ls_halvings: some(|u| u.ls_halvings),
            ls_refused: some(|u| u.ls_refused),
        }
    }

    /// The first episode (from 0, as on the plots' x axis) at which the mean smoothed curve
    /// reaches `level`, if it does.
    #[must_use]
    pub fn first_reaching(&self, level: f64) -> Option<usize> {
        self.band.mean.iter().position(|&v| v >= level)
    }

    /// The lowest seed's last-50 mean.
    #[must_use]
    pub fn worst_final(&self) -> f64 {
        self.finals.iter().copied().fold(f64::INFINITY, f64::min)
    }

    /// How far the arm's updates moved the policy, for the proximal experiment: the mean and
    /// largest per-update `KL(π_old ‖ π_new)`, with PPO-Penalty's β range and the line
    /// search's mean halvings and refusals where they apply.
    #[must_use]
    pub fn kl_summary(&self) -> String {
        let u = self.mean_updates();
        let mut out = tr!(
            "{}: per-update KL(π_old ‖ π_new) {:.4} on average, at most {:.4}",
            "{}：每次更新的 KL(π_old ‖ π_new) 平均 {:.4}，最大 {:.4}",
            self.label,
            u.kl_after,
            u.kl_after_max
        );
        if let Some((lo, hi)) = u.beta_range {
            out.push_str(&tr!(
                "; β between {lo:.1e} and {hi:.1e}",
                "；β 介于 {lo:.1e} 与 {hi:.1e} 之间"
            ));
        }
        if let (Some(h), Some(r)) = (u.ls_halvings, u.ls_refused) {
            out.push_str(&tr!(
                "; {h:.2} halvings per update, {:.1}% of updates without a step",
                "；每次更新平均减半 {h:.2} 次，{:.1}% 的更新没有迈步",
                100.0 * r
            ));
        }
        out
    }

    /// One sentence the lessons quote: the final score over seeds, the worst seed, and when
    /// the mean curve reaches 400.
    #[must_use]
    pub fn summary(&self) -> String {
        let (mean, std) = self.final_mean_std();
        let reach = self.first_reaching(400.0).map_or_else(
            || t("never reaches 400", "始终没有达到 400").to_string(),
            |e| tr!("reaches 400 at episode {e}", "在第 {e} 回合达到 400"),
        );
        tr!(
            "{}: {mean:.1} ± {std:.1}, worst seed {:.1}; its mean curve {reach}",
            "{}：{mean:.1} ± {std:.1}，最差的随机种子 {:.1}；平均曲线{reach}",
            self.label,
            self.worst_final()
        )
    }
}

/// A finished experiment.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LabResult {
    /// Which experiment.
    pub experiment: Experiment,
    /// The seeds every arm ran.
    pub seeds: Vec<u64>,
    /// Episodes per run.
    pub episodes: usize,
    /// The arms, base first.
    pub arms: Vec<ArmResult>,
    /// [`LabResult::paired`], computed on first use (a bootstrap per arm: the app's panel
    /// draws it every frame).
    #[serde(skip)]
    pub(crate) paired: std::sync::OnceLock<Vec<Option<Paired>>>,
}

/// A paired difference in words: `−12.3 [−25.1, −1.2]: lower`, or `... : no difference
/// shown at 5 seeds` when the interval contains zero.
#[must_use]
pub fn paired_words(p: &Paired) -> String {
    let verdict = match p.verdict() {
        Verdict::Higher => t("higher", "更高").to_string(),
        Verdict::Lower => t("lower", "更低").to_string(),
        Verdict::NotShown => tr!(
            "no difference shown at {} seeds",
            "{} 个随机种子下没有显示出差异",
            p.n()
        ),
    };
    tr!(
        "{:+.1} [{:+.1}, {:+.1}]: {verdict}",
        "{:+.1} [{:+.1}, {:+.1}]：{verdict}",
        p.mean_difference,
        p.ci.low,
        p.ci.high
    )
}

/// [`paired_words`] for a comparison that may have no interval: with fewer than two of the
/// `n` seeds there is none, and the words say so and how to get one.
#[must_use]
pub(crate) fn paired_words_or_none(p: Option<&Paired>, n: usize) -> String {
    p.map_or_else(
        || {
            tr!(
                "no interval from {n} seed(s): run at least 2",
                "{n} 个随机种子算不出区间：至少需要 2 个"
            )
        },
        paired_words,
    )
}

impl LabResult {
    /// Each arm after the first against the first, seed by seed: the differences of the
    /// seeds' last-50 means, their mean and its 95% bootstrap interval. `None` for an arm
    /// where no interval exists (fewer than two seeds).
    #[must_use]
    pub fn paired(&self) -> &[Option<Paired>] {
        self.paired.get_or_init(|| {
            let Some((base, others)) = self.arms.split_first() else {
                return Vec::new();
            };
            others
                .iter()
                .map(|arm| Bootstrap::default().paired(&arm.finals, &base.finals).ok())
                .collect()
        })
    }

    /// The paired comparisons as lines: a heading naming the base and the seeds, then one
    /// line per other arm ([`paired_words`]).
    #[must_use]
    pub fn comparisons(&self) -> Vec<String> {
        let Some(base) = self.arms.first() else {
            return Vec::new();
        };
        let n = self.seeds.len();
        let label_width = self.label_width();
        let mut lines = vec![tr!(
            "each setting − {} on the same {n} seeds (mean difference of the last-{LAST} means, 95% bootstrap interval):",
            "各设置 − {}，在相同的 {n} 个随机种子上（最后 {LAST} 个回报均值之差的平均，95% 自助法置信区间）：",
            base.label
        )];
        for (arm, paired) in self.arms.iter().skip(1).zip(self.paired()) {
            let words = paired_words_or_none(paired.as_ref(), n);
            lines.push(format!("{} {words}", pad_right(&arm.label, label_width)));
        }
        lines
    }

    /// The width of the labels' column: the widest label, at least 30.
    fn label_width(&self) -> usize {
        self.arms
            .iter()
            .map(|a| crate::i18n::width(&a.label))
            .fold(30, usize::max)
    }

    /// The result as a table, one row per setting: the mean ± sample std over seeds of each
    /// seed's last-50 mean, and the update statistics averaged over seeds.
    ///
    /// The proximal experiment adds two columns after the score: the mean and the largest
    /// per-update exact `KL(π_old ‖ π_new)` ([`UpdateStats::kl_after`]), the one measure all
    /// its arms share. Labels wider than 30 columns widen the first column.
    #[must_use]
    pub fn table(&self) -> Vec<String> {
        let label_width = self.label_width();
        let with_kl = self.experiment == Experiment::Proximal;
        let kl_head = if with_kl {
            format!(
                " {} {}",
                pad_left(t("KL/update", "每次更新 KL"), 11),
                pad_left(t("max KL", "最大 KL"), 8)
            )
        } else {
            String::new()
        };
        let mut lines = vec![format!(
            "{} {}{kl_head} {:>9} {} {:>8} {}",
            pad_right(
                &tr!(
                    "setting (last {LAST} returns)",
                    "设置（最后 {LAST} 个回报）"
                ),
                label_width
            ),
            pad_left(t("mean ± std", "均值 ± 标准差"), 15),
            "approx_kl",
            pad_left(t("clip frac", "截断比例"), 9),
            "max|r−1|",
            pad_left(t("epochs", "轮数"), 6)
        )];
        for arm in &self.arms {
            let (mean, std) = arm.final_mean_std();
            let u = arm.mean_updates();
            let kl = if with_kl {
                format!(" {:>11.4} {:>8.4}", u.kl_after, u.kl_after_max)
            } else {
                String::new()
            };
            lines.push(format!(
                "{} {:>15}{kl} {:>9.4} {:>9.3} {:>8.3} {:>6.1}",
                pad_right(&arm.label, label_width),
                format!("{mean:.1} ± {std:.1}"),
                u.approx_kl,
                u.clip_fraction,
                u.max_ratio_deviation,
                u.epochs_run
            ));
        }
        lines
    }
}
