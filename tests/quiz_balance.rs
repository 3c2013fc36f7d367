//! The quizzes cannot be passed by the look of the choices. A learner who always picks the
//! longest choice, the shortest, the only one with a number in it, or the same letter should
//! do no better than chance. The rule, per language, over the multiple-choice questions
//! whose right letter is fixed:
//!
//! - the right choice is the strictly longest one in at most a third of the questions, and
//!   the strictly shortest one in at most a third (a choice drawn at random would be a
//!   quarter of the time with four choices, a third with three);
//! - it is the only choice with a digit in at most a tenth of them;
//! - no right choice is more than 1.5 times as long as the longest wrong one;
//! - no letter is the right one in more than 40% of them.
//!
//! A question whose right choice the run decides has every choice right in some run, so its
//! longest choice may be at most 1.5 times as long as its shortest.
//!
//! Length is display width (`unicode-width`: a Chinese character is two columns, a combining
//! mark none), what the learner sees; a digit is an ASCII digit. The quizzes are read from
//! `lessons/`, or from the folder named by `QUIZ_BALANCE_LESSONS` (to check another copy of
//! the course, such as an older commit's: `git archive` it into a folder and point there).

use std::path::{Path, PathBuf};

use ppo_tutor::i18n::Lang;
use ppo_tutor::lesson::quiz::{self, Answer, Question, QuestionKind, letter_of};
use unicode_width::UnicodeWidthStr;

type TestResult = Result<(), Box<dyn std::error::Error>>;

/// A multiple-choice question: where it is, its choices, and the index of the right one
/// (`None` when the run decides it).
struct Choice {
    at: String,
    choices: Vec<String>,
    right: Option<usize>,
}

/// How the right choices of a set of questions stand out, and what of the rule they break.
struct Balance {
    /// Questions with a fixed right letter.
    fixed: usize,
    /// Those whose right choice is the strictly longest.
    longest: Vec<String>,
    /// Those whose right choice is the strictly shortest.
    shortest: Vec<String>,
    /// Those whose right choice is the only one with a digit.
    only_digits: Vec<String>,
    /// The largest ratio of a right choice's width to its longest wrong one's, and where.
    max_ratio: (f64, String),
    /// One line per broken clause, naming the questions that break it.
    broken: Vec<String>,
}

const MAX_RATIO: f64 = 1.5;

fn width(s: &str) -> usize {
    UnicodeWidthStr::width(s)
}

fn has_digit(s: &str) -> bool {
    s.chars().any(|c| c.is_ascii_digit())
}

/// Checks `questions` (of one language) against the rule of this file.
fn balance(questions: &[Choice]) -> Balance {
    let mut b = Balance {
        fixed: 0,
        longest: Vec::new(),
        shortest: Vec::new(),
        only_digits: Vec::new(),
        max_ratio: (0.0, String::new()),
        broken: Vec::new(),
    };
    let mut letters = [0usize; 26];
    let mut too_long = Vec::new();
    for q in questions {
        let widths: Vec<usize> = q.choices.iter().map(|c| width(c)).collect();
        let Some(right) = q.right else {
            let (lo, hi) = (
                widths.iter().min().copied().unwrap_or(0),
                widths.iter().max().copied().unwrap_or(0),
            );
            if hi as f64 > MAX_RATIO * lo as f64 {
                b.broken.push(format!(
                    "{}: the run decides its right choice, so every choice is right in some \
                     run, but its choices are {widths:?} columns wide (more than {MAX_RATIO}× \
                     apart)",
                    q.at
                ));
            }
            continue;
        };
        b.fixed += 1;
        letters[right.min(25)] += 1;
        let others: Vec<usize> = (0..widths.len()).filter(|&i| i != right).collect();
        let w = widths[right];
        let longest_other = others.iter().map(|&i| widths[i]).max().unwrap_or(0);
        let shortest_other = others.iter().map(|&i| widths[i]).min().unwrap_or(0);
        let label = format!("{} ({}), {widths:?}", q.at, letter_of(right));
        if w > longest_other {
            b.longest.push(label.clone());
        }
        if w < shortest_other {
            b.shortest.push(label.clone());
        }
        if has_digit(&q.choices[right]) && !others.iter().any(|&i| has_digit(&q.choices[i])) {
            b.only_digits.push(label.clone());
        }
        let ratio = w as f64 / longest_other.max(1) as f64;
        if ratio > b.max_ratio.0 {
            b.max_ratio = (ratio, q.at.clone());
        }
        if ratio > MAX_RATIO {
            too_long.push(format!("{label}: {ratio:.2}×"));
        }
    }
    let n = b.fixed;
    let list = |v: &[String]| v.join("\n    ");
    if b.longest.len() * 3 > n {
        b.broken.push(format!(
            "the right choice is the longest in {} of {n} questions (at most a third):\n    {}",
            b.longest.len(),
            list(&b.longest)
        ));
    }
    if b.shortest.len() * 3 > n {
        b.broken.push(format!(
            "the right choice is the shortest in {} of {n} questions (at most a third):\n    {}",
            b.shortest.len(),
            list(&b.shortest)
        ));
    }
    if b.only_digits.len() * 10 > n {
        b.broken.push(format!(
            "the right choice is the only one with a digit in {} of {n} questions (at most a \
             tenth):\n    {}",
            b.only_digits.len(),
            list(&b.only_digits)
        ));
    }
    if !too_long.is_empty() {
        b.broken.push(format!(
            "right choices more than {MAX_RATIO}× as wide as the longest wrong one:\n    {}",
            list(&too_long)
        ));
    }
    for (i, &count) in letters.iter().enumerate() {
        if count * 5 > n * 2 {
            b.broken.push(format!(
                "{}) is the right letter in {count} of {n} questions (at most 40%)",
                letter_of(i)
            ));
        }
    }
    b
}

