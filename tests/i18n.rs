//! The Chinese course: one structure, two languages.
//!
//! Every lesson, quiz, exercise text and starter has a Chinese twin that matches its English
//! file item for item (the loader checks the structure; these tests check completeness and
//! what a loader cannot: untranslated paragraphs, lost numbers and code, the glossary).

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

use ppo_tutor::i18n::Lang;
use ppo_tutor::lesson::Course;
use ppo_tutor::lesson::loader::embedded_exercises_in;
use ppo_tutor::lesson::quiz::QuestionKind;

type TestResult = Result<(), Box<dyn std::error::Error>>;

fn lessons_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("lessons")
}

fn lesson_folders() -> Result<Vec<PathBuf>, std::io::Error> {
    let mut dirs: Vec<PathBuf> = std::fs::read_dir(lessons_dir())?
        .filter_map(Result::ok)
        .map(|e| e.path())
        .filter(|p| p.is_dir())
        .collect();
    dirs.sort();
    Ok(dirs)
}

fn is_cjk(c: char) -> bool {
    ('\u{4e00}'..='\u{9fff}').contains(&c) || ('\u{3400}'..='\u{4dbf}').contains(&c)
}

fn has_cjk(s: &str) -> bool {
    s.chars().any(is_cjk)
}

/// `text` without fenced code blocks and inline code spans.
fn prose(text: &str) -> String {
    let mut out = String::new();
    let mut fenced = false;
    for line in text.lines() {
        if line.trim_start().starts_with("```") {
            fenced = !fenced;
            continue;
        }
        if !fenced {
            out.push_str(line);
            out.push('\n');
        }
    }
    let mut plain = String::new();
    let mut in_code = false;
    for c in out.chars() {
        if c == '`' {
            in_code = !in_code;
            plain.push(' ');
        } else if !in_code {
            plain.push(c);
        }
    }
    plain
}

/// The inline code spans of `text` (outside fenced blocks).
fn code_spans(text: &str) -> BTreeSet<String> {
    let mut spans = BTreeSet::new();
    let mut fenced = false;
    for line in text.lines() {
        if line.trim_start().starts_with("```") {
            fenced = !fenced;
            continue;
        }
        if fenced {
            continue;
        }
        let parts: Vec<&str> = line.split('`').collect();
        for (i, part) in parts.iter().enumerate() {
            if i % 2 == 1 && i + 1 < parts.len() && !part.is_empty() {
                spans.insert((*part).to_string());
            }
        }
    }
    spans
}

/// The numbers written in `text`'s prose (`500`, `0.98`, `1e-2`), as written.
fn numbers(text: &str) -> BTreeSet<String> {
    let p = prose(text);
    let chars: Vec<char> = p.chars().collect();
    let mut out = BTreeSet::new();
    let mut i = 0;
    while i < chars.len() {
        let starts = chars[i].is_ascii_digit()
            && (i == 0
                || !(chars[i - 1].is_ascii_alphanumeric()
                    || chars[i - 1] == '_'
                    || chars[i - 1] == '.'));
        if !starts {
            i += 1;
            continue;
        }
        let mut j = i;
        while j < chars.len()
            && (chars[j].is_ascii_digit()
                || (chars[j] == '.' && j + 1 < chars.len() && chars[j + 1].is_ascii_digit()))
        {
            j += 1;
        }
        out.insert(chars[i..j].iter().collect());
        i = j;
    }
    out
}

/// Paragraphs of a Chinese text that are still English: six or more English words in a
/// row and no Chinese character (code, formulas and tags removed first).
fn english_paragraphs(text: &str) -> Vec<String> {
    let p = prose(text);
    let mut out = Vec::new();
    for para in p.split("\n\n") {
        let cleaned = [
            "<app>",
            "</app>",
            "<notebook>",
            "</notebook>",
            "</details>",
            "<details>",
            "<summary>",
            "</summary>",
        ]
        .iter()
        .fold(para.to_string(), |acc, tag| acc.replace(tag, " "));
        if has_cjk(&cleaned) {
            continue;
        }
        let mut run = 0;
        let mut longest = 0;
        for word in cleaned.split_whitespace() {
            let w = word.trim_matches(|c: char| ",.;:!?()\"'".contains(c));
            if w.len() >= 2 && w.chars().all(|c| c.is_ascii_alphabetic()) {
                run += 1;
                longest = longest.max(run);
            } else {
                run = 0;
            }
        }
        if longest >= 6 {
            out.push(para.trim().chars().take(80).collect());
        }
    }
    out
}

