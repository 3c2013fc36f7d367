//! No English on a Chinese screen: every Chinese screen of the terminal
//! app (the `*zh*` insta snapshots `tests/tui.rs` writes) and every Chinese notebook's outputs
//! (`notebooks/zh/*.ipynb`, as the last `dev notebooks` run left them), read as a user reads
//! them, hold no English word outside code, identifiers, units and names.
//!
//! What counts as code or a name comes from the program's own data, not from a list typed
//! here: the code the app's code pane can show (each step's quoted Python, the engine's code
//! by anchor, hidden or revealed, and the lessons' Rust files), the live values' names, the
//! hyper-parameter table, the clip lab's experiments, and the words a lesson writes in code
//! spans or uses as identifiers of that code. The detector is
//! [`ppo_tutor::i18n::english_words`], with its reviewed [`ppo_tutor::i18n::ALLOWED_WORDS`].
//!
//! A failure lists `file: row/cell: words`, so that whoever fixes it finds the string.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

use ppo_tutor::i18n::{ALLOWED_WORDS, Lang, english_words};
use ppo_tutor::lesson::live::names;
use ppo_tutor::lesson::reveal::{Row, listing};
use ppo_tutor::lesson::{AgentKind, Course, RunConfig, Session, Snapshot};
use ppo_tutor::ppo::knobs::{KnobKind, Tunable};
use ppo_tutor::ppo::lab::Experiment;
use ppo_tutor::ppo::{PpoConfig, PpoContinuousConfig};

type TestResult = Result<(), Box<dyn std::error::Error>>;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// Keywords of Rust and Python: the code's words that are also English words, so they are
/// not identifiers a prose may use bare (`while not done` in prose is a slip: write it as code).
const KEYWORDS: &[&str] = &[
    "as", "break", "const", "continue", "crate", "else", "enum", "extern", "false", "fn", "for",
    "if", "impl", "in", "let", "loop", "match", "mod", "move", "mut", "pub", "ref", "return",
    "self", "Self", "static", "struct", "super", "trait", "true", "type", "unsafe", "use", "where",
    "while", "async", "await", "dyn", "and", "assert", "def", "del", "elif", "except", "finally",
    "from", "global", "import", "is", "lambda", "nonlocal", "not", "or", "pass", "raise", "try",
    "with", "yield", "None", "True", "False",
];

/// Names of keyboard keys as printed on the keys (the app's key bar and help).
const KEY_CAPS: &[&str] = &[
    "Esc",
    "Enter",
    "Ctrl-C",
    "Backspace",
    "Tab",
    "PgDn",
    "PgUp",
    "Home",
    "End",
];

/// Python's bool literals: a bool tensor's elements as the seed's PyTorch prints them (the
/// live pane's `clipped` and `dones` columns).
const LITERALS: &[&str] = &["True", "False"];

/// Everything the checks need from the program, gathered once.
struct Known {
    /// Every line (trimmed) of code the app's code pane can show.
    code_lines: BTreeSet<String>,
    /// Words allowed on every screen: live values, hyper-parameter names, experiments,
    /// language names, key caps, bool literals.
    global: BTreeSet<String>,
    /// The hyper-parameter table's rows, `(name, value)`: a value is allowed beside its name.
    hyper: BTreeSet<(String, String)>,
    /// Per lesson folder (`07-td-target`): the words of its Chinese files' code spans and the
    /// code identifiers its Chinese prose uses.
    lesson: BTreeMap<String, BTreeSet<String>>,
}

