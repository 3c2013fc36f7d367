//! Check-your-understanding quizzes: the questions at the end of each lesson, kept as data
//! in `lessons/NN-slug/quiz.toml`, and how an answer is graded.
//!
//! A question is either **multiple choice** (one right letter, an explanation for every
//! choice) or **predict the number**: the learner commits to a number before the live value
//! is revealed, and is right within the question's tolerance. The live value is a
//! [`Measure`] of the running agent's [`Snapshot`], named in the question's `predict` field
//! and listed in [`MEASURES`].
//!
//! The terminal app asks them after a lesson's last step; a notebook cell grades one in
//! place with [`answer`] or [`predict`]:
//!
//! ```
//! use ppo_tutor::lesson::quiz;
//!
//! let verdict = quiz::answer("ratio", 1, '?');
//! assert!(!verdict.answered);
//! let lesson = quiz::questions("ratio")?;
//! assert!(lesson.len() >= 3);
//! # Ok::<(), ppo_tutor::lesson::quiz::QuizError>(())
//! ```

use serde::Deserialize;

use super::Snapshot;
use super::files::embedded_file;
use crate::i18n::{Lang, t};
use crate::tr;

/// One question.
#[derive(Debug, Clone, PartialEq)]
pub struct Question {
    /// The question, as the learner reads it.
    pub prompt: String,
    /// How it is answered.
    pub kind: QuestionKind,
}

/// How a question is answered and graded.
#[derive(Debug, Clone, PartialEq)]
pub enum QuestionKind {
    /// Pick one of 3 or 4 choices.
    Choice {
        /// The choices, shown as a), b), c), d).
        choices: Vec<String>,
        /// The index of the right choice.
        answer: usize,
        /// Why each choice is right or wrong, one per choice.
        explain: Vec<String>,
    },
    /// Predict a live value before it is shown.
    Predict {
        /// The measure whose live value is the answer.
        measure: &'static Measure,
        /// How far from the live value an answer may be and still be right.
        tolerance: f64,
        /// Why the value is what it is.
        explain: String,
    },
}

/// A number a prediction is graded against, measured on the running agent.
#[derive(Debug)]
pub struct Measure {
    /// The name a question's `predict` field uses.
    pub name: &'static str,
    /// What it is, in words (shown with the revealed value).
    pub about: &'static str,
    /// [`Measure::about`] in Chinese.
    pub about_zh: &'static str,
    /// Its value in a snapshot, `None` before anything computed it.
    pub value: fn(&Snapshot) -> Option<f64>,
}

impl Measure {
    /// What it is, in words, in the current language.
    #[must_use]
    pub fn describe(&self) -> &'static str {
        t(self.about, self.about_zh)
    }
}

impl PartialEq for Measure {
    fn eq(&self, other: &Self) -> bool {
        self.name == other.name
    }
}

