//! No answer on screen before the learner earns it: the code each exercise gives away, and
//! what a face may show of an anchor before the exercise is passed.
//!
//! Every `[[exercise]]` of a lesson's `exercise.toml` declares `reveals`, the code anchors
//! that compute what it asks. Where the answer is a few lines of a bigger anchor, those
//! lines are wrapped in a nested anchor and only it is declared, so the rest stays
//! visible. A region declared by several exercises (the candle ratio is part of both
//! `importance_weighted_mean`'s and `ppo_losses`'s answers) opens once all of them are passed.
//!
//! A face that shows a step's anchor asks [`listing`] with what the learner has passed.
//! Each declared region not yet open becomes one placeholder row that names the exercises
//! to solve and their lessons ([`note`]); an anchor that is itself declared becomes that
//! row alone. The terminal app and `ppo-tutor show` pass the progress file's
//! `exercises_done`; a notebook, which has no progress, passes the exercises of earlier
//! lessons, and shows the crate's version after its own exercise's grading cells.
//!
//! ```
//! use ppo_engine::lesson::reveal::{Row, listing};
//!
//! // Nothing passed: GAE's backward loop is a note, the function's signature stays.
//! let before = listing("compute_advantage", &|_| false).ok_or("no anchor")?;
//! assert!(before.text().contains("pub fn compute_advantage"));
//! assert!(!before.text().contains("coef * adv"));
//! assert!(before.rows.iter().any(
//!     |r| matches!(r, Row::Hidden { by, .. } if by[0].exercise == "compute_advantage")
//! ));
//! // Once `compute_advantage` is passed, the whole anchor shows.
//! let after = listing("compute_advantage", &|e| e == "compute_advantage").ok_or("no anchor")?;
//! assert!(after.text().contains("adv = coef * adv + delta"));
//! assert_eq!(after.shown[0].exercise, "compute_advantage");
//! # Ok::<(), &str>(())
//! ```

use std::collections::BTreeMap;
use std::sync::OnceLock;

use super::anchor::{self, Line};
use crate::i18n::Lang;

/// An exercise, as a gate on the code it gives away.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Gate {
    /// The exercise's name (`compute_advantage`).
    pub exercise: String,
    /// The order of the lesson that asks it (8).
    pub lesson: u32,
    /// That lesson's folder (`08-gae`).
    pub folder: String,
}

/// Every exercise of the course with what it reveals, in course order (from the embedded
/// English `exercise.toml` files; empty if they do not load, which the content check
/// reports).
#[must_use]
pub fn exercises() -> &'static [(Gate, Vec<String>)] {
    static ALL: OnceLock<Vec<(Gate, Vec<String>)>> = OnceLock::new();
    ALL.get_or_init(|| {
        let files = super::loader::embedded_exercises_in(Lang::En).unwrap_or_default();
        let mut all = Vec::new();
        for (folder, texts) in files {
            let lesson = folder
                .split_once('-')
                .and_then(|(n, _)| n.parse().ok())
                .unwrap_or(0);
            for t in texts {
                let gate = Gate {
                    exercise: t.name,
                    lesson,
                    folder: folder.clone(),
                };
                all.push((gate, t.reveals.unwrap_or_default()));
            }
        }
        all
    })
}

/// The exercises that declare anchor `name`, in course order (none for code no exercise
/// asks for).
#[must_use]
pub fn gates_of(name: &str) -> Vec<&'static Gate> {
    static BY_ANCHOR: OnceLock<BTreeMap<String, Vec<&'static Gate>>> = OnceLock::new();
    BY_ANCHOR
        .get_or_init(|| {
            let mut map: BTreeMap<String, Vec<&'static Gate>> = BTreeMap::new();
            for (gate, reveals) in exercises() {
                for anchor in reveals {
                    map.entry(anchor.clone()).or_default().push(gate);
                }
            }
            map
        })
        .get(name)
        .cloned()
        .unwrap_or_default()
}

/// The gate of exercise `name`, if the course has it.
#[must_use]
pub fn gate(name: &str) -> Option<&'static Gate> {
    exercises()
        .iter()
        .map(|(g, _)| g)
        .find(|g| g.exercise == name)
}

/// One row of a [`Listing`].
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Row {
    /// A line of the crate's code.
    Code(String),
    /// A region left out until `by` are passed, at `indent` spaces.
    Hidden {
        /// Spaces before the region's code.
        indent: usize,
        /// The exercises still to pass, in course order.
        by: Vec<Gate>,
    },
}

/// An anchor's code as a face may show it now.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Listing {
    /// The crate whose source it is (`ppo-rl`, the RL core, or `ppo-engine`).
    pub krate: &'static str,
    /// The file, relative to that crate's `src/`.
    pub path: String,
    /// The rows, de-indented.
    pub rows: Vec<Row>,
    /// The passed exercises whose declared code it shows, in course order.
    pub shown: Vec<Gate>,
}

impl Listing {
    /// The code with each hidden region as one comment line, `// ` and its [`note`].
    #[must_use]
    pub fn text(&self) -> String {
        self.rows
            .iter()
            .map(|r| match r {
                Row::Code(code) => code.clone(),
                Row::Hidden { indent, by } => format!("{}// {}", " ".repeat(*indent), note(by)),
            })
            .collect::<Vec<_>>()
            .join("\n")
    }