fn words_of(text: &str) -> impl Iterator<Item = &str> {
    text.split(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
        .filter(|w| w.starts_with(|c: char| c.is_ascii_alphabetic()))
}

fn without_comment(line: &str) -> &str {
    let cut = line.find("//").unwrap_or(line.len());
    let line = &line[..cut];
    match line.find("# ") {
        Some(i) if !line.trim_start().starts_with("#[") => &line[..i],
        _ => line,
    }
}

/// The inline code spans of a Markdown or TOML text.
fn code_spans(text: &str) -> Vec<&str> {
    text.lines()
        .flat_map(|line| {
            let parts: Vec<&str> = line.split('`').collect();
            let n = parts.len();
            parts
                .into_iter()
                .enumerate()
                .filter(move |(i, _)| i % 2 == 1 && i + 1 < n)
                .map(|(_, p)| p)
        })
        .collect()
}

fn lesson_folders() -> std::io::Result<Vec<PathBuf>> {
    let mut dirs: Vec<PathBuf> = std::fs::read_dir(root().join("lessons"))?
        .filter_map(Result::ok)
        .map(|e| e.path())
        .filter(|p| p.is_dir())
        .collect();
    dirs.sort();
    Ok(dirs)
}

fn files_in(dir: &Path, keep: impl Fn(&str) -> bool) -> std::io::Result<Vec<PathBuf>> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)?
        .filter_map(Result::ok)
        .map(|e| e.path())
        .filter(|p| p.file_name().and_then(|n| n.to_str()).is_some_and(&keep))
        .collect();
    files.sort();
    Ok(files)
}

impl Known {
    fn gather() -> Result<Self, Box<dyn std::error::Error>> {
        let mut code = Vec::<String>::new();
        for lang in Lang::ALL {
            let course = Course::embedded_in(lang)?;
            for lesson in &course.lessons {
                for step in &lesson.steps {
                    code.extend(step.python.lines().map(str::to_string));
                    for passed in [false, true] {
                        if let Some(l) = listing(&step.code, &|_| passed) {
                            code.extend(l.rows.into_iter().filter_map(|r| match r {
                                Row::Code(c) => Some(c),
                                Row::Hidden { .. } => None,
                            }));
                        }
                    }
                }
            }
        }
        let folders = lesson_folders()?;
        for dir in &folders {
            for file in files_in(dir, |n| n.ends_with(".rs"))? {
                code.extend(std::fs::read_to_string(file)?.lines().map(str::to_string));
            }
        }
        let code_lines: BTreeSet<String> = code
            .iter()
            .map(|l| l.trim().to_string())
            .filter(|l| !l.is_empty())
            .collect();
        let identifiers: BTreeSet<String> = code_lines
            .iter()
            .flat_map(|l| words_of(without_comment(l)))
            .filter(|w| !KEYWORDS.contains(w))
            .map(str::to_string)
            .collect();

        let mut hyper = BTreeSet::new();
        for agent in AgentKind::ALL {
            hyper.extend(Snapshot::new(RunConfig::default_for(agent), 0).hyper);
        }
        let mut global: BTreeSet<String> = names().iter().map(|s| (*s).to_string()).collect();
        global.extend(hyper.iter().map(|(k, _)| k.clone()));
        global.extend(Experiment::ALL.iter().map(|e| e.name().to_string()));
        global.extend(Lang::ALL.iter().map(|l| l.name().to_string()));
        global.extend(KEY_CAPS.iter().chain(LITERALS).map(|s| (*s).to_string()));
        // The sandbox's settings and every value it shows for them (in Chinese: a switch
        // shows 开/关 there, so `true`/`false` are not among them).
        {
            let _zh = Lang::Zh.scoped();
            knob_words::<PpoConfig>(&mut global);
            knob_words::<PpoContinuousConfig>(&mut global);
        }
        // The live values' element types (`bool`, `int64`), from a short run of each kind.
        for snapshot in [
            Session::run(PpoConfig::default(), 0, 1)?,
            Session::run(PpoContinuousConfig::default(), 0, 1)?,
        ] {
            for name in names() {
                if let Some(view) = snapshot.tensor(name) {
                    global.insert(view.dtype.to_string());
                }
            }
        }

        // Lesson titles name code (`PolicyNet 与 ValueNet`): the lesson list shows them all.
        for lang in Lang::ALL {
            for l in &Course::embedded_in(lang)?.lessons {
                global.extend(
                    english_words(&l.title, &BTreeSet::new())
                        .into_iter()
                        .filter(|w| identifiers.contains(w)),
                );
            }
        }
        let mut lesson = BTreeMap::new();
        for dir in &folders {
            let mut words = BTreeSet::new();
            for file in files_in(dir, |n| n.contains(".zh."))? {
                let text = std::fs::read_to_string(file)?;
                for span in code_spans(&text) {
                    words.extend(span.split(char::is_whitespace).map(str::to_string));
                    // Also the parts a wrapped screen row may cut it into (`actor_lr`).
                    for word in words_of(span) {
                        words.extend(word.split('_').map(str::to_string));
                        words.insert(word.to_string());
                    }
                }
                // The code's identifiers the prose writes bare (`softmax`, `logits`).
                words.extend(
                    english_words(&text, &BTreeSet::new())
                        .into_iter()
                        .filter(|w| identifiers.contains(w)),
                );
            }
            let name = dir
                .file_name()
                .and_then(|n| n.to_str())
                .ok_or("a lesson folder without a name")?;
            lesson.insert(name.to_string(), words);
        }
        Ok(Self {
            code_lines,
            global,
            hyper,
            lesson,
        })
    }