#[test]
fn every_lesson_file_has_a_chinese_twin() -> TestResult {
    let mut missing = Vec::new();
    for dir in lesson_folders()? {
        for (en, zh) in [
            ("lesson.md", "lesson.zh.md"),
            ("quiz.toml", "quiz.zh.toml"),
            ("exercise.toml", "exercise.zh.toml"),
            ("exercise.rs", "exercise.zh.rs"),
            ("exercise_candle.rs", "exercise_candle.zh.rs"),
        ] {
            if dir.join(en).exists() != dir.join(zh).exists() {
                missing.push(format!(
                    "{}: {en} without {zh} (or the reverse)",
                    dir.display()
                ));
            }
        }
    }
    assert!(missing.is_empty(), "{missing:#?}");
    Ok(())
}

#[test]
fn the_chinese_course_has_the_english_structure_and_chinese_prose() -> TestResult {
    let en = Course::embedded_in(Lang::En)?;
    let zh = Course::embedded_in(Lang::Zh)?;
    assert_eq!(en.lessons.len(), zh.lessons.len());
    let mut problems = Vec::new();
    for (e, z) in en.lessons.iter().zip(&zh.lessons) {
        let at = format!("lessons/{:02}-{}/lesson.zh.md", e.order, e.id);
        assert_eq!(
            (e.id.as_str(), e.order, e.env),
            (z.id.as_str(), z.order, z.env)
        );
        assert!(
            has_cjk(&z.title) && has_cjk(&z.summary),
            "{at}: title or summary untranslated"
        );
        assert_eq!(e.steps.len(), z.steps.len(), "{at}");
        for (i, (es, zs)) in e.steps.iter().zip(&z.steps).enumerate() {
            let n = i + 1;
            // Shared structure.
            assert_eq!(
                (&es.python, &es.code, &es.show, &es.lab),
                (&zs.python, &zs.code, &zs.show, &zs.lab),
                "{at} step {n}"
            );
            // A title of code names alone ("zero_grad, backward, step") may stay as it is.
            if !has_cjk(&zs.title) && zs.title == es.title {
                problems.push(format!("{at} step {n}: title '{}' untranslated", zs.title));
            }
            for p in english_paragraphs(&zs.body) {
                problems.push(format!("{at} step {n}: untranslated paragraph: {p}"));
            }
            let lost: Vec<String> = code_spans(&es.body)
                .difference(&code_spans(&zs.body))
                .cloned()
                .collect();
            if !lost.is_empty() {
                problems.push(format!("{at} step {n}: code spans missing: {lost:?}"));
            }
            let lost: Vec<String> = numbers(&es.body)
                .difference(&numbers(&zs.body))
                .cloned()
                .collect();
            if !lost.is_empty() {
                problems.push(format!("{at} step {n}: numbers missing: {lost:?}"));
            }
        }
        // Quizzes: same answers, measures and tolerances; Chinese prose.
        assert_eq!(e.quiz.len(), z.quiz.len(), "{at}: quiz");
        for (i, (eq, zq)) in e.quiz.iter().zip(&z.quiz).enumerate() {
            let n = i + 1;
            let texts: Vec<&str> = match (&eq.kind, &zq.kind) {
                (
                    QuestionKind::Choice {
                        answer: a,
                        choices: ca,
                        ..
                    },
                    QuestionKind::Choice {
                        answer: b,
                        choices: cb,
                        explain,
                        ..
                    },
                ) => {
                    assert_eq!((a, ca.len()), (b, cb.len()), "{at} quiz {n}");
                    explain.iter().map(String::as_str).collect()
                }
                (
                    QuestionKind::Predict {
                        measure: ma,
                        tolerance: ta,
                        ..
                    },
                    QuestionKind::Predict {
                        measure: mb,
                        tolerance: tb,
                        explain,
                    },
                ) => {
                    assert_eq!((ma.name, ta), (mb.name, tb), "{at} quiz {n}");
                    vec![explain.as_str()]
                }
                _ => return Err(format!("{at} quiz {n}: kinds differ").into()),
            };
            for t in std::iter::once(zq.prompt.as_str()).chain(texts) {
                if !has_cjk(t) {
                    problems.push(format!("{at} quiz {n}: untranslated: {t}"));
                }
            }
        }
        assert_eq!(
            e.exercise
                .as_ref()
                .map(|x| (&x.name, &x.also, x.hints.len())),
            z.exercise
                .as_ref()
                .map(|x| (&x.name, &x.also, x.hints.len())),
            "{at}: exercise"
        );
    }
    assert!(problems.is_empty(), "{}", problems.join("\n"));
    Ok(())
}

