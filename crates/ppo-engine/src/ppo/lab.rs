//! The clip lab: one of PPO's knobs changed at a time, every arm trained over the same
//! seeds, so that a difference between arms is a difference between settings and not the
//! luck of one seed. Lesson 13 runs the experiments on the clip and the actor's steps,
//! lesson 4 the comparison with REINFORCE, and lesson 15 one experiment per remaining
//! setting (critic_lr, hidden_dim, gamma, lmbda), each predicted before it runs.
//!
//! An [`Experiment`] lists its arms; the first is always the base configuration (the seed's
//! settings unless the caller changed them). [`run`] trains every `(arm, seed)` pair on a
//! pool of threads and summarises each arm: the band of its smoothed return curves, each
//! seed's mean of the last 50 returns, and what the updates did (approx_kl, clip fraction,
//! the ratios' largest distance from 1, epochs run).
//!
//! The proximal experiment compares four ways to stay near π_old (the clip, PPO-Penalty, the
//! KL line search, none) and reports, for every arm, the same per-update exact KL.
//!
//! ```
//! use ppo_engine::ppo::lab::Experiment;
//! use ppo_engine::ppo::PpoConfig;
//!
//! let arms = Experiment::Eps.arms(&PpoConfig::default());
//! assert_eq!(arms.len(), 3);
//! assert_eq!(arms[0].config, PpoConfig::default());
//! assert!(arms[2].config.no_clip);
//! ```

use std::collections::HashMap;
use std::sync::{Mutex, OnceLock};

use crate::i18n::t;
use crate::tr;
use serde::Serialize;

use super::config::{PpoConfig, UpdateRule};
use super::moving_average::smoothed_returns;
use super::seeds::{Band, SeedError, train_jobs};
use super::train::mean_last;

mod predict;
mod results;

pub use predict::{Outcome, PredictionGrade, choice_index, letters};
use results::Sums;
pub(crate) use results::paired_words_or_none;
pub use results::{ArmResult, LabResult, UpdateStats, paired_words};

/// The returns each seed's final score averages.
pub const LAST: usize = 50;

/// The experiments of the clip lab, the policy-gradient lesson's comparison, and the
/// hyper-parameter lesson's one-knob runs.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Experiment {
    /// The clip range: ε = 0.2 (the seed), 0.05, and no clip at all.
    Eps,
    /// Passes over each episode: 10 (the seed), 1 and 40; then 1 for the actor with the
    /// critic's 10, and 10 for the actor with the critic's 1, which tell apart what each
    /// network's reuse of an episode does; and one actor step at ten times the learning
    /// rate with the critic's 10, which moves the actor about as far per episode as the
    /// seed's ten steps without reusing the episode.
    Epochs,
    /// The actor's learning rate: 1e-3 (the seed) and ten times that.
    ActorLr,
    /// Early stopping: 40 epochs with and without `target_kl = 0.01`, beside the seed.
    TargetKl,
    /// PPO (the seed) against REINFORCE with a baseline.
    Reinforce,
    /// The critic's learning rate: 1e-2 (the seed) and a tenth of that.
    CriticLr,
    /// The width of both networks' hidden layer: 128 (the seed) and 16.
    HiddenDim,
    /// The discount factor γ: 0.98 (the seed), 0.9 and 0.999.
    Gamma,
    /// GAE's λ: 0.95 (the seed), 0.5 and 1.
    Lmbda,
    /// Four ways to stay near π_old: the clip (the seed), PPO-Penalty's adaptive β, the KL
    /// line search, and none of them; with each arm's per-update KL.
    Proximal,
}

/// One setting of an experiment.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Arm {
    /// How the lesson and the plot name it, e.g. `ε = 0.05`.
    pub label: String,
    /// Its configuration.
    pub config: PpoConfig,
}

impl Experiment {
    /// Every experiment, in the order the lessons use them.
    pub const ALL: [Self; 10] = [
        Self::Eps,
        Self::Epochs,
        Self::ActorLr,
        Self::TargetKl,
        Self::Reinforce,
        Self::CriticLr,
        Self::HiddenDim,
        Self::Gamma,
        Self::Lmbda,
        Self::Proximal,
    ];