    /// Whether `cell` (a piece of a screen row) is code the code pane shows: what is left
    /// of it, without a cut mark or a wrapped line's `↪`, is part of a line of code.
    fn is_code(&self, cell: &str) -> bool {
        let c = cell.trim();
        let c = c.strip_prefix('↪').unwrap_or(c);
        let c = c.trim().trim_end_matches('…').trim();
        c.is_empty() || self.code_lines.iter().any(|l| l.contains(c))
    }

    /// The English words of `text`, a piece of a screen of lesson `lesson` (a folder name,
    /// if the screen belongs to one).
    fn english(&self, text: &str, lesson: Option<&str>) -> Vec<String> {
        let none = BTreeSet::new();
        let local = lesson.and_then(|l| self.lesson.get(l)).unwrap_or(&none);
        let allowed =
            |w: &str| ALLOWED_WORDS.contains(&w) || self.global.contains(w) || local.contains(w);
        let text = self.without_pairs(&without_glosses(text));
        let mut out = Vec::new();
        for word in english_words(&text, &self.global) {
            let w = word.trim_matches(|c: char| "“”‘’\"'".contains(c));
            let w = w
                .strip_suffix("'s")
                .or_else(|| w.strip_suffix("’s"))
                .unwrap_or(w);
            // One letter: a key (`q 退出`), a quiz choice (`b)`), a variable (`t = 1`).
            // Anything but letters, `-` and `'`: a formula (`∇log`, `|r`, `m̂`, `a–d`).
            if w.chars().filter(char::is_ascii_alphabetic).count() < 2
                || w.chars()
                    .any(|c| !(c.is_ascii_alphabetic() || "-'’".contains(c)))
                || allowed(w)
            {
                continue;
            }
            // A word cut by the screen's edge (`ValueN…`, or a row that just stops) of an
            // allowed one.
            if (text.contains(&format!("{w}…")) || text.trim_end().ends_with(w))
                && (self.global.iter().chain(local).any(|a| a.starts_with(w))
                    || ALLOWED_WORDS.iter().any(|a| a.starts_with(w)))
            {
                continue;
            }
            out.push(w.to_string());
        }
        out
    }