#[test]
fn every_hint_and_mistake_text_is_translated() -> TestResult {
    let en = embedded_exercises_in(Lang::En)?;
    let zh = embedded_exercises_in(Lang::Zh)?;
    assert_eq!(
        en.iter().map(|(d, _)| d).collect::<Vec<_>>(),
        zh.iter().map(|(d, _)| d).collect::<Vec<_>>()
    );
    let mut untranslated = Vec::new();
    for (dir, texts) in &zh {
        for t in texts {
            let all = t
                .hints
                .iter()
                .chain(std::iter::once(&t.fallback))
                .chain(t.idea.as_ref())
                .chain(t.mistakes.values())
                .chain(t.other.values());
            for s in all {
                if !has_cjk(s) {
                    untranslated.push(format!("{dir}/exercise.zh.toml {}: {s}", t.name));
                }
            }
        }
    }
    assert!(untranslated.is_empty(), "{untranslated:#?}");
    Ok(())
}

/// The code of a Rust file: comments removed, blank lines dropped.
fn code_only(text: &str) -> Vec<String> {
    text.lines()
        .map(|l| match l.find("//") {
            Some(i) => l[..i].trim_end().to_string(),
            None => l.trim_end().to_string(),
        })
        .filter(|l| !l.trim().is_empty())
        .collect()
}

#[test]
fn chinese_starters_are_the_english_code_with_chinese_comments() -> TestResult {
    let mut checked = 0;
    for dir in lesson_folders()? {
        for (en, zh) in [
            ("exercise.rs", "exercise.zh.rs"),
            ("exercise_candle.rs", "exercise_candle.zh.rs"),
        ] {
            let (Ok(e), Ok(z)) = (
                std::fs::read_to_string(dir.join(en)),
                std::fs::read_to_string(dir.join(zh)),
            ) else {
                continue;
            };
            assert_eq!(
                code_only(&e),
                code_only(&z),
                "{}/{zh}: the code differs from {en}",
                dir.display()
            );
            for line in z.lines().filter(|l| l.trim_start().starts_with("//")) {
                assert!(
                    english_paragraphs(line.trim_start_matches(['/', '!', ' '])).is_empty(),
                    "{}/{zh}: English comment: {line}",
                    dir.display()
                );
            }
            checked += 1;
        }
    }
    assert!(checked >= 10, "only {checked} starters checked");
    Ok(())
}

#[test]
fn chinese_starters_are_what_reset_writes_in_chinese() -> TestResult {
    let tmp = tempfile::tempdir()?;
    let _zh = Lang::Zh.scoped();
    let path = ppo_tutor::grade::reset("n_step_target", tmp.path())?.path;
    let written = std::fs::read_to_string(&path)?;
    let expected = std::fs::read_to_string(lessons_dir().join("07-td-target/exercise.zh.rs"))?;
    assert_eq!(written, expected);
    Ok(())
}

#[derive(serde::Deserialize)]
struct Glossary {
    term: Vec<Term>,
}

#[derive(serde::Deserialize)]
struct Term {
    en: String,
    zh: String,
    #[serde(default)]
    avoid: Vec<String>,
    /// Phrases removed from a text before this term's `avoid` words are looked for: the
    /// narrow exceptions to an avoided word (梯度裁剪, gradient-norm clipping, for the clip's
    /// 裁剪).
    #[serde(default)]
    allow: Vec<String>,
}

