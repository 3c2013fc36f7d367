//! Parsing and validating `lessons/`: front matter, steps, and their references.

use std::collections::BTreeMap;

use serde::Deserialize;

use super::{AgentKind, Exercise, Lesson, Step, VIEWS, anchor};
use crate::i18n::Lang;

/// A lesson file that cannot be used, with where and how to fix it.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum LessonError {
    /// The folder name does not start with a two-digit order, like `07-td-target`.
    #[error("lessons/{dir}: folder name must be NN-slug (two digits, a dash, the id)")]
    BadFolderName {
        /// The folder.
        dir: String,
    },
    /// `lesson.md` is missing from a lesson folder.
    #[error("lessons/{dir}/lesson.md: missing; every lesson folder needs one")]
    MissingFile {
        /// The folder.
        dir: String,
    },
    /// The front matter is absent or not valid TOML.
    #[error("lessons/{dir}/lesson.md: front matter: {reason}")]
    FrontMatter {
        /// The folder.
        dir: String,
        /// What is wrong, from the TOML parser or the format check.
        reason: String,
    },
    /// The body's `## ` headings do not match the `[[steps]]` tables, or a step's
    /// `<details>` block or `<app>`/`<notebook>` passage is malformed.
    #[error("lessons/{dir}/lesson.md: step {index}: {reason}")]
    StepMismatch {
        /// The folder.
        dir: String,
        /// The 1-based step.
        index: usize,
        /// What differs.
        reason: String,
    },
    /// A step names a code anchor or a live value that does not exist.
    #[error("lessons/{dir}/lesson.md: step {index}: unknown {kind} '{name}'")]
    UnknownReference {
        /// The folder.
        dir: String,
        /// The 1-based step.
        index: usize,
        /// `code anchor` or `live value`.
        kind: &'static str,
        /// The name used.
        name: String,
    },
    /// `exercise.toml` is not valid.
    #[error("lessons/{dir}/exercise.toml: {reason}")]
    ExerciseFile {
        /// The folder.
        dir: String,
        /// What is wrong, from the TOML parser.
        reason: String,
    },
    /// A Chinese twin (`lesson.zh.md`, `quiz.zh.toml`, `exercise.zh.toml`) does not match
    /// its English file.
    #[error("lessons/{dir}/{file}: {reason}")]
    Translation {
        /// The folder.
        dir: String,
        /// The translated file.
        file: &'static str,
        /// What differs, and the fix.
        reason: String,
    },
    /// `quiz.toml` is not valid.
    #[error(transparent)]
    Quiz(#[from] super::quiz::QuizError),
    /// Two lessons share an id, or an id does not match its folder.
    #[error("lessons/{dir}: {reason}")]
    BadId {
        /// The folder.
        dir: String,
        /// What is wrong.
        reason: String,
    },
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct FrontMatter {
    id: String,
    title: String,
    #[serde(default)]
    summary: String,
    #[serde(default)]
    env: Option<String>,
    #[serde(default)]
    steps: Vec<StepMeta>,
}

/// What the learner reads of one exercise, as written in `lessons/NN-slug/exercise.toml`
/// (one `[[exercise]]` table per graded function, in the order the lesson presents them).
#[derive(Debug, Clone, PartialEq, Eq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ExerciseText {
    /// The function's name.
    pub name: String,
    /// The idea the exercise tests, in one line (both languages): what the learner must
    /// have understood from the lesson to solve it in a situation the lesson did not show.
    #[serde(default)]
    pub idea: Option<String>,
    /// Hints revealed one by one (`h` in the tutor), from gentle to nearly the answer.
    #[serde(default)]
    pub hints: Vec<String>,
    /// The grader's hint when no known mistake explains a wrong answer.
    pub fallback: String,
    /// The grader's hint for each typical mistake, by the mistake's id.
    #[serde(default)]
    pub mistakes: BTreeMap<String, String>,
    /// Further hints the exercise's grader gives in situations of its own, by key.
    #[serde(default)]
    pub other: BTreeMap<String, String>,
    /// The code anchors (often nested in a bigger one) that compute what the exercise asks:
    /// every face hides them until the learner has passed it ([`super::reveal`]). Declared
    /// in `exercise.toml` only, `[]` when no code shown in the course computes it; the
    /// Chinese twin takes it from there.
    #[serde(default)]
    pub reveals: Option<Vec<String>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct ExerciseFile {
    exercise: Vec<ExerciseText>,
}

/// Parses the `exercise.toml` of lesson folder `dir`.
///
/// # Errors
/// [`LessonError::ExerciseFile`] with the TOML parser's message.
pub fn parse_exercises(dir: &str, text: &str) -> Result<Vec<ExerciseText>, LessonError> {
    toml::from_str::<ExerciseFile>(text)
        .map(|f| f.exercise)
        .map_err(|e| LessonError::ExerciseFile {
            dir: dir.into(),
            reason: e.message().to_string(),
        })
}

/// Checks that every exercise of an English `exercise.toml` declares what it `reveals`, and
/// that each name there is a code anchor.
///
/// # Errors
/// [`LessonError::ExerciseFile`] naming the exercise and the fix.
pub fn check_reveals(dir: &str, texts: &[ExerciseText]) -> Result<(), LessonError> {
    let bad = |reason: String| {
        Err(LessonError::ExerciseFile {
            dir: dir.into(),
            reason,
        })
    };
    for t in texts {
        if t.idea.as_deref().is_none_or(|i| i.trim().is_empty()) {
            return bad(format!(
                "exercise `{}` has no `idea`: state in one line the idea of the lesson it \
                 tests (`idea = \"...\"`)",
                t.name
            ));
        }
        let Some(reveals) = &t.reveals else {
            return bad(format!(
                "exercise `{}` has no `reveals`: list the code anchors that compute what it \
                 asks (wrap the lines in a nested `// ANCHOR:` if they sit in a bigger one), \
                 or write `reveals = []` when no code the course shows computes it",
                t.name
            ));
        };
        if let Some(unknown) = reveals.iter().find(|a| anchor::find(a).is_none()) {
            return bad(format!(
                "exercise `{}` reveals '{unknown}', which is not a code anchor (mark it in the \
                 engine's source with `// ANCHOR: {unknown}` and `// ANCHOR_END: {unknown}`)",
                t.name
            ));
        }
    }
    Ok(())
}

/// Every embedded `exercise.toml`, as `(lesson folder, exercises)` in course order, in the
/// current language ([`Lang::current`]).
///
/// # Errors
/// The first file that fails to parse.
pub fn embedded_exercises() -> Result<Vec<(String, Vec<ExerciseText>)>, LessonError> {
    embedded_exercises_in(Lang::current())
}

/// [`embedded_exercises`] in `lang`: for Chinese each `exercise.zh.toml`, which must name
/// the same exercises, hints and mistakes as its English file.
///
/// # Errors
/// The first file that fails to parse, or a Chinese file that does not match.
pub fn embedded_exercises_in(lang: Lang) -> Result<Vec<(String, Vec<ExerciseText>)>, LessonError> {
    let mut out: Vec<(String, Vec<ExerciseText>)> = Vec::new();
    for d in super::files::root().dirs() {
        let name = d.path().file_name().and_then(|n| n.to_str()).unwrap_or("");
        let file = |f: &str| d.get_file(d.path().join(f)).and_then(|f| f.contents_utf8());
        if let Some(text) = file("exercise.toml") {
            let english = parse_exercises(name, text)?;
            check_reveals(name, &english)?;
            let texts = match (lang, file("exercise.zh.toml")) {
                (Lang::Zh, Some(zh)) => {
                    let mut chinese = parse_exercises(name, zh)
                        .map_err(|e| translation(name, "exercise.zh.toml", e.to_string()))?;
                    same_exercises(name, &english, &chinese)?;
                    for (z, e) in chinese.iter_mut().zip(&english) {
                        z.reveals.clone_from(&e.reveals);
                    }
                    chinese
                }
                _ => english,
            };
            out.push((name.to_string(), texts));
        }
    }
    out.sort_by(|a, b| a.0.cmp(&b.0));
    Ok(out)
}

fn translation(dir: &str, file: &'static str, reason: String) -> LessonError {
    LessonError::Translation {
        dir: dir.into(),
        file,
        reason,
    }
}

/// Checks that `zh` translates `en` item for item: the same functions in the same order,
/// as many hints, the same mistake and situation keys.
fn same_exercises(dir: &str, en: &[ExerciseText], zh: &[ExerciseText]) -> Result<(), LessonError> {
    let bad = |reason: String| Err(translation(dir, "exercise.zh.toml", reason));
    let names = |t: &[ExerciseText]| t.iter().map(|e| e.name.clone()).collect::<Vec<_>>();
    if names(en) != names(zh) {
        return bad(format!(
            "exercises {:?}, but exercise.toml has {:?}; translate the same ones in the same order",
            names(zh),
            names(en)
        ));
    }
    for (e, z) in en.iter().zip(zh) {
        if z.reveals.is_some() {
            return bad(format!(
                "{}: `reveals` is structure, declared in exercise.toml only; remove it here",
                e.name
            ));
        }
        if z.idea.as_deref().is_none_or(|i| i.trim().is_empty()) {
            return bad(format!("{}: no `idea`; translate exercise.toml's", e.name));
        }
        if e.hints.len() != z.hints.len() {
            return bad(format!(
                "{}: {} hints, but exercise.toml has {}",
                e.name,
                z.hints.len(),
                e.hints.len()
            ));
        }
        for (what, a, b) in [
            ("mistakes", &e.mistakes, &z.mistakes),
            ("other", &e.other, &z.other),
        ] {
            let ka: Vec<&String> = a.keys().collect();
            let kb: Vec<&String> = b.keys().collect();
            if ka != kb {
                return bad(format!(
                    "{}: [exercise.{what}] has keys {kb:?}, but exercise.toml has {ka:?}",
                    e.name
                ));
            }
        }
    }
    Ok(())
}

/// The lesson's exercise as the tutor presents it: every function of `texts` in order,
/// their hints one after another.
fn lesson_exercise(texts: &[ExerciseText]) -> Option<Exercise> {
    let (first, rest) = texts.split_first()?;
    Some(Exercise {
        name: first.name.clone(),
        also: rest.iter().map(|t| t.name.clone()).collect(),
        hints: texts.iter().flat_map(|t| t.hints.iter().cloned()).collect(),
        ideas: texts
            .iter()
            .map(|t| t.idea.clone().unwrap_or_default())
            .collect(),
    })
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct StepMeta {
    title: String,
    #[serde(default)]
    python: String,
    #[serde(default)]
    code: String,
    #[serde(default)]
    show: Vec<String>,
    #[serde(default)]
    lab: String,
    #[serde(default)]
    predict: String,
}

/// The whole course, in order.
#[derive(Debug, Clone, PartialEq)]
pub struct Course {
    /// The lessons, sorted by their `NN-` prefix.
    pub lessons: Vec<Lesson>,
}

impl Course {
    /// The course embedded in the binary at build time, in the current language
    /// ([`Lang::current`]).
    ///
    /// # Errors
    /// The first lesson file that fails to parse (the content test catches this first).
    pub fn embedded() -> Result<Self, LessonError> {
        Self::embedded_in(Lang::current())
    }

    /// The embedded course in `lang`. The structure (steps, code anchors, live values,
    /// exercises, quiz answers) always comes from the English files; Chinese takes its prose
    /// from each folder's `lesson.zh.md`, `quiz.zh.toml` and `exercise.zh.toml`, which must
    /// match them step for step. A lesson without a Chinese twin stays English.
    ///
    /// # Errors
    /// The first lesson file that fails to parse, or a translation that does not match.
    pub fn embedded_in(lang: Lang) -> Result<Self, LessonError> {
        let mut folders: Vec<(&str, Option<&str>)> = super::files::root()
            .dirs()
            .map(|d| {
                let name = d.path().file_name().and_then(|n| n.to_str()).unwrap_or("");
                let text = d
                    .get_file(d.path().join("lesson.md"))
                    .and_then(|f| f.contents_utf8());
                (name, text)
            })
            .collect();
        folders.sort_by(|a, b| a.0.cmp(b.0));
        let lessons = folders
            .into_iter()
            .map(|(dir, text)| {
                let text = text.ok_or_else(|| LessonError::MissingFile { dir: dir.into() })?;
                let mut lesson = parse_lesson(dir, text)?;
                if lang == Lang::Zh
                    && let Some(zh) = super::files::embedded_file(&format!("{dir}/lesson.zh.md"))
                {
                    translate_lesson(&mut lesson, dir, zh)?;
                }
                Ok(lesson)
            })
            .collect::<Result<Vec<_>, LessonError>>()?;
        let mut lessons = lessons;
        for (dir, texts) in embedded_exercises_in(lang)? {
            if let Some(lesson) = lessons
                .iter_mut()
                .find(|l| format!("{:02}-{}", l.order, l.id) == dir)
            {
                lesson.exercise = lesson_exercise(&texts);
            }
        }
        for lesson in &mut lessons {
            lesson.quiz = super::quiz::questions_in(&lesson.id, lang)?;
        }
        let course = Self { lessons };
        course.check_ids()?;
        Ok(course)
    }

    fn check_ids(&self) -> Result<(), LessonError> {
        let mut seen = std::collections::BTreeSet::new();
        for l in &self.lessons {
            if !seen.insert(&l.id) {
                return Err(LessonError::BadId {
                    dir: format!("{:02}-{}", l.order, l.id),
                    reason: format!("id '{}' is used by two lessons", l.id),
                });
            }
        }
        Ok(())
    }

    /// The lesson with `id`.
    #[must_use]
    pub fn get(&self, id: &str) -> Option<&Lesson> {
        self.lessons.iter().find(|l| l.id == id)
    }

    /// The position of lesson `id` in the course.
    #[must_use]
    pub fn index_of(&self, id: &str) -> Option<usize> {
        self.lessons.iter().position(|l| l.id == id)
    }

    /// Total number of steps over all lessons.
    #[must_use]
    pub fn total_steps(&self) -> usize {
        self.lessons.iter().map(|l| l.steps.len()).sum()
    }
}

/// Splits `+++\n<toml>\n+++\n<body>`.
fn split_front_matter(text: &str) -> Option<(&str, &str)> {
    let rest = text.strip_prefix("+++")?.trim_start_matches('\r');
    let rest = rest.strip_prefix('\n')?;
    let end = rest.find("\n+++")?;
    let body = rest[end + 4..].trim_start_matches(['\r', '\n']);
    Some((&rest[..end], body))
}

/// Splits a markdown body into `(heading, text)` pairs at `## ` headings.
fn split_steps(body: &str) -> Vec<(String, String)> {
    let mut steps: Vec<(String, String)> = Vec::new();
    for line in body.lines() {
        if let Some(title) = line.strip_prefix("## ") {
            steps.push((title.trim().to_string(), String::new()));
        } else if let Some((_, text)) = steps.last_mut() {
            text.push_str(line);
            text.push('\n');
        }
    }
    for (_, text) in &mut steps {
        *text = text.trim().to_string();
    }
    steps
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct TranslatedFront {
    title: String,
    #[serde(default)]
    summary: String,
    #[serde(default)]
    steps: Vec<TranslatedStep>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct TranslatedStep {
    title: String,
}

/// Replaces `lesson`'s prose (title, summary, step titles and bodies) with that of its
/// translation `text` (a `lesson.zh.md`: front matter with `title`, `summary` and one
/// `[[steps]]` table per step holding only its `title`, then one `## ` section per step).
///
/// # Errors
/// [`LessonError::Translation`] when the steps, their `<app>`/`<notebook>` passages or
/// `<details>` blocks do not match the English lesson's.
pub fn translate_lesson(lesson: &mut Lesson, dir: &str, text: &str) -> Result<(), LessonError> {
    const FILE: &str = "lesson.zh.md";
    let bad = |reason: String| translation(dir, FILE, reason);
    let (front, body) = split_front_matter(text).ok_or_else(|| {
        bad("the file must start with a '+++' line and close it with another".into())
    })?;
    let meta: TranslatedFront = toml::from_str(front).map_err(|e| {
        bad(format!(
            "front matter: {} (a translation holds only title, summary and [[steps]] titles)",
            e.message()
        ))
    })?;
    let bodies = split_steps(body);
    if meta.steps.len() != lesson.steps.len() || bodies.len() != lesson.steps.len() {
        return Err(bad(format!(
            "{} [[steps]] tables and {} '## ' headings, but lesson.md has {} steps",
            meta.steps.len(),
            bodies.len(),
            lesson.steps.len()
        )));
    }
    let mut translated = Vec::with_capacity(bodies.len());
    for (i, ((step, m), (heading, zh))) in
        lesson.steps.iter().zip(meta.steps).zip(bodies).enumerate()
    {
        let n = i + 1;
        if m.title != heading {
            return Err(bad(format!(
                "step {n}: title '{}' but heading '## {heading}'",
                m.title
            )));
        }
        super::face::check(&zh).map_err(|e| bad(format!("step {n}: {e}")))?;
        for face in super::face::Face::ALL {
            let (en_text, zh_text) = (
                super::face::text(&step.body, face),
                super::face::text(&zh, face),
            );
            let en = super::details::parts(&en_text).map_err(|e| bad(format!("step {n}: {e}")))?;
            let ours =
                super::details::parts(&zh_text).map_err(|e| bad(format!("step {n}: {e}")))?;
            if en.len() != ours.len() {
                return Err(bad(format!(
                    "step {n} ({face:?}): {} parts (text and <details> blocks), but lesson.md has {}",
                    ours.len(),
                    en.len()
                )));
            }
        }
        for tag in ["<app>", "<notebook>", super::AFTER_THE_RUN] {
            if step.body.matches(tag).count() != zh.matches(tag).count() {
                return Err(bad(format!(
                    "step {n}: {tag} appears {} times, but {} times in lesson.md",
                    zh.matches(tag).count(),
                    step.body.matches(tag).count()
                )));
            }
        }
        translated.push((m.title, zh));
    }
    lesson.title = meta.title;
    lesson.summary = meta.summary;
    for (step, (title, body)) in lesson.steps.iter_mut().zip(translated) {
        step.title = title;
        step.body = body;
    }
    Ok(())
}

/// Parses one `lesson.md` from folder `dir` and checks its references.
///
/// # Errors
/// A [`LessonError`] naming the folder, the step and the fix.
pub fn parse_lesson(dir: &str, text: &str) -> Result<Lesson, LessonError> {
    let (order, slug) = dir
        .split_once('-')
        .and_then(|(n, slug)| Some((n.parse::<u32>().ok().filter(|_| n.len() == 2)?, slug)))
        .ok_or_else(|| LessonError::BadFolderName { dir: dir.into() })?;
    let (front, body) = split_front_matter(text).ok_or_else(|| LessonError::FrontMatter {
        dir: dir.into(),
        reason: "the file must start with a '+++' line and close it with another".into(),
    })?;
    let meta: FrontMatter = toml::from_str(front).map_err(|e| LessonError::FrontMatter {
        dir: dir.into(),
        reason: e.message().to_string(),
    })?;
    if meta.id != slug {
        return Err(LessonError::BadId {
            dir: dir.into(),
            reason: format!("id '{}' must equal the folder's slug '{slug}'", meta.id),
        });
    }
    let env = match meta.env.as_deref() {
        None => AgentKind::default(),
        Some(name) => AgentKind::from_name(name).ok_or_else(|| LessonError::FrontMatter {
            dir: dir.into(),
            reason: format!(
                "env = '{name}' is not an environment; write \"CartPole-v1\" or \"Pendulum-v1\""
            ),
        })?,
    };
    let bodies = split_steps(body);
    if bodies.len() != meta.steps.len() {
        return Err(LessonError::StepMismatch {
            dir: dir.into(),
            index: bodies.len().min(meta.steps.len()) + 1,
            reason: format!(
                "{} [[steps]] tables but {} '## ' headings",
                meta.steps.len(),
                bodies.len()
            ),
        });
    }
    let steps = meta
        .steps
        .into_iter()
        .zip(bodies)
        .enumerate()
        .map(|(i, (m, (heading, body)))| check_step(dir, i + 1, env, m, &heading, body))
        .collect::<Result<Vec<_>, _>>()?;
    Ok(Lesson {
        id: meta.id,
        title: meta.title,
        summary: meta.summary,
        order,
        steps,
        exercise: None,
        quiz: Vec::new(),
        env,
    })
}

fn check_step(
    dir: &str,
    index: usize,
    env: AgentKind,
    meta: StepMeta,
    heading: &str,
    body: String,
) -> Result<Step, LessonError> {
    if meta.title != heading {
        return Err(LessonError::StepMismatch {
            dir: dir.into(),
            index,
            reason: format!("title '{}' but heading '## {heading}'", meta.title),
        });
    }
    let step_error = |reason: String| LessonError::StepMismatch {
        dir: dir.into(),
        index,
        reason,
    };
    super::face::check(&body).map_err(|e| step_error(e.to_string()))?;
    for face in super::face::Face::ALL {
        super::details::parts(&super::face::text(&body, face))
            .map_err(|e| step_error(e.to_string()))?;
    }
    if !meta.code.is_empty() && anchor::find(&meta.code).is_none() {
        return Err(LessonError::UnknownReference {
            dir: dir.into(),
            index,
            kind: "code anchor",
            name: meta.code,
        });
    }
    if let Some(bad) = meta
        .show
        .iter()
        .find(|n| !VIEWS.contains(&n.as_str()) && !super::live::is_known(n))
    {
        return Err(LessonError::UnknownReference {
            dir: dir.into(),
            index,
            kind: "live value",
            name: bad.clone(),
        });
    }
    if let Some(bad) = meta.show.iter().find(|n| {
        (super::live::is_known(n) && !super::live::runs_on(n, env))
            || super::View::from_name(n)
                .and_then(super::View::agent)
                .is_some_and(|e| e != env)
    }) {
        return Err(LessonError::StepMismatch {
            dir: dir.into(),
            index,
            reason: format!(
                "'{bad}' has no value in a {} run; show it in a lesson of the other environment",
                env.as_str()
            ),
        });
    }
    let lab = if meta.lab.is_empty() {
        None
    } else {
        Some(
            crate::ppo::lab::Experiment::from_name(&meta.lab).ok_or_else(|| {
                LessonError::UnknownReference {
                    dir: dir.into(),
                    index,
                    kind: "lab experiment",
                    name: meta.lab.clone(),
                }
            })?,
        )
    };
    if lab.is_some() != meta.show.iter().any(|s| s == "lab") {
        return Err(LessonError::StepMismatch {
            dir: dir.into(),
            index,
            reason: "a step with `lab = \"NAME\"` must show \"lab\", and only such a step may"
                .into(),
        });
    }
    let predict = if meta.predict.is_empty() {
        None
    } else {
        Some(
            crate::ppo::lab::Outcome::from_name(&meta.predict).ok_or_else(|| {
                LessonError::UnknownReference {
                    dir: dir.into(),
                    index,
                    kind: "prediction (ends_highest or ends_lowest)",
                    name: meta.predict.clone(),
                }
            })?,
        )
    };
    if predict.is_some() && lab.is_none() {
        return Err(LessonError::StepMismatch {
            dir: dir.into(),
            index,
            reason: "`predict` asks about the step's experiment: add `lab = \"NAME\"` or remove it"
                .into(),
        });
    }
    let marked = body.lines().any(|l| l.trim_end() == super::AFTER_THE_RUN);
    if predict.is_some() != marked {
        return Err(LessonError::StepMismatch {
            dir: dir.into(),
            index,
            reason: format!(
                "a step with `predict` must hide what the run found after a line `{}`, and only such a step may have one",
                super::AFTER_THE_RUN
            ),
        });
    }
    Ok(Step {
        title: meta.title,
        python: meta.python.trim().to_string(),
        code: meta.code,
        show: meta.show,
        body,
        lab,
        predict,
    })
}