    /// `text` without what code writes, in the forms a screen prints it: assignments (a
    /// name or `[a, b]`, `=`, then a value, a `[list]` or `x or y`: `gamma = 0.98`,
    /// `done = term or trunc`, `let x = …`), a loop's head (`for e in 0..E`), `} else {`,
    /// Rust's `Debug` fields (`algorithm: Ppo,`) and the
    /// hyper-parameter table's rows (`bootstrap_on_truncation  false`).
    fn without_pairs(&self, text: &str) -> String {
        const OPERATORS: &[&str] = &[
            "or", "and", "not", "+", "-", "−", "*", "/", "×", "·", "==", "||", "&&",
        ];
        let plain = |t: &str| {
            !t.is_empty()
                && t.chars()
                    .all(|c| c.is_ascii_alphanumeric() || "_.-+[]'(),;".contains(c))
        };
        let tokens: Vec<&str> = text.split_whitespace().collect();
        let mut out: Vec<String> = Vec::new();
        let mut i = 0;
        while i < tokens.len() {
            let token = tokens[i];
            if ["=", "+=", "-=", "*=", "/="].contains(&token) {
                // The name: a `[list]`, or the identifier that ends the token before.
                if out.last().is_some_and(|l| l.ends_with(']'))
                    && out.iter().any(|l| l.contains('['))
                {
                    while let Some(l) = out.pop() {
                        if l.contains('[') {
                            break;
                        }
                    }
                } else if let Some(last) = out.pop() {
                    let keep = last
                        .char_indices()
                        .rev()
                        .find(|(_, c)| !c.is_ascii())
                        .map_or(0, |(at, c)| at + c.len_utf8());
                    if keep > 0 {
                        out.push(last[..keep].to_string());
                    }
                    // `let mut x = …`
                    while let Some(l) = out.pop() {
                        let rest = l.trim_end_matches("mut").trim_end_matches("let");
                        if rest.len() < l.len() && !rest.ends_with(|c: char| c.is_ascii()) {
                            if !rest.is_empty() {
                                out.push(rest.to_string());
                            }
                            continue;
                        }
                        out.push(l);
                        break;
                    }
                }
                // The value.
                i += 1;
                if tokens.get(i).is_some_and(|t| t.starts_with('[')) {
                    while let Some(t) = tokens.get(i) {
                        i += 1;
                        if t.contains(']') {
                            break;
                        }
                    }
                } else {
                    i += 1;
                    while i + 1 < tokens.len()
                        && OPERATORS.contains(&tokens[i])
                        && plain(tokens[i + 1])
                    {
                        i += 2;
                    }
                }
                continue;
            }
            // A loop's head (`for e in 0..E`) and an `} else {`.
            if token.ends_with("for") && tokens.get(i + 2) == Some(&"in") {
                out.push(token.trim_end_matches("for").to_string());
                i += 4;
                continue;
            }
            if token == "else" && i > 0 && tokens[i - 1] == "}" {
                i += 1;
                continue;
            }
            let field = token.strip_suffix(':').is_some_and(|name| {
                !name.is_empty()
                    && name
                        .chars()
                        .all(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || c == '_')
            });
            if field && tokens.get(i + 1).is_some_and(|v| v.ends_with(',')) {
                i += 2;
                continue;
            }
            if let Some(value) = tokens.get(i + 1)
                && self
                    .hyper
                    .contains(&(token.to_string(), (*value).to_string()))
            {
                i += 2;
                continue;
            }
            out.push(token.to_string());
            i += 1;
        }
        out.join(" ")
    }
}

/// The sandbox's setting names for agents configured by `C`, and the values it shows for
/// each, a few notches up and down from the default.
fn knob_words<C: Tunable + Default>(out: &mut BTreeSet<String>) {
    for knob in C::KNOBS {
        out.insert(knob.id.to_string());
        if let KnobKind::Value { show, nudge } = &knob.kind {
            for up in [true, false] {
                let mut config = C::default();
                for _ in 0..8 {
                    out.extend(show(&config).split_whitespace().map(str::to_string));
                    nudge(&mut config, up);
                }
            }
        }
    }
}

fn is_ideograph(c: char) -> bool {
    ('\u{4e00}'..='\u{9fff}').contains(&c) || ('\u{3400}'..='\u{4dbf}').contains(&c)
}

/// `text` without the English glosses of Chinese terms: a full-width parenthesis right after
/// a Chinese character, holding no Chinese character (`近端策略优化（Proximal Policy
/// Optimization，PPO）`, `在线策略（on-policy）`), also when the screen wraps it (the gloss
/// then runs to the end of the row, or starts the next one).
fn without_glosses(text: &str) -> String {
    let chars: Vec<char> = text.chars().collect();
    let mut out = String::new();
    let mut i = 0;
    // A row that opens inside a gloss: up to the first `）` if nothing Chinese precedes it.
    if let Some(close) = chars.iter().position(|&c| c == '）') {
        let head = &chars[..close];
        if !head.contains(&'（') && !head.iter().any(|&c| is_ideograph(c)) {
            i = close + 1;
        }
    }
    while i < chars.len() {
        let c = chars[i];
        if c == '（' && (i == 0 || is_ideograph(chars[i - 1])) {
            let end = chars[i..]
                .iter()
                .position(|&c| c == '）')
                .map_or(chars.len(), |p| i + p + 1);
            if !chars[i..end].iter().any(|&c| is_ideograph(c)) {
                out.push(' ');
                i = end;
                continue;
            }
        }
        out.push(c);
        i += 1;
    }
    out
}

