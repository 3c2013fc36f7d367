//! A prediction the learner commits to before a lab experiment runs, graded against the run
//! that follows.
//!
//! A lab step of a lesson names what to predict (`predict = "ends_highest"` in its front
//! matter): which of the experiment's settings will end highest, or lowest, by the mean over
//! seeds of each seed's last-50 mean. The choices are the experiment's own arms, lettered
//! a, b, c, ... in their order. The grade says what the run found and, because a five-seed
//! ordering may be luck, whether the run separates the learner's choice from the setting it
//! found: the paired difference of the two over the run's seeds and its bootstrap interval.
//!
//! ```
//! use ppo_engine::ppo::lab::{Experiment, Outcome};
//! use ppo_engine::ppo::PpoConfig;
//!
//! let choices = Outcome::EndsHighest.choices(Experiment::Eps, &PpoConfig::default());
//! assert_eq!(choices.len(), 3);
//! assert!(choices[0].starts_with("a) "));
//! assert_eq!(Outcome::from_name("ends_lowest"), Some(Outcome::EndsLowest));
//! ```

use serde::Serialize;

use super::super::config::PpoConfig;
use super::{Experiment, LAST, LabResult, paired_words_or_none};
use crate::i18n::t;
use crate::stats::Bootstrap;
use crate::tr;

/// What the learner predicts about an experiment's settings.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Outcome {
    /// Which setting ends with the highest mean of its seeds' last-50 means.
    EndsHighest,
    /// Which setting ends with the lowest.
    EndsLowest,
}

/// A graded prediction: whether the run agreed, and the lines that say why.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct PredictionGrade {
    /// The learner's choice is the setting the run found.
    pub right: bool,
    /// What was predicted, what the run found, and whether the run separates the two.
    pub lines: Vec<String>,
}

impl Outcome {
    /// Every outcome, as lessons name them.
    pub const ALL: [Self; 2] = [Self::EndsHighest, Self::EndsLowest];