    /// The name on the command line and in lessons (`eps`, `epochs`, `actor-lr`,
    /// `target-kl`, `reinforce`, `critic-lr`, `hidden-dim`, `gamma`, `lmbda`, `proximal`).
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::Eps => "eps",
            Self::Epochs => "epochs",
            Self::ActorLr => "actor-lr",
            Self::TargetKl => "target-kl",
            Self::Reinforce => "reinforce",
            Self::CriticLr => "critic-lr",
            Self::HiddenDim => "hidden-dim",
            Self::Gamma => "gamma",
            Self::Lmbda => "lmbda",
            Self::Proximal => "proximal",
        }
    }

    /// The experiment called `name`.
    #[must_use]
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|e| e.name() == name)
    }

    /// The question the experiment answers.
    #[must_use]
    pub fn question(self) -> &'static str {
        match self {
            Self::Eps => t(
                "What does the clip range do, and what happens without a clip?",
                "截断范围起什么作用？不截断又会怎样？",
            ),
            Self::Epochs => t(
                "How many passes over one episode help, which network's, and when do they hurt?",
                "在一个回合的数据上训练几轮有帮助？是哪个网络的几轮？什么时候反而有害？",
            ),
            Self::ActorLr => t(
                "What does a ten times larger actor step do to PPO?",
                "策略网络的步长放大十倍，PPO 会怎样？",
            ),
            Self::TargetKl => t(
                "Can early stopping rescue too many epochs?",
                "提前停止能挽救轮数过多的训练吗？",
            ),
            Self::Reinforce => t(
                "What do the ratio, the clip and the epochs buy over REINFORCE?",
                "与 REINFORCE 相比，比率、截断和多轮训练带来了什么？",
            ),
            Self::CriticLr => t(
                "What does a ten times smaller critic step do to the actor's learning?",
                "价值网络的步长缩小到十分之一，策略网络的学习会怎样？",
            ),
            Self::HiddenDim => t(
                "Does CartPole need 128 hidden units, or do 16 do?",
                "车杆任务需要 128 个隐藏单元吗？16 个够不够？",
            ),
            Self::Gamma => t(
                "What does the horizon 1/(1 − γ) do, shorter or longer than the seed's 50 steps?",
                "视野 1/(1 − γ) 比原教程代码的 50 步更短或更长，会怎样？",
            ),
            Self::Lmbda => t(
                "What does GAE's λ change: trusting the critic more, or less?",
                "GAE 的 λ 改变了什么：更信任价值网络，还是更不信任？",
            ),
            Self::Proximal => t(
                "Clip, KL penalty, KL line search or nothing: which way of staying near π_old learns best, and how far does each move the policy per update?",
                "截断、KL 惩罚、KL 线搜索，还是什么都不用：哪种让策略留在 π_old 附近的办法学得最好？每次更新又让策略移动多远？",
            ),
        }
    }

    /// The arms, `base` first (labelled with what it is), then the changed settings.
    #[must_use]
    pub fn arms(self, base: &PpoConfig) -> Vec<Arm> {
        let arm = |label: String, config: PpoConfig| Arm { label, config };
        let with = |f: &dyn Fn(&mut PpoConfig)| {
            let mut c = base.clone();
            f(&mut c);
            c
        };
        let first = |what: String| arm(what, base.clone());
        match self {
            Self::Eps => vec![
                first(format!("ε = {}", base.eps)),
                arm("ε = 0.05".into(), with(&|c| c.eps = 0.05)),
                arm(
                    t("no clip", "不截断").into(),
                    base.clone().with_rule(UpdateRule::NoClip),
                ),
            ],
            Self::Epochs => {
                let (actor, critic) = base.epochs_of_each();
                vec![
                    first(tr!("{} epochs", "{} 轮", base.epochs)),
                    arm(t("1 epoch", "1 轮").into(), with(&|c| c.epochs = 1)),
                    arm(t("40 epochs", "40 轮").into(), with(&|c| c.epochs = 40)),
                    // only the actor's epochs change, then only the critic's
                    arm(
                        tr!(
                            "actor 1, critic {critic} epochs",
                            "策略网络 1 轮，价值网络 {critic} 轮"
                        ),
                        with(&|c| {
                            c.epochs = 1;
                            c.critic_epochs = Some(critic);
                        }),
                    ),
                    arm(
                        tr!(
                            "actor {actor}, critic 1 epoch",
                            "策略网络 {actor} 轮，价值网络 1 轮"
                        ),
                        with(&|c| {
                            c.epochs = actor;
                            c.critic_epochs = Some(1);
                        }),
                    ),
                    // one actor step as long as the base's steps together (Adam moves a
                    // weight by about the learning rate per step): the actor's movement
                    // per episode without its reuse of the episode
                    arm(
                        tr!(
                            "actor 1 at {:.0e}, critic {critic} epochs",
                            "策略网络 1 轮（{:.0e}），价值网络 {critic} 轮",
                            base.actor_lr * actor as f64
                        ),
                        with(&|c| {
                            c.epochs = 1;
                            c.critic_epochs = Some(critic);
                            c.actor_lr *= actor as f64;
                        }),
                    ),
                ]
            }
            Self::ActorLr => vec![
                first(format!("actor_lr = {:.0e}", base.actor_lr)),
                arm(
                    format!("actor_lr = {:.0e}", base.actor_lr * 10.0),
                    with(&|c| c.actor_lr *= 10.0),
                ),
            ],
            Self::TargetKl => vec![
                first(tr!("{} epochs", "{} 轮", base.epochs)),
                arm(t("40 epochs", "40 轮").into(), with(&|c| c.epochs = 40)),
                arm(
                    t("40 epochs, target_kl = 0.01", "40 轮，target_kl = 0.01").into(),
                    with(&|c| {
                        c.epochs = 40;
                        c.target_kl = Some(0.01);
                    }),
                ),
            ],
            Self::Reinforce => vec![
                first("PPO".into()),
                arm(
                    t("REINFORCE + baseline", "REINFORCE + 基线").into(),
                    base.clone().with_rule(UpdateRule::Reinforce),
                ),
            ],
            Self::CriticLr => vec![
                first(format!("critic_lr = {:.0e}", base.critic_lr)),
                arm(
                    format!("critic_lr = {:.0e}", base.critic_lr / 10.0),
                    with(&|c| c.critic_lr /= 10.0),
                ),
            ],
            Self::HiddenDim => vec![
                first(format!("hidden_dim = {}", base.hidden_dim)),
                arm("hidden_dim = 16".into(), with(&|c| c.hidden_dim = 16)),
            ],
            Self::Gamma => vec![
                first(format!("gamma = {}", base.gamma)),
                arm("gamma = 0.9".into(), with(&|c| c.gamma = 0.9)),
                arm("gamma = 0.999".into(), with(&|c| c.gamma = 0.999)),
            ],
            Self::Lmbda => vec![
                first(format!("lmbda = {}", base.lmbda)),
                arm("lmbda = 0.5".into(), with(&|c| c.lmbda = 0.5)),
                arm("lmbda = 1".into(), with(&|c| c.lmbda = 1.0)),
            ],
            Self::Proximal => {
                let delta = PpoConfig::default().kl_delta;
                vec![
                    first(tr!("clip ε = {}", "截断 ε = {}", base.eps)),
                    arm(
                        t("penalty, adaptive β (no clip)", "惩罚，自适应 β（不截断）").into(),
                        with(&|c| {
                            *c = c.clone().with_rule(UpdateRule::Penalty);
                            c.beta_init = 1.0;
                            c.kl_delta = delta;
                        }),
                    ),
                    arm(
                        // short enough for the app's lab panel to show the KL columns
                        tr!(
                            "KL line search δ={delta} (no clip, 1 step, no Adam)",
                            "KL 线搜索 δ={delta}（不截断，一步，无 Adam）"
                        ),
                        with(&|c| {
                            *c = c.clone().with_rule(UpdateRule::LineSearch);
                            c.kl_delta = delta;
                        }),
                    ),
                    arm(
                        t("none (no clip, no penalty)", "都不用（不截断，无惩罚）").into(),
                        base.clone().with_rule(UpdateRule::NoClip),
                    ),
                ]
            }
        }
    }
}