impl Term {
    /// The `avoid` words `text` uses, once the `allow` phrases are taken out of it.
    fn avoided_in(&self, text: &str) -> Vec<&str> {
        let rest = self.allow.iter().fold(text.to_string(), |acc, phrase| {
            acc.replace(phrase.as_str(), " ")
        });
        self.avoid
            .iter()
            .filter(|word| rest.contains(word.as_str()))
            .map(String::as_str)
            .collect()
    }
}

fn glossary() -> Result<Glossary, Box<dyn std::error::Error>> {
    Ok(toml::from_str(&std::fs::read_to_string(
        lessons_dir().join("glossary.toml"),
    )?)?)
}

#[test]
fn no_two_english_terms_share_a_chinese_term() -> TestResult {
    let g = glossary()?;
    let mut by_zh: BTreeMap<&str, Vec<&str>> = BTreeMap::new();
    for t in &g.term {
        by_zh.entry(t.zh.as_str()).or_default().push(t.en.as_str());
    }
    let shared: Vec<_> = by_zh.iter().filter(|(_, en)| en.len() > 1).collect();
    assert!(
        shared.is_empty(),
        "one Chinese term for several English ones: {shared:?}"
    );
    let en: BTreeSet<&str> = g.term.iter().map(|t| t.en.as_str()).collect();
    assert_eq!(en.len(), g.term.len(), "an English term is listed twice");
    // The two ideas Chinese texts both call 截断 are kept apart.
    let zh_of = |prefix: &str| {
        g.term
            .iter()
            .find(|t| t.en.starts_with(prefix))
            .map(|t| t.zh.clone())
    };
    let clip = zh_of("clip").ok_or("no clip term")?;
    let truncation = zh_of("truncation").ok_or("no truncation term")?;
    assert_ne!(clip, truncation);
    assert!(!truncation.contains(&clip), "{truncation} contains {clip}");
    Ok(())
}

#[test]
fn the_chinese_course_never_uses_a_word_the_glossary_avoids() -> TestResult {
    let g = glossary()?;
    let mut found = Vec::new();
    for dir in lesson_folders()? {
        for entry in std::fs::read_dir(&dir)? {
            let path = entry?.path();
            let name = path.file_name().and_then(|n| n.to_str()).unwrap_or("");
            if !name.contains(".zh.") {
                continue;
            }
            let text = std::fs::read_to_string(&path)?;
            for t in &g.term {
                for word in t.avoided_in(&text) {
                    found.push(format!(
                        "{}: '{word}' (write {} for {})",
                        path.display(),
                        t.zh,
                        t.en
                    ));
                }
            }
        }
    }
    assert!(found.is_empty(), "{found:#?}");
    Ok(())
}