    /// The name a lesson's front matter uses (`ends_highest`).
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            Self::EndsHighest => "ends_highest",
            Self::EndsLowest => "ends_lowest",
        }
    }

    /// The outcome a lesson names, `None` for an unknown name.
    #[must_use]
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|o| o.name() == name)
    }

    /// The question, in the current language, for a run over `seeds` seeds.
    #[must_use]
    pub fn question(self, seeds: usize) -> String {
        match self {
            Self::EndsHighest => tr!(
                "Predict before the run: which setting will end highest, by the mean over its {seeds} seeds of each seed's last {LAST} returns?",
                "运行之前先预测：按 {seeds} 个随机种子各自最后 {LAST} 个回报的均值再取平均，哪种设置最终最高？"
            ),
            Self::EndsLowest => tr!(
                "Predict before the run: which setting will end lowest, by the mean over its {seeds} seeds of each seed's last {LAST} returns?",
                "运行之前先预测：按 {seeds} 个随机种子各自最后 {LAST} 个回报的均值再取平均，哪种设置最终最低？"
            ),
        }
    }

    /// The choices: the experiment's settings from `base`, lettered in their order
    /// (`a) ε = 0.2 (seed)`).
    #[must_use]
    pub fn choices(self, experiment: Experiment, base: &PpoConfig) -> Vec<String> {
        experiment
            .arms(base)
            .iter()
            .zip(letters())
            .map(|(arm, letter)| format!("{letter}) {}", arm.label))
            .collect()
    }

    /// The index of the setting the run found (the first of equals), `None` for a result
    /// without arms.
    #[must_use]
    pub fn answer(self, result: &LabResult) -> Option<usize> {
        self.best(&final_means(result))
    }

    /// The index of the best of `means` on the outcome's side (the first of equals).
    fn best(self, means: &[f64]) -> Option<usize> {
        let better = |a: f64, b: f64| match self {
            Self::EndsHighest => a > b,
            Self::EndsLowest => a < b,
        };
        let mut best: Option<usize> = None;
        for (i, &m) in means.iter().enumerate() {
            if best.is_none_or(|b| better(m, means[b])) {
                best = Some(i);
            }
        }
        best
    }

    /// Grades `choice` (an arm's index) against `result`; `None` when `choice` names no arm
    /// of the result.
    #[must_use]
    pub fn grade(self, choice: usize, result: &LabResult) -> Option<PredictionGrade> {
        let means = final_means(result);
        let found = self.best(&means)?;
        let chosen = result.arms.get(choice)?;
        let top = &result.arms[found];
        let n = result.seeds.len();
        let right = choice == found;
        let kind = match self {
            Self::EndsHighest => t("highest", "最高"),
            Self::EndsLowest => t("lowest", "最低"),
        };
        let mut lines = vec![if right {
            tr!(
                "Your prediction: {}. Right on these {n} seeds: it ended {kind} ({:.1}).",
                "你的预测：{}。在这 {n} 个随机种子上猜对了：它最终{kind}（{:.1}）。",
                chosen.label,
                means[choice]
            )
        } else {
            tr!(
                "Your prediction: {} ({:.1}). Not on these {n} seeds: {} ended {kind} ({:.1}).",
                "你的预测：{}（{:.1}）。在这 {n} 个随机种子上没猜对：{} 最终{kind}（{:.1}）。",
                chosen.label,
                means[choice],
                top.label,
                means[found]
            )
        }];
        // Whether the run separates the choice from the setting it found: if right, the
        // runner-up against it; if not, the choice against it.
        let other = if right {
            self.runner_up(&means, found)
        } else {
            Some(choice)
        };
        if let Some(other) = other {
            let o = &result.arms[other];
            let paired = Bootstrap::default().paired(&o.finals, &top.finals).ok();
            let words = paired_words_or_none(paired.as_ref(), n);
            lines.push(tr!(
                "Paired seed by seed, {} − {}: {words}.",
                "逐个随机种子配对，{} − {}：{words}。",
                o.label,
                top.label
            ));
            lines.push(
                tr!(
                    "An ordering counts only where that interval excludes zero; {n} seeds often cannot tell two settings apart.",
                    "只有区间不含 0 时，这个先后才算数；{n} 个随机种子常常分不出两种设置的高下。"
                ),
            );
        }
        Some(PredictionGrade { right, lines })
    }

    /// The setting closest to `found` on the outcome's side: the second highest (lowest).
    fn runner_up(self, means: &[f64], found: usize) -> Option<usize> {
        let mut rest: Vec<(usize, f64)> = means
            .iter()
            .copied()
            .enumerate()
            .filter(|(i, _)| *i != found)
            .collect();
        rest.sort_by(|a, b| a.1.total_cmp(&b.1));
        match self {
            Self::EndsHighest => rest.last().map(|r| r.0),
            Self::EndsLowest => rest.first().map(|r| r.0),
        }
    }
}

/// Each arm's mean over seeds of its seeds' last-50 means, in the arms' order.
fn final_means(result: &LabResult) -> Vec<f64> {
    result.arms.iter().map(|a| a.final_mean_std().0).collect()
}

/// The choice letters, `a` on.
pub fn letters() -> impl Iterator<Item = char> {
    ('a'..='z').take(26)
}

/// The arm index a choice letter names (`'b'` → 1), `None` for a letter past `arms`.
#[must_use]
pub fn choice_index(letter: char, arms: usize) -> Option<usize> {
    letters().position(|l| l == letter).filter(|&i| i < arms)
}

#[cfg(test)]
mod tests {
    use super::super::{ArmResult, UpdateStats};
    use super::*;
    use crate::ppo::seeds::Band;

    fn arm(label: &str, finals: &[f64]) -> ArmResult {
        ArmResult {
            label: label.into(),
            config: PpoConfig::default(),
            returns: vec![Vec::new(); finals.len()],
            band: Band::default(),
            finals: finals.to_vec(),
            updates: vec![UpdateStats::default(); finals.len()],
        }
    }