/// Runs every arm of `experiment` (built from `base`) once per seed, `threads` runs at a
/// time. `on_episode(done, total)` counts finished episodes over all runs (from worker
/// threads), for a progress bar.
///
/// # Errors
/// The first [`SeedError`]: an arm's invalid setting or a diverged run.
pub fn run(
    experiment: Experiment,
    base: &PpoConfig,
    seeds: &[u64],
    threads: usize,
    on_episode: impl Fn(usize, usize) + Sync,
) -> Result<LabResult, SeedError> {
    let arms = experiment.arms(base);
    let jobs: Vec<(&PpoConfig, u64)> = arms
        .iter()
        .flat_map(|a| seeds.iter().map(move |&s| (&a.config, s)))
        .collect();
    // Runs are deterministic: a (config, seed) trained by an earlier experiment of this
    // process (the base arm of every experiment, the 40 epochs of two) is not trained again.
    let keys: Vec<String> = jobs.iter().map(|(c, s)| run_key(c, *s)).collect();
    let mut found: Vec<Option<Finished>> = {
        let cache = cache().lock().unwrap_or_else(|p| p.into_inner());
        keys.iter().map(|k| cache.get(k).cloned()).collect()
    };
    let missing: Vec<usize> = (0..jobs.len()).filter(|&i| found[i].is_none()).collect();
    let todo: Vec<(&PpoConfig, u64)> = missing.iter().map(|&i| jobs[i]).collect();
    let total: usize = todo.iter().map(|(c, _)| c.num_episodes).sum();
    let done = std::sync::atomic::AtomicUsize::new(0);
    let sums: Mutex<Vec<Sums>> = Mutex::new(vec![Sums::default(); todo.len()]);
    let runs = train_jobs(&todo, threads, |job, report| {
        if let Ok(mut s) = sums.lock() {
            s[job].add(report);
        }
        let n = done.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1;
        on_episode(n, total);
    })?;
    let sums = sums.into_inner().unwrap_or_else(|p| p.into_inner());
    {
        let mut cache = cache().lock().unwrap_or_else(|p| p.into_inner());
        for ((&i, run), s) in missing.iter().zip(runs).zip(sums) {
            let finished = Finished {
                returns: run.summary.returns,
                stats: s.stats(),
            };
            cache.insert(keys[i].clone(), finished.clone());
            found[i] = Some(finished);
        }
    }
    let finished: Vec<Finished> = found.into_iter().flatten().collect();
    let per_arm = seeds.len();
    let arms = arms
        .into_iter()
        .enumerate()
        .map(|(k, arm)| {
            let range = k * per_arm..(k + 1) * per_arm;
            let returns: Vec<Vec<f64>> = finished[range.clone()]
                .iter()
                .map(|r| r.returns.clone())
                .collect();
            let smoothed: Vec<Vec<f64>> = returns.iter().map(|r| smoothed_returns(r)).collect();
            ArmResult {
                label: arm.label,
                config: arm.config,
                band: Band::of(&smoothed),
                finals: returns.iter().map(|r| mean_last(r, LAST)).collect(),
                updates: finished[range].iter().map(|r| r.stats).collect(),
                returns,
            }
        })
        .collect();
    Ok(LabResult {
        experiment,
        seeds: seeds.to_vec(),
        episodes: base.num_episodes,
        arms,
        paired: std::sync::OnceLock::new(),
    })
}