/// The lesson folder a screen belongs to, from its top row (` 07/18 TD 目标… · 第 1/5 节`).
fn lesson_of_screen(first_row: &str, folders: &[String]) -> Option<String> {
    let order: u32 = first_row.trim().split('/').next()?.trim().parse().ok()?;
    folders
        .iter()
        .find(|f| f.starts_with(&format!("{order:02}-")))
        .cloned()
}

/// The Chinese snapshots' problems, one line per cell with English in it.
fn snapshot_problems(known: &Known) -> Result<(usize, Vec<String>), Box<dyn std::error::Error>> {
    let folders: Vec<String> = known.lesson.keys().cloned().collect();
    let snaps = files_in(&root().join("tests/snapshots"), |n| {
        n.contains("zh") && n.ends_with(".snap")
    })?;
    let mut problems = Vec::new();
    for snap in &snaps {
        let text = std::fs::read_to_string(snap)?;
        let name = snap.file_name().and_then(|n| n.to_str()).unwrap_or("?");
        // The header (between the `---` lines) is insta's, not the screen.
        let body = text.splitn(3, "---\n").nth(2).unwrap_or("");
        let rows: Vec<&str> = body.lines().map(|r| r.trim().trim_matches('"')).collect();
        let lesson = rows.first().and_then(|r| lesson_of_screen(r, &folders));
        for (n, row) in rows.iter().enumerate() {
            // Cells: what lies between box-drawing characters (panels, overlays).
            for cell in row.split(|c: char| ('\u{2500}'..='\u{257f}').contains(&c)) {
                if known.is_code(cell) {
                    continue;
                }
                let words = known.english(cell, lesson.as_deref());
                if !words.is_empty() {
                    problems.push(format!(
                        "{name}: row {}: {:?}: {}",
                        n + 1,
                        cell.trim(),
                        words.join(", ")
                    ));
                }
            }
        }
    }
    Ok((snaps.len(), problems))
}

/// What a reader sees of an HTML or SVG output: the text between tags (`<code>` as a code
/// span), and tooltips.
fn visible_text(html: &str) -> String {
    let mut out = String::new();
    let mut rest = html;
    while let Some(start) = rest.find('<') {
        out.push_str(&rest[..start]);
        out.push(' ');
        let tail = &rest[start..];
        let end = tail.find('>').map_or(tail.len(), |e| e + 1);
        let tag = &tail[..end];
        if let Some(skipped) = ["style", "script"]
            .into_iter()
            .find(|s| tag.starts_with(&format!("<{s}")))
        {
            let close = format!("</{skipped}>");
            let after = tail.find(&close).map_or(tail.len(), |e| e + close.len());
            rest = &tail[after..];
            continue;
        }
        // `<code>` is code, as a code span is.
        if tag == "<code>" || tag.starts_with("<code ") || tag == "</code>" {
            out.push('`');
        }
        if let Some(title) = tag
            .split("title=\"")
            .nth(1)
            .and_then(|t| t.split('"').next())
        {
            out.push_str(title);
            out.push(' ');
        }
        rest = &tail[end..];
    }
    out.push_str(rest);
    out.replace("&lt;", "<")
        .replace("&gt;", ">")
        .replace("&quot;", "\"")
        .replace("&#39;", "'")
        .replace("&nbsp;", " ")
        .replace("&amp;", "&")
}

fn joined(value: &serde_json::Value) -> String {
    match value {
        serde_json::Value::String(s) => s.clone(),
        serde_json::Value::Array(parts) => parts.iter().filter_map(|p| p.as_str()).collect(),
        _ => String::new(),
    }
}