    fn result(arms: Vec<ArmResult>) -> LabResult {
        LabResult {
            experiment: Experiment::Eps,
            seeds: (0..arms[0].finals.len() as u64).collect(),
            episodes: 500,
            arms,
            paired: std::sync::OnceLock::new(),
        }
    }

    #[test]
    fn the_answer_is_the_arm_with_the_highest_or_lowest_mean() {
        let r = result(vec![
            arm("a", &[400.0, 410.0, 420.0]),
            arm("b", &[480.0, 490.0, 500.0]),
            arm("c", &[100.0, 120.0, 90.0]),
        ]);
        assert_eq!(Outcome::EndsHighest.answer(&r), Some(1));
        assert_eq!(Outcome::EndsLowest.answer(&r), Some(2));
    }

    #[test]
    fn a_right_guess_is_checked_against_the_runner_up_and_a_wrong_one_against_the_answer()
    -> Result<(), &'static str> {
        let r = result(vec![
            arm("seed", &[400.0, 410.0, 420.0, 430.0, 440.0]),
            arm("wide", &[480.0, 490.0, 500.0, 495.0, 485.0]),
            arm("narrow", &[401.0, 409.0, 421.0, 431.0, 439.0]),
        ]);
        let right = Outcome::EndsHighest.grade(1, &r).ok_or("no arm")?;
        assert!(right.right);
        // Runner-up is "narrow" (420.2 > 420.0); its difference from "wide" is clearly negative.
        assert!(
            right.lines[1].contains("narrow − wide"),
            "{:?}",
            right.lines
        );
        assert!(right.lines[1].contains("lower"), "{:?}", right.lines);
        let wrong = Outcome::EndsHighest.grade(2, &r).ok_or("no arm")?;
        assert!(!wrong.right);
        assert!(
            wrong.lines[0].contains("wide ended highest"),
            "{:?}",
            wrong.lines
        );
        assert!(
            wrong.lines[1].contains("narrow − wide"),
            "{:?}",
            wrong.lines
        );
        // "seed" and "narrow" differ by a point either way: not separated.
        let close = Outcome::EndsLowest.grade(2, &r).ok_or("no arm")?;
        assert!(!close.right);
        assert!(
            close.lines[1].contains("no difference shown at 5 seeds"),
            "{:?}",
            close.lines
        );
        assert_eq!(Outcome::EndsHighest.grade(3, &r), None);
        Ok(())
    }

    #[test]
    fn a_notebook_without_a_letter_is_told_which_experiment_waits_for_one() {
        let r = result(vec![arm("a", &[1.0, 2.0]), arm("b", &[3.0, 4.0])]);
        let lines = r.prediction_lines("ends_highest", ' ');
        assert_eq!(lines.len(), 1, "{lines:?}");
        assert!(lines[0].contains("`eps` experiment"), "{lines:?}");
        assert!(lines[0].contains("from a to b"), "{lines:?}");
        let graded = r.prediction_lines("ends_highest", 'b');
        assert!(graded[0].contains("Right on these 2 seeds"), "{graded:?}");
        assert!(r.prediction_lines("ends_first", 'a')[0].contains("ends_first"));
    }

    #[test]
    fn letters_name_the_arms_in_order() {
        assert_eq!(choice_index('a', 3), Some(0));
        assert_eq!(choice_index('c', 3), Some(2));
        assert_eq!(choice_index('d', 3), None);
        let choices = Outcome::EndsLowest.choices(Experiment::Epochs, &PpoConfig::default());
        assert_eq!(
            choices.len(),
            Experiment::Epochs.arms(&PpoConfig::default()).len()
        );
        assert!(choices[1].starts_with("b) "));
        // The app types a prediction with a–f: no experiment has more settings.
        for e in Experiment::ALL {
            assert!(e.arms(&PpoConfig::default()).len() <= 6, "{}", e.name());
        }
    }
}