/// Every measure a prediction can be graded against.
pub static MEASURES: &[Measure] = &[
    Measure {
        name: "batch_rows",
        about: "transitions in the latest episode's batch",
        about_zh: "最新回合批次中的状态转移数",
        value: |s| match &s.continuous {
            Some(c) => Some(c.rewards.len() as f64),
            None => Some(s.trace.as_ref()?.rewards.len() as f64),
        },
    },
    Measure {
        name: "episode_return",
        about: "the latest episode's return",
        about_zh: "最新回合的回报",
        value: |s| s.returns.last().copied(),
    },
    Measure {
        name: "dones_count",
        about: "rows of the latest batch with done = 1",
        about_zh: "最新批次中 done = 1 的行数",
        value: |s| {
            let dones = match &s.continuous {
                Some(c) => &c.dones,
                None => &s.trace.as_ref()?.dones,
            };
            Some(dones.iter().filter(|d| **d).count() as f64)
        },
    },
    Measure {
        name: "obs_dim",
        about: "numbers in one CartPole observation",
        about_zh: "一个 CartPole 观测中的数的个数",
        value: |s| s.trace.as_ref()?.states.first().map(|o| o.len() as f64),
    },
    Measure {
        name: "actor_parameters",
        about: "trainable parameters of the actor",
        about_zh: "策略网络的可训练参数个数",
        value: |s| parameters(s, "actor."),
    },
    Measure {
        name: "critic_parameters",
        about: "trainable parameters of the critic",
        about_zh: "价值网络的可训练参数个数",
        value: |s| parameters(s, "critic."),
    },
    Measure {
        name: "probs_row_sum",
        about: "π(left|s_0) + π(right|s_0) for the batch's first row",
        about_zh: "批次第一行的 π(left|s_0) + π(right|s_0)",
        value: |s| s.probs.first().map(|p| f64::from(p[0]) + f64::from(p[1])),
    },
    Measure {
        name: "entropy_max",
        about: "the largest entropy of a policy over CartPole's actions, in nats",
        about_zh: "CartPole 动作上策略熵的最大值（单位 nat）",
        value: |s| s.probs.first().map(|p| (p.len() as f64).ln()),
    },
    Measure {
        name: "td_target_last",
        about: "the TD target of the batch's last row",
        about_zh: "批次最后一行的 TD 目标",
        value: |s| s.trace.as_ref()?.td_target.last().map(|&v| f64::from(v)),
    },
    Measure {
        name: "gamma_lambda",
        about: "γ·λ of the run",
        about_zh: "本次运行的 γ·λ",
        value: |s| Some(s.gamma * lambda(s)?),
    },
    Measure {
        name: "discount_50",
        about: "γ^50, the weight of a reward 50 steps ahead",
        about_zh: "γ^50，即 50 步之后一个奖励的权重",
        value: |s| Some(s.gamma.powi(50)),
    },
    Measure {
        name: "horizon_gamma",
        about: "1/(1 − γ)",
        about_zh: "1/(1 − γ)",
        value: |s| Some(1.0 / (1.0 - s.gamma)),
    },
    Measure {
        name: "horizon_gae",
        about: "1/(1 − γλ)",
        about_zh: "1/(1 − γλ)",
        value: |s| Some(1.0 / (1.0 - s.gamma * lambda(s)?)),
    },
    Measure {
        name: "advantage_last_minus_td_delta_last",
        about: "Â_T − δ_T for the batch's last row",
        about_zh: "批次最后一行的 Â_T − δ_T",
        value: |s| {
            let t = s.trace.as_ref()?;
            Some(f64::from(*t.advantage.last()?) - f64::from(*t.td_delta.last()?))
        },
    },
    Measure {
        name: "ratio_epoch1_min",
        about: "the smallest ratio in epoch 1",
        about_zh: "第 1 轮中最小的比率",
        value: |s| first_ratios(s).map(min),
    },
    Measure {
        name: "ratio_epoch1_max",
        about: "the largest ratio in epoch 1",
        about_zh: "第 1 轮中最大的比率",
        value: |s| first_ratios(s).map(max),
    },
    Measure {
        name: "clipped_rows_epoch1",
        about: "rows with the clip active in epoch 1",
        about_zh: "第 1 轮中截断生效的行数",
        value: |s| first_epoch(s, |e| e.clipped.iter().filter(|c| **c).count() as f64),
    },
    Measure {
        name: "clip_frac_epoch1",
        about: "the clip fraction of epoch 1",
        about_zh: "第 1 轮的截断比例（clip fraction）",
        value: |s| first_epoch(s, |e| f64::from(e.clip_fraction)),
    },
    Measure {
        name: "approx_kl_epoch1",
        about: "approx_kl in epoch 1",
        about_zh: "第 1 轮的 approx_kl",
        value: |s| first_epoch(s, |e| f64::from(e.approx_kl)),
    },
    Measure {
        name: "actor_loss_epoch1_plus_mean_advantage",
        about: "the actor loss of epoch 1 plus the batch's mean advantage",
        about_zh: "第 1 轮的策略网络损失加上批次的平均优势值",
        value: |s| {
            let t = s.trace.as_ref()?;
            let mean =
                t.advantage.iter().map(|&a| f64::from(a)).sum::<f64>() / t.advantage.len() as f64;
            Some(f64::from(t.epochs.first()?.actor_loss) + mean)
        },
    },
    Measure {
        name: "epochs_run",
        about: "epochs the latest update ran",
        about_zh: "最新一次更新运行的轮数",
        value: |s| Some(s.trace.as_ref()?.epochs_run() as f64),
    },
    Measure {
        name: "grad_max_diff",
        about: "the largest difference between the two policy gradients at θ_old",
        about_zh: "θ_old 处两种策略梯度之间的最大差值",
        value: |s| {
            let g = s.gradients.as_ref()?;
            Some(f64::from(g.max_abs_diff()))
        },
    },
    Measure {
        name: "adv_norm_mean",
        about: "the mean of the normalised advantages",
        about_zh: "归一化后优势值的均值",
        value: |s| normalised(s).map(|(mean, _)| mean),
    },
    Measure {
        name: "adv_norm_std",
        about: "the unbiased standard deviation of the normalised advantages",
        about_zh: "归一化后优势值的无偏标准差",
        value: |s| normalised(s).map(|(_, std)| std),
    },
    Measure {
        name: "moving_average_window",
        about: "the window of the seed's moving average",
        about_zh: "原教程代码中移动平均的窗口大小",
        value: |_| Some(super::live::session::MOVING_AVERAGE_WINDOW as f64),
    },
];