/// A Markdown cell's prose: no fenced code, no `$math$`, no HTML tags.
fn markdown_prose(text: &str) -> String {
    let mut out = String::new();
    let mut fenced = false;
    for line in text.lines() {
        if line.trim_start().starts_with("```") {
            fenced = !fenced;
            continue;
        }
        if fenced {
            continue;
        }
        let plain: String = line
            .split('$')
            .enumerate()
            .filter(|(i, _)| i % 2 == 0)
            .map(|(_, p)| p)
            .collect::<Vec<_>>()
            .join(" ");
        // Emphasis marks go (a gloss follows `**在线策略**（on-policy）`).
        out.push_str(&visible_text(&plain).replace("**", ""));
        out.push('\n');
    }
    out
}

/// The Chinese notebooks' problems, one line per line with English in it: their cells'
/// outputs, or (`markdown`) their Markdown cells' prose.
fn notebook_problems(
    known: &Known,
    markdown: bool,
) -> Result<(usize, Vec<String>), Box<dyn std::error::Error>> {
    let books = files_in(&root().join("notebooks/zh"), |n| n.ends_with(".ipynb"))?;
    let mut problems = Vec::new();
    for book in &books {
        let name = book.file_name().and_then(|n| n.to_str()).unwrap_or("?");
        let lesson = name.trim_end_matches(".ipynb");
        let nb: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(book)?)?;
        let cells = nb["cells"].as_array().ok_or("a notebook without cells")?;
        for (i, cell) in cells.iter().enumerate() {
            let source = joined(&cell["source"]);
            let mut texts: Vec<(String, String)> = Vec::new();
            if markdown {
                if cell["cell_type"] == "markdown" {
                    texts.push(("markdown".into(), markdown_prose(&source)));
                }
            } else {
                // A cell with evcxr commands (`:dep`, `:env`, the setup cell) prints the
                // kernel's own messages (`Child process restarted`), not the course's.
                let kernel_only = source.lines().any(|l| l.starts_with(':'));
                for output in cell["outputs"].as_array().into_iter().flatten() {
                    if kernel_only {
                        break;
                    }
                    if output.get("text").is_some() {
                        texts.push(("stream".into(), joined(&output["text"])));
                    }
                    for (kind, data) in output["data"].as_object().into_iter().flatten() {
                        let text = joined(data);
                        match kind.as_str() {
                            "text/plain" => texts.push((kind.clone(), text)),
                            "text/html" | "image/svg+xml" => {
                                texts.push((kind.clone(), visible_text(&text)));
                            }
                            _ => {}
                        }
                    }
                }
            }
            let mut seen = BTreeSet::new();
            for (kind, text) in texts {
                for line in text.lines() {
                    // A grader report's `异常：` line quotes the learner's program (Rust's
                    // own message, `not yet implemented`), as the compiler's errors are.
                    let line = line.split("异常：").next().unwrap_or(line);
                    let words = known.english(line, Some(lesson));
                    if !words.is_empty() && seen.insert(words.clone()) {
                        problems.push(format!(
                            "notebooks/zh/{name}: cell {i} ({kind}): {:?}: {}",
                            line.trim(),
                            words.join(", ")
                        ));
                    }
                }
            }
        }
    }
    Ok((books.len(), problems))
}

fn report(what: &str, problems: &[String]) -> String {
    let mut by_word: BTreeMap<&str, usize> = BTreeMap::new();
    for p in problems {
        for w in p.rsplit(": ").next().unwrap_or("").split(", ") {
            *by_word.entry(w).or_default() += 1;
        }
    }
    format!(
        "{} {what} with English (file: row/cell: text: words):\n{}\n\nwords, with how often: {by_word:?}",
        problems.len(),
        problems.join("\n")
    )
}