    /// The exercises still to pass for the whole anchor to show, in course order.
    #[must_use]
    pub fn hidden(&self) -> Vec<&Gate> {
        let mut out: Vec<&Gate> = Vec::new();
        for r in &self.rows {
            if let Row::Hidden { by, .. } = r {
                for g in by {
                    if !out.contains(&g) {
                        out.push(g);
                    }
                }
            }
        }
        out.sort_by_key(|g| g.lesson);
        out
    }
}

/// Anchor `name` as a face may show it to a learner who has passed the exercises for which
/// `passed` holds: each declared region with an exercise still to pass is a
/// [`Row::Hidden`]. `None` for an unknown anchor.
#[must_use]
pub fn listing(name: &str, passed: &dyn Fn(&str) -> bool) -> Option<Listing> {
    let open = |region: &str| gates_of(region).iter().all(|g| passed(&g.exercise));
    let pending = |region: &str| -> Vec<Gate> {
        gates_of(region)
            .into_iter()
            .filter(|g| !passed(&g.exercise))
            .cloned()
            .collect()
    };
    if !open(name) {
        let (path, _) = anchor::find(name)?;
        return Some(Listing {
            krate: anchor::crate_of(name)?,
            path,
            rows: vec![Row::Hidden {
                indent: 0,
                by: pending(name),
            }],
            shown: Vec::new(),
        });
    }
    let (path, lines) = anchor::find_masked(name, &|inner| !open(inner))?;
    let mut masked = Vec::new();
    let rows = lines
        .into_iter()
        .map(|l| match l {
            Line::Code(code) => Row::Code(code),
            Line::Masked { name, indent } => {
                let by = pending(&name);
                masked.push(name);
                Row::Hidden { indent, by }
            }
        })
        .collect();
    // Inside a hidden region nothing shows, open or not.
    let inside_masked: Vec<String> = masked.iter().flat_map(|m| anchor::nested(m)).collect();
    let mut shown: Vec<Gate> = Vec::new();
    for region in std::iter::once(name.to_string()).chain(anchor::nested(name)) {
        if masked.contains(&region) || inside_masked.contains(&region) {
            continue;
        }
        for g in gates_of(&region) {
            if !shown.contains(g) {
                shown.push(g.clone());
            }
        }
    }
    shown.sort_by_key(|g| g.lesson);
    Some(Listing {
        krate: anchor::crate_of(name)?,
        path,
        rows,
        shown,
    })
}

/// What a hidden region says instead of its code: "solve exercise `compute_advantage` (lesson 8)
/// to see the crate's version", in the current language.
#[must_use]
pub fn note(by: &[Gate]) -> String {
    let names: Vec<String> = by
        .iter()
        .map(|g| {
            let (name, n) = (&g.exercise, g.lesson);
            crate::tr!("`{name}` (lesson {n})", "`{name}`（第 {n} 课）")
        })
        .collect();
    let list = names.join(crate::i18n::t(" and ", "和 "));
    if by.len() > 1 {
        crate::tr!(
            "solve exercises {list} to see the crate's version",
            "完成练习 {list}后即可看到本库的写法"
        )
    } else {
        crate::tr!(
            "solve exercise {list} to see the crate's version",
            "完成练习 {list}后即可看到本库的写法"
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_region_declared_twice_opens_when_both_are_passed() -> Result<(), &'static str> {
        let gates: Vec<&str> = gates_of("ratio")
            .iter()
            .map(|g| g.exercise.as_str())
            .collect();
        assert_eq!(gates, ["importance_weighted_mean", "ppo_losses"]);
        let first = "importance_weighted_mean";
        let only_first = listing("ratio", &|e| e == first).ok_or("no anchor")?;
        assert_eq!(only_first.rows.len(), 1);
        assert_eq!(only_first.hidden()[0].exercise, "ppo_losses");
        let both = listing("ratio", &|e| e == first || e == "ppo_losses").ok_or("no anchor")?;
        assert!(both.text().contains(".exp()"), "{}", both.text());
        assert!(both.hidden().is_empty());
        Ok(())
    }

    #[test]
    fn a_hidden_region_keeps_its_indentation_and_the_rest_shows() -> Result<(), &'static str> {
        let l = listing("take_action", &|_| false).ok_or("no anchor")?;
        let text = l.text();
        assert!(text.contains("pub fn take_action"), "{text}");
        assert!(!text.contains("cumulative"), "{text}");
        assert!(
            text.contains("    // solve exercise `sample_action` (lesson 3)"),
            "{text}"
        );
        assert!(l.shown.is_empty());
        // Code no exercise asks for is never hidden.
        let free = listing("physics", &|_| false).ok_or("no anchor")?;
        assert!(free.hidden().is_empty() && free.shown.is_empty());
        Ok(())
    }

    #[test]
    fn the_note_names_every_exercise_still_to_pass() {
        let _en = Lang::En.scoped();
        let gate = |exercise: &str, lesson| Gate {
            exercise: exercise.into(),
            lesson,
            folder: String::new(),
        };
        assert_eq!(
            note(&[gate("n_step_target", 7)]),
            "solve exercise `n_step_target` (lesson 7) to see the crate's version"
        );
        assert_eq!(
            note(&[gate("zero_gradient_rows", 10), gate("ppo_losses", 11)]),
            "solve exercises `zero_gradient_rows` (lesson 10) and `ppo_losses` (lesson 11) to \
             see the crate's version"
        );
        let _zh = Lang::Zh.scoped();
        assert_eq!(
            note(&[gate("n_step_target", 7)]),
            "完成练习 `n_step_target`（第 7 课）后即可看到本库的写法"
        );
    }
}