/// One finished run, as the lab keeps it.
#[derive(Debug, Clone)]
struct Finished {
    returns: Vec<f64>,
    stats: UpdateStats,
}

/// The runs this process has finished, by [`run_key`].
fn cache() -> &'static Mutex<HashMap<String, Finished>> {
    static CACHE: OnceLock<Mutex<HashMap<String, Finished>>> = OnceLock::new();
    CACHE.get_or_init(|| Mutex::new(HashMap::new()))
}

/// A run's identity: every setting and the seed.
fn run_key(config: &PpoConfig, seed: u64) -> String {
    format!("{seed}:{config:?}")
}

#[cfg(test)]
mod tests {
    use super::*;

    type TestResult = Result<(), Box<dyn std::error::Error>>;

    #[test]
    fn every_experiment_changes_one_thing_from_its_base() {
        let base = PpoConfig::default();
        for e in Experiment::ALL {
            let arms = e.arms(&base);
            assert_eq!(arms[0].config, base, "{}", e.name());
            assert!(arms.len() >= 2);
            for a in &arms[1..] {
                assert_ne!(a.config, base, "{}: {}", e.name(), a.label);
                assert!(a.config.validate().is_ok(), "{}", a.label);
            }
            assert_eq!(Experiment::from_name(e.name()), Some(e));
        }
        assert_eq!(Experiment::from_name("clip"), None);
    }