/// Every `.rs` file under `dir`, recursively.
fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) -> std::io::Result<()> {
    for entry in std::fs::read_dir(dir)? {
        let path = entry?.path();
        if path.is_dir() {
            rust_files(&path, out)?;
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
    Ok(())
}

/// The interface's Chinese (every line of the program's and the crates' sources that holds
/// Chinese: the second half of `t`/`tr!` pairs, the graders' phrases, the CLI's help
/// catalogue) keeps to the glossary as the course does. Two files use a word the glossary
/// avoids as test data for the markdown renderer, not as text anyone reads.
#[test]
fn the_interface_never_uses_a_word_the_glossary_avoids() -> TestResult {
    const TEST_DATA: [&str; 2] = ["inline.rs", "markdown.rs"];
    let g = glossary()?;
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut files = Vec::new();
    rust_files(&root.join("src"), &mut files)?;
    for krate in std::fs::read_dir(root.join("crates"))? {
        rust_files(&krate?.path().join("src"), &mut files)?;
    }
    assert!(files.len() > 50, "found only {} source files", files.len());
    let mut found = Vec::new();
    for path in &files {
        let name = path.file_name().and_then(|n| n.to_str()).unwrap_or("");
        if TEST_DATA.contains(&name) {
            continue;
        }
        let text = std::fs::read_to_string(path)?;
        for (i, line) in text.lines().enumerate().filter(|(_, l)| has_cjk(l)) {
            for t in &g.term {
                for word in t.avoided_in(line) {
                    found.push(format!(
                        "{}:{}: '{word}' (write {} for {})",
                        path.display(),
                        i + 1,
                        t.zh,
                        t.en
                    ));
                }
            }
        }
    }
    assert!(found.is_empty(), "{found:#?}");
    Ok(())
}

#[test]
fn an_allowed_phrase_is_the_only_exception_to_an_avoided_word() -> TestResult {
    let g = glossary()?;
    let clip = g
        .term
        .iter()
        .find(|t| t.en.starts_with("clip"))
        .ok_or("no clip term")?;
    // Gradient-norm clipping is 梯度裁剪; PPO's clip is never 裁剪.
    assert!(
        clip.avoided_in("对梯度做梯度裁剪（最大范数 0.5）。")
            .is_empty()
    );
    assert_eq!(clip.avoided_in("把比率裁剪到 [0.8, 1.2]。"), ["裁剪"]);
    assert_eq!(clip.avoided_in("梯度裁剪之后，再把比率裁剪。"), ["裁剪"]);
    // Every allowed phrase contains one of its term's avoided words, or it would allow nothing.
    for t in &g.term {
        for phrase in &t.allow {
            assert!(
                t.avoid.iter().any(|w| phrase.contains(w.as_str())),
                "{}: allow '{phrase}' contains none of its avoid words",
                t.en
            );
        }
    }
    Ok(())
}

#[test]
fn a_translation_that_does_not_match_its_lesson_is_refused() -> TestResult {
    use ppo_tutor::lesson::loader::{parse_lesson, translate_lesson};
    let english = "+++\nid = \"demo\"\ntitle = \"Demo\"\n\n[[steps]]\ntitle = \"One\"\n\n[[steps]]\ntitle = \"Two\"\n+++\n\n## One\n\nRun it<app> with `x`</app>.\n\n## Two\n\nDone.\n";
    let lesson = parse_lesson("99-demo", english)?;
    let good = "+++\ntitle = \"演示\"\n\n[[steps]]\ntitle = \"一\"\n\n[[steps]]\ntitle = \"二\"\n+++\n\n## 一\n\n运行它<app>（按 `x`）</app>。\n\n## 二\n\n完成。\n";
    let mut ok = lesson.clone();
    translate_lesson(&mut ok, "99-demo", good)?;
    assert_eq!(
        (ok.title.as_str(), ok.steps[1].title.as_str()),
        ("演示", "二")
    );
    assert_eq!(ok.steps[0].code, lesson.steps[0].code);
    for (broken, why) in [
        (good.replace("\n## 二\n\n完成。\n", ""), "a step missing"),
        (
            good.replace("<app>（按 `x`）</app>", "（按 `x`）"),
            "an <app> passage lost",
        ),
        (
            good.replace("## 二", "## 三"),
            "a heading that is not its title",
        ),
        (
            good.replace("title = \"演示\"", "title = \"演示\"\ncode = \"ratio\""),
            "structure in a translation",
        ),
    ] {
        let mut l = lesson.clone();
        let err = translate_lesson(&mut l, "99-demo", &broken)
            .err()
            .ok_or(why)?;
        assert!(
            err.to_string().contains("lessons/99-demo/lesson.zh.md"),
            "{why}: {err}"
        );
    }
    Ok(())
}

#[test]
fn the_untranslated_paragraph_check_finds_english() {
    assert_eq!(
        english_paragraphs("这是一段中文，提到 `td_target` 和 r_t·Â_t。").len(),
        0
    );
    assert_eq!(
        english_paragraphs(
            "中文段落。\n\nThe critic predicted the value before the step was taken."
        )
        .len(),
        1
    );
    // Code alone is not an English paragraph.
    assert_eq!(
        english_paragraphs("`let the value be what it is here now`").len(),
        0
    );
}

/// A recipe's code with comments and string literals blanked, and its `// %%` markers.
fn recipe_shape(text: &str) -> (Vec<String>, Vec<String>) {
    let mut code = Vec::new();
    let mut markers = Vec::new();
    for line in text.lines() {
        let t = line.trim_start();
        if t.starts_with("// %%") || t.starts_with("// check:") {
            markers.push(line.to_string());
            continue;
        }
        let mut out = String::new();
        let mut in_str = false;
        let mut escaped = false;
        let chars: Vec<char> = line.chars().collect();
        let mut i = 0;
        while i < chars.len() {
            let c = chars[i];
            if in_str {
                if escaped {
                    escaped = false;
                } else if c == '\\' {
                    escaped = true;
                } else if c == '"' {
                    in_str = false;
                    out.push('"');
                }
            } else if c == '/' && chars.get(i + 1) == Some(&'/') {
                break;
            } else {
                out.push(c);
                if c == '"' {
                    in_str = true;
                }
            }
            i += 1;
        }
        if !out.trim().is_empty() {
            code.push(out.trim_end().to_string());
        }
    }
    (code, markers)
}

#[test]
fn chinese_recipes_run_the_english_code() -> TestResult {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("notebooks/src");
    let mut checked = 0;
    for entry in std::fs::read_dir(&src)? {
        let path = entry?.path();
        let Some(name) = path.file_name().and_then(|n| n.to_str()) else {
            continue;
        };
        if !name.ends_with(".rs") {
            continue;
        }
        let en = std::fs::read_to_string(&path)?;
        let zh = std::fs::read_to_string(src.join("zh").join(name))
            .map_err(|e| format!("notebooks/src/zh/{name}: {e}"))?;
        let (ec, em) = recipe_shape(&en);
        let (zc, zm) = recipe_shape(&zh);
        assert_eq!(
            em, zm,
            "notebooks/src/zh/{name}: the `// %%` markers differ"
        );
        assert_eq!(
            ec, zc,
            "notebooks/src/zh/{name}: the code differs from the English recipe"
        );
        for line in zh
            .lines()
            .filter(|l| l.trim_start().starts_with("//") && !l.contains("%%"))
        {
            assert!(
                english_paragraphs(line.trim_start_matches(['/', '!', ' '])).is_empty(),
                "notebooks/src/zh/{name}: English comment: {line}"
            );
        }
        checked += 1;
    }
    assert_eq!(checked, Course::embedded_in(Lang::En)?.lessons.len());
    Ok(())
}

/// The Chinese twin of `tests/lessons.rs`'s face check: a notebook's Chinese text says
/// nothing of panels, the sandbox, keys or the screen, and the terminal's nothing of cells.
#[test]
fn each_chinese_face_speaks_of_what_it_has() -> TestResult {
    use ppo_tutor::lesson::face::Face;
    let course = Course::embedded_in(Lang::Zh)?;
    let mut problems = Vec::new();
    for l in &course.lessons {
        for (i, s) in l.steps.iter().enumerate() {
            let at = format!(
                "lessons/{:02}-{}/lesson.zh.md, step {}",
                l.order,
                l.id,
                i + 1
            );
            let notebook = s.text(Face::Notebook);
            for word in [
                "面板",
                "沙盒",
                "按下 `",
                "按 `",
                "按键",
                "屏幕上",
                "这段文字旁边",
                "正文旁边",
                "应用里",
                "应用中",
            ] {
                if notebook.contains(word) {
                    problems.push(format!("{at}, notebook face: '{word}'"));
                }
            }
            let names: Vec<&str> = s
                .python
                .split(|c: char| !(c.is_alphanumeric() || c == '_'))
                .collect();
            let chars: Vec<char> = notebook.chars().collect();
            for w in chars.windows(3) {
                if w[0] == '`'
                    && w[2] == '`'
                    && w[1].is_ascii_graphic()
                    && w[1] != '`'
                    && !names.contains(&w[1].to_string().as_str())
                {
                    problems.push(format!("{at}, notebook face: the key `{}`", w[1]));
                }
            }
            let terminal = s.text(Face::Terminal);
            for word in ["单元格", "笔记本", "Jupyter"] {
                if terminal.contains(word) {
                    problems.push(format!("{at}, terminal face: '{word}'"));
                }
            }
        }
    }
    assert!(problems.is_empty(), "{}", problems.join("\n"));
    Ok(())
}