/// The measure called `name`.
#[must_use]
pub fn measure(name: &str) -> Option<&'static Measure> {
    MEASURES.iter().find(|m| m.name == name)
}

fn lambda(s: &Snapshot) -> Option<f64> {
    s.hyper
        .iter()
        .find(|(name, _)| name == "lmbda")
        .and_then(|(_, v)| v.parse().ok())
}

fn parameters(s: &Snapshot, prefix: &str) -> Option<f64> {
    let n: usize = s
        .weights
        .iter()
        .filter(|(name, _)| name.starts_with(prefix))
        .map(|(_, w)| w.data.len())
        .sum();
    (n > 0).then_some(n as f64)
}

fn first_epoch(s: &Snapshot, f: impl Fn(&crate::ppo::EpochTrace) -> f64) -> Option<f64> {
    s.trace.as_ref()?.epochs.first().map(f)
}

/// The ratios of the latest update's first epoch, in either run.
fn first_ratios(s: &Snapshot) -> Option<&[f32]> {
    match &s.continuous {
        Some(c) => c.epochs.first().map(|e| e.ratio.as_slice()),
        None => s.trace.as_ref()?.epochs.first().map(|e| e.ratio.as_slice()),
    }
}

fn max(xs: &[f32]) -> f64 {
    xs.iter()
        .map(|&x| f64::from(x))
        .fold(f64::NEG_INFINITY, f64::max)
}

fn min(xs: &[f32]) -> f64 {
    xs.iter()
        .map(|&x| f64::from(x))
        .fold(f64::INFINITY, f64::min)
}

/// Mean and unbiased std of CleanRL's normalised advantages of the latest batch.
fn normalised(s: &Snapshot) -> Option<(f64, f64)> {
    let adv = &s.trace.as_ref()?.advantage;
    if adv.len() < 2 {
        return None;
    }
    let out = crate::ppo::advantage::normalize_advantage(adv);
    let n = out.len() as f64;
    let mean = out.iter().map(|&x| f64::from(x)).sum::<f64>() / n;
    let var = out
        .iter()
        .map(|&x| (f64::from(x) - mean).powi(2))
        .sum::<f64>()
        / (n - 1.0);
    Some((mean, var.sqrt()))
}