    #[test]
    fn a_short_lab_summarises_every_arm_and_seed() -> TestResult {
        let base = PpoConfig {
            num_episodes: 12,
            ..PpoConfig::default()
        };
        let calls = std::sync::atomic::AtomicUsize::new(0);
        let lab = run(Experiment::Eps, &base, &[0, 1], 2, |_, total| {
            calls.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
            assert_eq!(total, 3 * 2 * 12);
        })?;
        assert_eq!(calls.into_inner(), 72);
        // The same base arm in another experiment comes from the cache: only the other
        // settings train, and the base arm's numbers are the same.
        let calls = std::sync::atomic::AtomicUsize::new(0);
        let epochs = run(Experiment::Epochs, &base, &[0, 1], 2, |_, total| {
            calls.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
            assert_eq!(total, 5 * 2 * 12);
        })?;
        assert_eq!(calls.into_inner(), 120);
        assert_eq!(epochs.arms[0].returns, lab.arms[0].returns);
        assert_eq!(epochs.arms[0].updates, lab.arms[0].updates);
        assert_eq!(lab.arms.len(), 3);
        for arm in &lab.arms {
            assert_eq!(arm.returns.len(), 2);
            assert_eq!(arm.finals.len(), 2);
            assert_eq!(arm.band.mean.len(), 12);
            let u = arm.mean_updates();
            assert!((u.epochs_run - 10.0).abs() < 1e-12);
        }
        // The base arm equals a plain run of each seed.
        let (alone, _) =
            crate::ppo::train(base.clone(), 1, |_| std::ops::ControlFlow::Continue(()))?;
        assert_eq!(lab.arms[0].returns[1], alone.returns);
        // After nine steps on a batch, the last epoch's ratios have moved off 1 in every arm.
        assert!(
            lab.arms
                .iter()
                .all(|a| a.mean_updates().max_ratio_deviation > 0.0)
        );
        Ok(())
    }

    /// The proximal experiment's four arms: what each changes, and the statistics only some
    /// of them have; every arm reports its per-update KL, in the table's extra columns.
    #[test]
    fn the_proximal_arms_each_report_their_per_update_kl() -> TestResult {
        let base = PpoConfig {
            num_episodes: 8,
            ..PpoConfig::default()
        };
        let arms = Experiment::Proximal.arms(&base);
        let rules: Vec<_> = arms.iter().map(|a| a.config.rule()).collect();
        assert_eq!(
            rules,
            [
                Ok(UpdateRule::Clip),
                Ok(UpdateRule::Penalty),
                Ok(UpdateRule::LineSearch),
                Ok(UpdateRule::NoClip),
            ]
        );
        assert_eq!(Experiment::ALL.last(), Some(&Experiment::Proximal));
        assert!(arms[1].label.contains("no clip") && arms[2].label.contains("no Adam"));
        let lab = run(Experiment::Proximal, &base, &[0, 1], 2, |_, _| {})?;
        for arm in &lab.arms {
            let u = arm.mean_updates();
            assert!(
                u.kl_after > 0.0 && u.kl_after_max >= u.kl_after,
                "{}: {u:?}",
                arm.label
            );
            let penalty = arm.config.rule() == Ok(UpdateRule::Penalty);
            let search = arm.config.rule() == Ok(UpdateRule::LineSearch);
            assert_eq!(u.beta_range.is_some(), penalty, "{}", arm.label);
            assert_eq!(u.ls_halvings.is_some(), search, "{}", arm.label);
            if search {
                // every accepted step is inside δ, and a refused search moves nothing
                assert!(u.kl_after_max <= arm.config.kl_delta * 1.001, "{u:?}");
            }
            assert!(arm.kl_summary().starts_with(&arm.label));
        }
        let table = lab.table();
        assert_eq!(table.len(), 5);
        assert!(
            table[0].contains("mean ± std   KL/update   max KL approx_kl"),
            "{}",
            table[0]
        );
        // the app's lab panel (86 columns at 160 × 50) shows the label, the score and the KL
        let kl_end = table[0].find("max KL").map_or(0, |i| i + "max KL".len());
        assert!(
            crate::i18n::width(&table[0][..kl_end]) <= 86,
            "{}",
            table[0]
        );
        let widths: Vec<usize> = table.iter().map(|l| crate::i18n::width(l)).collect();
        assert!(widths.iter().all(|&w| w == widths[0]), "{table:#?}");
        // the other experiments' tables keep their columns
        let eps = run(Experiment::Eps, &base, &[0], 1, |_, _| {})?;
        assert!(eps.table()[0].ends_with("epochs"));
        Ok(())
    }
}