#[test]
fn no_english_on_a_chinese_screen_of_the_app() -> TestResult {
    let known = Known::gather()?;
    let (screens, problems) = snapshot_problems(&known)?;
    assert!(
        screens >= 200,
        "only {screens} Chinese snapshots in tests/snapshots (run `cargo test --test tui`)"
    );
    assert!(problems.is_empty(), "{}", report("cells", &problems));
    Ok(())
}

#[test]
fn no_english_in_a_chinese_notebook_s_outputs() -> TestResult {
    let known = Known::gather()?;
    let (books, problems) = notebook_problems(&known, false)?;
    assert!(
        books >= known.lesson.len(),
        "{books} Chinese notebooks in notebooks/zh for {} lessons",
        known.lesson.len()
    );
    assert!(
        problems.is_empty(),
        "{}",
        report("notebook output lines", &problems)
    );
    Ok(())
}

/// The notebooks' Markdown is the lessons' prose (`tests/i18n.rs` checks it at the source);
/// here it is read as the notebook shows it, code blocks and `$math$` left out.
#[test]
fn no_english_in_a_chinese_notebook_s_prose() -> TestResult {
    let known = Known::gather()?;
    let (books, problems) = notebook_problems(&known, true)?;
    assert!(books >= known.lesson.len(), "{books} Chinese notebooks");
    assert!(
        problems.is_empty(),
        "{}",
        report("notebook prose lines", &problems)
    );
    Ok(())
}

#[test]
fn the_checks_find_english_and_pass_code_names_and_glosses() -> TestResult {
    let known = Known::gather()?;
    // Interface English is found, in a cell and in a notebook line.
    assert_eq!(known.english("j / k, wheel    滚动讲解", None), ["wheel"]);
    assert_eq!(
        known.english(
            "probs (447, 2) float32   均值 0.50 · mean 0.50 · 9 positive",
            None
        ),
        ["mean", "positive"]
    );
    assert_eq!(
        known.english("第 2 轮报错 “Trying to backward”", None),
        ["Trying", "to", "backward"]
    );
    // Code, identifiers of the lesson, glosses, assignments, formulas, keys pass.
    assert!(known.is_code("critic_loss = torch.mean(F.mse_loss(self.critic(states), td_tar…"));
    for fine in [
        "近端策略优化（Proximal Policy Optimization，PPO）是一种",
        "（Proximal Policy",
        "Optimization，PPO）是一种强化学习算法",
        "bootstrap_on_truncation = false",
        "bootstrap_on_truncation  false",
        "∇log π 加权，|r − 1|，m̂ = g",
        "←/→ 翻页  l 课程  q 退出  L English  Esc 关闭",
        "clipped (29, 1) bool  29 个中 0 个为 True",
        "05/18 PolicyNet 与 ValueN…",
        "dones = [true, true, false], gamma = 0.98",
        "最后一步：done = true，V(s') = 4.05",
        "因为 done = term or trunc 为 1",
        "critic_epochs: None,",
        "6. for e in 0..E：kl = (1/N)，用 f32 求和",
        "用 f32 计算：let var = σ * σ; total += 1",
        "y[t] = r[t] * (if d[t] { 0.0 } else { 1.0 })，用 f32 计算。",
        "carry = delta + gamma * lmbda * (1 − d) * carry; adv[t] = carry",
    ] {
        assert_eq!(
            known.english(fine, Some("05-networks")),
            Vec::<String>::new(),
            "{fine}"
        );
    }
    for (html, words) in [
        (
            "<pre>panic：   <code>not yet implemented</code></pre>",
            vec!["panic"],
        ),
        (
            "<pre>panic：   not yet implemented</pre>",
            vec!["panic", "not", "yet", "implemented"],
        ),
        (
            // (`advantage` is a live value's name.)
            "<td title=\"positive advantage\">0.1</td>",
            vec!["positive"],
        ),
    ] {
        assert_eq!(known.english(&visible_text(html), None), words, "{html}");
    }
    // An identifier is allowed only on the screens of a lesson whose prose uses it.
    assert!(
        known
            .english("所以 detach 可不是", Some("09-ratio"))
            .is_empty()
    );
    assert_eq!(known.english("所以 detach 可不是", None), ["detach"]);
    Ok(())
}