fn lessons_dir() -> PathBuf {
    std::env::var_os("QUIZ_BALANCE_LESSONS").map_or_else(
        || Path::new(env!("CARGO_MANIFEST_DIR")).join("lessons"),
        PathBuf::from,
    )
}

/// The multiple-choice questions of every `quiz.toml` under `root`, in `lang` (Chinese from
/// the `quiz.zh.toml` twins), parsed as the course parses them.
fn choice_questions(root: &Path, lang: Lang) -> Result<Vec<Choice>, Box<dyn std::error::Error>> {
    let mut dirs: Vec<PathBuf> = std::fs::read_dir(root)
        .map_err(|e| format!("{}: {e}", root.display()))?
        .filter_map(Result::ok)
        .map(|e| e.path())
        .filter(|p| p.join("quiz.toml").is_file())
        .collect();
    dirs.sort();
    let mut out = Vec::new();
    for dir in dirs {
        let name = dir
            .file_name()
            .and_then(|n| n.to_str())
            .ok_or("a lesson folder's name")?
            .to_string();
        let mut questions: Vec<Question> =
            quiz::parse(&name, &std::fs::read_to_string(dir.join("quiz.toml"))?)?;
        if lang == Lang::Zh {
            let zh = std::fs::read_to_string(dir.join("quiz.zh.toml"))
                .map_err(|e| format!("{name}/quiz.zh.toml: {e}"))?;
            quiz::translate(&name, &mut questions, &zh)?;
        }
        for (i, q) in questions.into_iter().enumerate() {
            if let QuestionKind::Choice {
                choices, answer, ..
            } = q.kind
            {
                out.push(Choice {
                    at: format!("{name} question {}", i + 1),
                    right: match answer {
                        Answer::Letter(a) => Some(a),
                        Answer::Live(_) => None,
                    },
                    choices,
                });
            }
        }
    }
    Ok(out)
}

#[test]
fn no_quiz_can_be_passed_by_the_length_or_the_digits_of_its_choices() -> TestResult {
    let root = lessons_dir();
    let mut problems = Vec::new();
    for lang in [Lang::En, Lang::Zh] {
        let questions = choice_questions(&root, lang)?;
        let b = balance(&questions);
        assert!(
            b.fixed >= 40,
            "{lang:?}: only {} multiple-choice questions found under {}",
            b.fixed,
            root.display()
        );
        let summary = format!(
            "{lang:?}: {} multiple-choice questions; the right choice is the longest in {}, \
             the shortest in {}, the only one with a digit in {}; at most {:.2}× as wide as \
             the longest wrong one ({})",
            b.fixed,
            b.longest.len(),
            b.shortest.len(),
            b.only_digits.len(),
            b.max_ratio.0,
            b.max_ratio.1
        );
        println!("{summary}");
        for broken in b.broken {
            problems.push(format!("{lang:?}: {broken}"));
        }
    }
    assert!(
        problems.is_empty(),
        "the right answer can be told by its look; rewrite the choices so that the wrong ones \
         are as long and as detailed as the right one (lessons/*/quiz.toml and quiz.zh.toml):\n{}",
        problems.join("\n")
    );
    Ok(())
}

/// The rule is not empty: a quiz whose right choice is always the longest, the one with the
/// number, and the same letter breaks every clause, and a balanced one none.
#[test]
fn the_rule_catches_a_quiz_that_gives_its_answers_away() {
    let q = |i: usize, choices: [&str; 4], right: usize| Choice {
        at: format!("q{i}"),
        choices: choices.iter().map(|s| (*s).to_string()).collect(),
        right: Some(right),
    };
    let biased: Vec<Choice> = (0..6)
        .map(|i| {
            q(
                i,
                [
                    "Yes.",
                    "Right: because the ratio is 1 in epoch 1, the gradient is the policy gradient.",
                    "No.",
                    "Never.",
                ],
                1,
            )
        })
        .collect();
    let b = balance(&biased);
    let broken = b.broken.join("\n");
    for clause in [
        "the longest in 6 of 6",
        "the only one with a digit in 6 of 6",
        "more than 1.5× as wide",
        "b) is the right letter in 6 of 6",
    ] {
        assert!(broken.contains(clause), "{clause}: {broken}");
    }
    let shortest = balance(&[q(0, ["Up.", "Down a lot.", "Not at all.", "Sideways."], 0)]);
    assert!(
        shortest
            .broken
            .iter()
            .any(|l| l.contains("the shortest in 1 of 1")),
        "{:?}",
        shortest.broken
    );
    // Right choices of every length and letter, as wide as the wrong ones.
    let even: Vec<Choice> = [0, 1, 2, 3, 0, 3, 2, 0]
        .into_iter()
        .enumerate()
        .map(|(i, right)| {
            q(
                i,
                ["aaaa bbbb", "cccc dddd e", "ffff ggg", "hhhh iiii"],
                right,
            )
        })
        .collect();
    let b = balance(&even);
    assert!(b.broken.is_empty(), "{:?}", b.broken);
    let live = Choice {
        at: "live".into(),
        choices: vec!["up".into(), "down".into(), "nothing at all, ever".into()],
        right: None,
    };
    assert!(
        balance(&[live])
            .broken
            .iter()
            .any(|l| l.contains("the run decides"))
    );
}