/// A quiz file that cannot be used, naming the file, the question and the fix.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum QuizError {
    /// No lesson has this id.
    #[error("{}", crate::tr!(
        "no lesson '{0}': `ppo-tutor lessons` lists the ids (for example 'gae')",
        "没有 '{0}' 这一课：`ppo-tutor lessons` 会列出各课的 id（例如 'gae'）",
        .0
    ))]
    UnknownLesson(String),
    /// The lesson has no question with this number.
    #[error("{}", crate::tr!(
        "lesson '{lesson}' has questions 1 to {count}; there is no question {number}",
        "'{lesson}' 这一课的题号是 1 到 {count}，没有第 {number} 题",
        lesson = lesson, count = count, number = number
    ))]
    NoSuchQuestion {
        /// The lesson id.
        lesson: String,
        /// The number asked for.
        number: usize,
        /// How many there are.
        count: usize,
    },
    /// The file is not valid.
    #[error("lessons/{dir}/quiz.toml: {reason}")]
    File {
        /// The lesson folder.
        dir: String,
        /// What is wrong and how to fix it.
        reason: String,
    },
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct QuizFile {
    question: Vec<RawQuestion>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawQuestion {
    prompt: String,
    #[serde(default)]
    choices: Vec<String>,
    #[serde(default)]
    answer: Option<String>,
    #[serde(default)]
    predict: Option<String>,
    #[serde(default)]
    tolerance: Option<f64>,
    explain: Explain,
}

#[derive(Debug, Deserialize)]
#[serde(untagged)]
enum Explain {
    One(String),
    PerChoice(Vec<String>),
}

/// Parses the `quiz.toml` of lesson folder `dir`.
///
/// # Errors
/// [`QuizError::File`] naming the question and what to fix.
pub fn parse(dir: &str, text: &str) -> Result<Vec<Question>, QuizError> {
    let bad = |reason: String| QuizError::File {
        dir: dir.to_string(),
        reason,
    };
    let file: QuizFile = toml::from_str(text).map_err(|e| bad(e.message().to_string()))?;
    file.question
        .into_iter()
        .enumerate()
        .map(|(i, q)| {
            let n = i + 1;
            let kind = match (q.predict, q.answer, q.explain) {
                (Some(name), None, Explain::One(explain)) if q.choices.is_empty() => {
                    let measure = measure(&name).ok_or_else(|| {
                        bad(format!(
                            "question {n}: predict = '{name}' is not a measure; use one of: {}",
                            MEASURES.iter().map(|m| m.name).collect::<Vec<_>>().join(", ")
                        ))
                    })?;
                    let tolerance = q.tolerance.filter(|t| t.is_finite() && *t >= 0.0);
                    let tolerance = tolerance.ok_or_else(|| {
                        bad(format!(
                            "question {n}: a predict question needs tolerance = a number ≥ 0"
                        ))
                    })?;
                    QuestionKind::Predict {
                        measure,
                        tolerance,
                        explain,
                    }
                }
                (None, Some(letter), Explain::PerChoice(explain)) => {
                    if !(3..=4).contains(&q.choices.len()) {
                        return Err(bad(format!("question {n}: give 3 or 4 choices")));
                    }
                    if explain.len() != q.choices.len() {
                        return Err(bad(format!(
                            "question {n}: explain needs one text per choice ({}), not {}",
                            q.choices.len(),
                            explain.len()
                        )));
                    }
                    let answer = letter_index(&letter)
                        .filter(|&a| a < q.choices.len())
                        .ok_or_else(|| {
                            bad(format!(
                                "question {n}: answer = '{letter}' must be the letter of a choice (a to {})",
                                letter_of(q.choices.len() - 1)
                            ))
                        })?;
                    QuestionKind::Choice {
                        choices: q.choices,
                        answer,
                        explain,
                    }
                }
                _ => {
                    return Err(bad(format!(
                        "question {n}: write either choices + answer + explain = [one per choice], \
                         or predict + tolerance + explain = \"...\""
                    )));
                }
            };
            Ok(Question {
                prompt: q.prompt,
                kind,
            })
        })
        .collect()
}

/// The questions of lesson `id` (e.g. `gae`), from the embedded `quiz.toml`; none when the
/// lesson has no quiz file.
///
/// # Errors
/// [`QuizError::UnknownLesson`], or [`QuizError::File`] for a malformed file.
pub fn questions(id: &str) -> Result<Vec<Question>, QuizError> {
    questions_in(id, Lang::current())
}

/// [`questions`] in `lang`: for Chinese, the prompts, choices and explanations of
/// `quiz.zh.toml`, with the answers, measures and tolerances of `quiz.toml`.
///
/// # Errors
/// As [`questions`], or [`QuizError::File`] when `quiz.zh.toml` does not match `quiz.toml`.
pub fn questions_in(id: &str, lang: Lang) -> Result<Vec<Question>, QuizError> {
    let dir = super::files::lesson_dirs()
        .into_iter()
        .find(|d| d.split_once('-').is_some_and(|(_, slug)| slug == id))
        .ok_or_else(|| QuizError::UnknownLesson(id.to_string()))?;
    let Some(text) = embedded_file(&format!("{dir}/quiz.toml")) else {
        return Ok(Vec::new());
    };
    let mut questions = parse(&dir, text)?;
    if lang == Lang::Zh
        && let Some(zh) = embedded_file(&format!("{dir}/quiz.zh.toml"))
    {
        translate(&dir, &mut questions, zh)?;
    }
    Ok(questions)
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct TranslatedFile {
    question: Vec<TranslatedQuestion>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct TranslatedQuestion {
    prompt: String,
    #[serde(default)]
    choices: Vec<String>,
    explain: Explain,
}

/// Replaces the prose of `questions` with that of `text` (a `quiz.zh.toml`: per question
/// only `prompt`, `choices` and `explain`, as many as in `quiz.toml`).
///
/// # Errors
/// [`QuizError::File`] naming the question that does not match.
pub fn translate(dir: &str, questions: &mut [Question], text: &str) -> Result<(), QuizError> {
    let bad = |reason: String| QuizError::File {
        dir: dir.to_string(),
        reason: format!("quiz.zh.toml: {reason}"),
    };
    let file: TranslatedFile = toml::from_str(text).map_err(|e| {
        bad(format!(
            "{} (a translation holds only prompt, choices and explain)",
            e.message()
        ))
    })?;
    if file.question.len() != questions.len() {
        return Err(bad(format!(
            "{} questions, but quiz.toml has {}",
            file.question.len(),
            questions.len()
        )));
    }
    for (i, (q, t)) in questions.iter_mut().zip(file.question).enumerate() {
        let n = i + 1;
        match (&mut q.kind, t.explain) {
            (
                QuestionKind::Choice {
                    choices, explain, ..
                },
                Explain::PerChoice(zh_explain),
            ) if t.choices.len() == choices.len() && zh_explain.len() == explain.len() => {
                *choices = t.choices;
                *explain = zh_explain;
            }
            (QuestionKind::Predict { explain, .. }, Explain::One(zh_explain))
                if t.choices.is_empty() =>
            {
                *explain = zh_explain;
            }
            _ => {
                return Err(bad(format!(
                    "question {n}: give the same kind of question as quiz.toml, with as many \
                     choices and explanations"
                )));
            }
        }
        q.prompt = t.prompt;
    }
    Ok(())
}

/// `0` for `a`, `1` for `b`, ... (either case).
#[must_use]
pub fn letter_index(letter: &str) -> Option<usize> {
    let mut chars = letter.trim().chars();
    let c = chars.next()?.to_ascii_lowercase();
    (chars.next().is_none() && c.is_ascii_lowercase()).then(|| usize::from(c as u8 - b'a'))
}

/// `a` for `0`, `b` for `1`, ...
#[must_use]
pub fn letter_of(index: usize) -> char {
    char::from(b'a' + u8::try_from(index.min(25)).unwrap_or(25))
}

/// The verdict on one answer, with what to read next.
#[derive(Debug, Clone, PartialEq)]
pub struct Verdict {
    /// Whether the learner gave an answer at all (a placeholder is not one).
    pub answered: bool,
    /// Whether it is right.
    pub right: bool,
    /// The live value, for a prediction (revealed only once answered).
    pub live: Option<f64>,
    /// What to show: the verdict line, then the explanation.
    pub text: String,
}

impl std::fmt::Display for Verdict {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.text)
    }
}

impl Verdict {
    fn unanswered(text: String) -> Self {
        Self {
            answered: false,
            right: false,
            live: None,
            text,
        }
    }

    /// Shows the verdict as a notebook cell's output (the evcxr kernel calls this).
    pub fn evcxr_display(&self) {
        for (mime, content) in crate::notebook::Rich::rich(self) {
            println!("EVCXR_BEGIN_CONTENT {mime}\n{content}\nEVCXR_END_CONTENT");
        }
    }
}

impl crate::notebook::Rich for Verdict {
    fn rich(&self) -> Vec<(&'static str, String)> {
        vec![("text/plain", self.text.clone())]
    }
}

impl Question {
    /// The question with its choices, as plain text (`a) ...` per line).
    #[must_use]
    pub fn text(&self) -> String {
        let mut out = self.prompt.clone();
        if let QuestionKind::Choice { choices, .. } = &self.kind {
            for (i, c) in choices.iter().enumerate() {
                out.push_str(&format!("\n  {}) {c}", letter_of(i)));
            }
        }
        out
    }

    /// Grades the choice `letter` (`'a'`..); a letter that is not a choice is no answer.
    #[must_use]
    pub fn choose(&self, letter: char) -> Verdict {
        let QuestionKind::Choice {
            choices,
            answer,
            explain,
        } = &self.kind
        else {
            return Verdict::unanswered(
                t(
                    "This question asks for a number: answer it with quiz::predict.",
                    "这道题要一个数：请用 quiz::predict 作答。",
                )
                .into(),
            );
        };
        let last = letter_of(choices.len() - 1);
        let Some(index) = letter_index(&letter.to_string()).filter(|&i| i < choices.len()) else {
            return Verdict::unanswered(tr!(
                "Not answered yet: put your choice (a to {last}) in place of '{letter}' and run it again.",
                "还没有作答：把 '{letter}' 换成你的选择（a 到 {last}），再运行一次。"
            ));
        };
        let right = index == *answer;
        let mut text = if right {
            tr!(
                "✓ Right: {}) {}",
                "✓ 答对了：{}) {}",
                letter_of(index),
                choices[index]
            )
        } else {
            tr!(
                "✗ Not {}). The answer is {}) {}",
                "✗ 不是 {}）。正确答案是 {}) {}",
                letter_of(index),
                letter_of(*answer),
                choices[*answer]
            )
        };
        text.push_str(&format!("\n\n{}) {}", letter_of(index), explain[index]));
        if !right {
            text.push_str(&format!("\n{}) {}", letter_of(*answer), explain[*answer]));
        }
        Verdict {
            answered: true,
            right,
            live: None,
            text,
        }
    }

    /// Grades the prediction `value` against the live value in `snapshot`.
    #[must_use]
    pub fn predict(&self, value: f64, snapshot: &Snapshot) -> Verdict {
        let QuestionKind::Predict {
            measure,
            tolerance,
            explain,
        } = &self.kind
        else {
            return Verdict::unanswered(
                t(
                    "This is a multiple-choice question: answer it with quiz::answer.",
                    "这是一道选择题：请用 quiz::answer 作答。",
                )
                .into(),
            );
        };
        if !value.is_finite() {
            return Verdict::unanswered(
                t(
                    "Not answered yet: predict a finite number.",
                    "还没有作答：请预测一个有限的数。",
                )
                .into(),
            );
        }
        let Some(live) = (measure.value)(snapshot) else {
            return Verdict::unanswered(tr!(
                "The live value ({}) does not exist yet: train at least one episode first.",
                "实时数值（{}）还不存在：请先至少训练一个回合。",
                measure.describe()
            ));
        };
        let right = (value - live).abs() <= *tolerance;
        let mark = if right {
            t("✓ Right", "✓ 答对了")
        } else {
            t("✗ Not quite", "✗ 不太对")
        };
        let text = tr!(
            "{mark}: you said {value}, the live value is {} ({}; within ±{tolerance} counts).\n\n{explain}",
            "{mark}：你的预测是 {value}，实时数值是 {}（{}；相差不超过 ±{tolerance} 即算对）。\n\n{explain}",
            show(live),
            measure.describe()
        );
        Verdict {
            answered: true,
            right,
            live: Some(live),
            text,
        }
    }
}

/// A live value for reading: integers as integers, others to 6 significant digits.
fn show(x: f64) -> String {
    if x.fract() == 0.0 && x.abs() < 1e9 {
        format!("{x:.0}")
    } else {
        format!("{x:.6}")
    }
}

fn question(lesson: &str, number: usize) -> Result<Question, QuizError> {
    let all = questions(lesson)?;
    let count = all.len();
    all.into_iter()
        .nth(number.wrapping_sub(1))
        .ok_or_else(|| QuizError::NoSuchQuestion {
            lesson: lesson.to_string(),
            number,
            count,
        })
}

/// Grades choice `letter` for question `number` (from 1) of lesson `lesson`, as a notebook
/// cell does: `quiz::answer("gae", 2, 'b')`. A placeholder such as `'?'` is no answer yet.
#[must_use]
pub fn answer(lesson: &str, number: usize, letter: char) -> Verdict {
    numbered(
        number,
        match question(lesson, number) {
            Ok(q) => q.choose(letter),
            Err(e) => Verdict::unanswered(e.to_string()),
        },
    )
}

/// `verdict` with the question's number in front, so that answers read apart in a notebook.
fn numbered(number: usize, mut verdict: Verdict) -> Verdict {
    verdict.text = tr!("Question {number}: {}", "第 {number} 题：{}", verdict.text);
    verdict
}

/// Grades the prediction `value` (a number as text, e.g. `"0.93"`; `"?"` is no answer yet)
/// for question `number` of lesson `lesson` against the live value in `snapshot`:
/// `quiz::predict("ratio", 3, "1.0", &snap)`.
#[must_use]
pub fn predict(lesson: &str, number: usize, value: &str, snapshot: &Snapshot) -> Verdict {
    let q = match question(lesson, number) {
        Ok(q) => q,
        Err(e) => return numbered(number, Verdict::unanswered(e.to_string())),
    };
    numbered(
        number,
        match value.trim().parse::<f64>() {
            Ok(v) => q.predict(v, snapshot),
            Err(_) => Verdict::unanswered(tr!(
                "Not answered yet: put your prediction (a number, like \"0.5\") in place of \"{value}\" and run it again.",
                "还没有作答：把 \"{value}\" 换成你的预测（一个数，例如 \"0.5\"），再运行一次。"
            )),
        },
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    const TWO: &str = r#"
[[question]]
prompt = "Which?"
choices = ["one", "two", "three"]
answer = "b"
explain = ["no 1", "yes", "no 3"]

[[question]]
prompt = "How many?"
predict = "batch_rows"
tolerance = 0.5
explain = "Because."
"#;

    #[test]
    fn parses_both_kinds_and_grades_them() -> Result<(), QuizError> {
        let qs = parse("99-x", TWO)?;
        assert_eq!(qs.len(), 2);
        let right = qs[0].choose('B');
        assert!(right.answered && right.right, "{right}");
        let wrong = qs[0].choose('c');
        assert!(wrong.answered && !wrong.right);
        assert!(
            wrong.text.contains("no 3") && wrong.text.contains("yes"),
            "{wrong}"
        );
        assert!(!qs[0].choose('?').answered);
        assert!(!qs[0].choose('d').answered, "d is not a choice of three");
        let mut snap = Snapshot::default();
        assert!(!qs[1].predict(3.0, &snap).answered, "nothing trained yet");
        snap.trace = Some(crate::ppo::UpdateTrace {
            rewards: vec![1.0; 12],
            ..crate::ppo::UpdateTrace::default()
        });
        let close = qs[1].predict(12.4, &snap);
        assert!(close.right && close.live == Some(12.0), "{close}");
        assert!(!qs[1].predict(13.0, &snap).right);
        Ok(())
    }

    #[test]
    fn bad_files_name_the_question_and_the_fix() {
        let cases = [
            (
                TWO.replace("answer = \"b\"", "answer = \"e\""),
                "answer = 'e'",
            ),
            (TWO.replace("\"no 3\"", ""), "one text per choice"),
            (TWO.replace("batch_rows", "batch_rowz"), "not a measure"),
            (TWO.replace("tolerance = 0.5\n", ""), "tolerance"),
            (
                TWO.replace("prompt = \"Which?\"", "prompt = \"Which?\"\nhint = 1"),
                "unknown field",
            ),
        ];
        for (text, want) in cases {
            let e = parse("99-x", &text)
                .err()
                .map(|e| e.to_string())
                .unwrap_or_default();
            assert!(
                e.contains("lessons/99-x/quiz.toml") && e.contains(want),
                "{e}"
            );
        }
    }

    #[test]
    fn unknown_lessons_and_numbers_are_explained() {
        assert!(answer("nope", 1, 'a').text.contains("ppo-tutor lessons"));
        assert!(
            answer("ratio", 99, 'a')
                .text
                .contains("there is no question 99")
        );
        assert!(
            answer("ratio", 0, 'a')
                .text
                .contains("there is no question 0")
        );
    }
}
