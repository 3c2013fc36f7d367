//! The notebooks' recipes (`notebooks/src/NN-slug.rs`) and saved files (`notebooks/*.ipynb`),
//! checked without a kernel.
//!
//! - No cell before a recipe's `// %% exercise` marker computes what the lesson's exercise
//!   asks the learner to write.
//! - No two code cells of a saved notebook show the same output. This one reads the
//!   committed notebooks, so after a change to the generator or a recipe it holds only once
//!   the notebooks are regenerated (`cargo run --features notebook-runner -- dev notebooks`).

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use ppo_tutor::generator::build;
use ppo_tutor::lesson::Course;
use serde_json::Value;

type TestResult = Result<(), Box<dyn std::error::Error>>;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// The live values each exercise computes (its output and the intermediates the seed names
/// on the way): a cell before the exercise that computes one of these itself gives the
/// exercise away. Every exercise of the course must be listed.
const SPOILS: &[(&str, &[&str])] = &[
    ("sample_action", &["actions"]),
    ("n_step_target", &["n_step_target"]),
    ("compute_advantage", &["advantage"]),
    ("importance_weighted_mean", &["weighted_mean"]),
    ("categorical_kl", &["categorical_kl"]),
    ("zero_gradient_rows", &["surr1", "surr2"]),
    ("clipped_value_loss", &["v_clipped", "value_loss"]),
    ("ppo_losses", &["actor_loss", "critic_loss"]),
    ("reverse_kl", &[]),
    ("kl_early_stop", &["stopped_at", "early_stop"]),
    ("td_target_truncation", &["td_target"]),
    ("gae_rollout", &["advantage"]),
    ("diag_gaussian_log_prob", &["old_log_probs", "log_probs"]),
];

/// The code of a recipe before its `// %% exercise` marker (the header and markers
/// included), or `None` without a marker.
fn before_exercise(recipe: &str) -> Option<String> {
    let mut out = String::new();
    for line in recipe.lines() {
        if line
            .strip_prefix("// %%")
            .is_some_and(|m| m.trim() == "exercise")
        {
            return Some(out);
        }
        out.push_str(line);
        out.push('\n');
    }
    None
}

/// How a line before the exercise gives away `name`, an exercise or one of its values, if
/// it does:
/// - `// check: NAME ...` declares that the cell computes NAME itself (`tests/notebooks.rs`
///   compares it with the library's);
/// - `TensorView::column("NAME", ...)` (or any `TensorView` constructor) shows a computed
///   tensor under that name;
/// - `fn NAME(` defines the function the learner is to write.
fn gives_away(line: &str, name: &str) -> Option<&'static str> {
    let trimmed = line.trim();
    if trimmed
        .strip_prefix("// check:")
        .and_then(|rest| rest.split_whitespace().next())
        == Some(name)
    {
        return Some("checks its own computation of");
    }
    if trimmed.contains("TensorView::") && trimmed.contains(&format!("(\"{name}\"")) {
        return Some("shows its own computation of");
    }
    if trimmed.contains(&format!("fn {name}(")) || trimmed.contains(&format!("fn {name}<")) {
        return Some("defines");
    }
    None
}

/// A check cell is where a notebook computes a live value itself and compares it with the
/// library's. Before the exercise, such a cell (or a table, or a function) of what the
/// exercise computes would solve it in plain sight: those computations come from the
/// library there (`trace.td_target`, `ppo_tutor::ppo::compute_advantage`, ...), or after the
/// exercise.
#[test]
fn no_cell_before_the_exercise_computes_it() -> TestResult {
    let course = Course::embedded()?;
    let spoils: BTreeMap<&str, &[&str]> = SPOILS.iter().copied().collect();
    let folders = build::recipe_folders(&root(), &course)?;
    let mut problems = Vec::new();
    for (lesson, folder) in course.lessons.iter().zip(&folders) {
        let Some(exercise) = &lesson.exercise else {
            continue;
        };
        let file = format!("notebooks/src/{folder}.rs");
        let recipe = std::fs::read_to_string(root().join(&file))?;
        let Some(before) = before_exercise(&recipe) else {
            problems.push(format!("{file}: no `// %% exercise` marker"));
            continue;
        };
        for name in exercise.names() {
            let values = spoils.get(name).ok_or_else(|| {
                format!(
                    "tests/recipes.rs: add exercise `{name}` and the values it computes to SPOILS"
                )
            })?;
            let targets: std::collections::BTreeSet<&str> = std::iter::once(name)
                .chain(values.iter().copied())
                .collect();
            for target in targets {
                for (i, line) in before.lines().enumerate() {
                    if let Some(how) = gives_away(line, target) {
                        problems.push(format!(
                            "{file}:{}: before `// %% exercise`, a cell {how} `{target}`, \
                             which the exercise `{name}` computes; take it from the library \
                             or move the cell after the exercise",
                            i + 1
                        ));
                    }
                }
            }
        }
    }
    assert!(problems.is_empty(), "{}", problems.join("\n"));
    Ok(())
}

#[test]
fn the_spoiler_check_sees_each_way_of_giving_an_exercise_away() {
    let recipe = "// %%\nlet a = 1;\n// %% step: S\n// check: td_target after 30 episodes\n\
                  TensorView::column(\"advantage\", &adv)\nfn compute_advantage(g: f32) {}\n\
                  // %% exercise\n// check: ratio after 30 episodes\n";
    let before = before_exercise(recipe).unwrap_or_default();
    let hits = |name: &str| before.lines().filter_map(|l| gives_away(l, name)).count();
    assert_eq!(hits("td_target"), 1);
    assert_eq!(hits("advantage"), 1);
    assert_eq!(hits("compute_advantage"), 1);
    // After the marker, and for reads of the library's values, nothing.
    assert_eq!(hits("ratio"), 0);
    assert_eq!(
        gives_away("let d = trace.td_delta.clone();", "td_delta"),
        None
    );
    assert_eq!(
        gives_away("// check: td_target_x after 3", "td_target"),
        None
    );
    assert_eq!(before_exercise("// %%\nx\n"), None);
}

/// A code cell's outputs without what differs between runs of identical content (the
/// execution count).
fn output_key(cell: &Value) -> Option<String> {
    let outputs = cell.get("outputs")?.as_array()?;
    if outputs.is_empty() {
        return None;
    }
    let stripped: Vec<Value> = outputs
        .iter()
        .map(|o| {
            let mut o = o.clone();
            if let Some(map) = o.as_object_mut() {
                map.remove("execution_count");
            }
            o
        })
        .collect();
    serde_json::to_string(&stripped).ok()
}

/// The cells of the saved notebook `path` whose outputs repeat an earlier cell's, as
/// `(earlier, later)` cell indices.
fn repeated_outputs(path: &Path) -> Result<Vec<(usize, usize)>, Box<dyn std::error::Error>> {
    let nb: Value = serde_json::from_str(&std::fs::read_to_string(path)?)?;
    let cells = nb
        .get("cells")
        .and_then(Value::as_array)
        .ok_or("a notebook without cells")?;
    let mut seen: BTreeMap<String, usize> = BTreeMap::new();
    let mut repeats = Vec::new();
    for (i, cell) in cells.iter().enumerate() {
        if cell.get("cell_type").and_then(Value::as_str) != Some("code") {
            continue;
        }
        let Some(key) = output_key(cell) else {
            continue;
        };
        if let Some(&first) = seen.get(&key) {
            repeats.push((first, i));
        } else {
            seen.insert(key, i);
        }
    }
    Ok(repeats)
}

/// Each output says something new: the generator shows a live value or a picture once per
/// notebook, and recipes print different things.
///
/// NOTE: this reads the committed notebooks; after a change to the generator it passes
/// only once they are regenerated (`cargo run --features notebook-runner -- dev notebooks`).
#[test]
fn no_saved_notebook_repeats_an_output() -> TestResult {
    let course = Course::embedded()?;
    let mut problems = Vec::new();
    for lesson in &course.lessons {
        let file = format!("notebooks/{}.ipynb", build::folder(lesson));
        for (first, again) in repeated_outputs(&root().join(&file))? {
            problems.push(format!(
                "{file}: cell {again} shows the same output as cell {first}"
            ));
        }
    }
    assert!(
        problems.is_empty(),
        "{}\n(regenerate the notebooks: {})",
        problems.join("\n"),
        build::REGENERATE
    );
    Ok(())
}

/// Each notebook folder names evcxr's work folder (`evcxr.toml`), so a fresh kernel reuses
/// the last kernel's build of the engine instead of rebuilding it: a hidden folder inside
/// the notebook folder, one per language (the notebook test runs the two languages side by
/// side, and two kernels building in one folder at once would overwrite each other's
/// cells), ignored by git and outside the workspace. The path has no `..`: evcxr takes
/// the work folder's path as written, and its cache (`:cache`) recognises a compiled
/// dependency from another folder only when that path is the one cargo reports.
#[test]
fn each_notebook_folder_builds_in_its_own_hidden_folder() -> TestResult {
    let mut seen = Vec::new();
    for dir in [
        root().join("notebooks"),
        root().join("notebooks").join("zh"),
    ] {
        let work = build::work_folder(&dir)?;
        let inside = work.strip_prefix(&dir)?;
        let parts: Vec<_> = inside.components().collect();
        assert!(
            parts.len() == 1
                && matches!(parts[0], std::path::Component::Normal(p)
                    if p.to_str().is_some_and(|p| p.starts_with('.'))),
            "{}/evcxr.toml: tmpdir {} must be one hidden folder inside this folder",
            dir.display(),
            inside.display()
        );
        let abs = std::fs::canonicalize(&dir)?.join(inside);
        assert!(
            !seen.contains(&abs),
            "{}/evcxr.toml: tmpdir {} is another notebook folder's",
            dir.display(),
            abs.display()
        );
        seen.push(abs);
        let name = inside.display().to_string();
        let ignored = std::fs::read_to_string(root().join(".gitignore"))?;
        assert!(
            ignored.lines().any(|l| l.trim() == format!("{name}/")),
            ".gitignore must ignore {name}/, evcxr's work folder"
        );
    }
    let manifest: toml::Table = std::fs::read_to_string(root().join("Cargo.toml"))?.parse()?;
    let excluded = manifest
        .get("workspace")
        .and_then(|w| w.get("exclude"))
        .and_then(toml::Value::as_array)
        .is_some_and(|e| e.iter().any(|v| v.as_str() == Some("notebooks")));
    assert!(
        excluded,
        "Cargo.toml: [workspace] exclude must list \"notebooks\", or cargo refuses to build \
         evcxr's work crate inside the workspace"
    );
    Ok(())
}

// ---------------------------------------------------------------------------------------
// No answer on screen before the learner earns it: the code each
// exercise gives away (its `reveals` anchors in `exercise.toml`, and its reference solution)
// shows in no code pane before the exercise is passed, and in no notebook cell before the
// exercise's cells; after a pass, it shows.

use ppo_tutor::i18n::Lang;
use ppo_tutor::lesson::{anchor, reveal};

/// A line of code as the spoiler check compares it: no comment after `//`, no whitespace.
fn normalised(line: &str) -> String {
    let code = line.split("//").next().unwrap_or("");
    code.chars().filter(|c| !c.is_whitespace()).collect()
}

/// A block of code as the spoiler check compares it: each line [`normalised`], joined.
fn normalised_block(text: &str) -> String {
    text.lines().map(normalised).collect()
}

/// Whether a normalised line says enough to give something away: it computes something
/// (an operator, or a call such as `exp`, `clamp` or `gather`) and is not short. Lines such
/// as `}`, `.collect()`, `.zip(values)` or `let mut total = 0.0_f32;` say nothing of the
/// answer.
fn telling(line: &str) -> bool {
    const CALLS: [&str; 10] = [
        "exp",
        "ln(",
        "log",
        "clamp",
        "min",
        "max",
        "gather",
        "sqrt",
        "cumulative",
        "abs",
    ];
    line.chars().count() >= 18
        && (line.contains(['+', '-', '*', '/', '<', '>']) || CALLS.iter().any(|c| line.contains(c)))
}

/// The body of `fn name` in the Rust source `text`: the lines after its signature up to
/// the closing brace at the start of a line.
fn fn_body(text: &str, name: &str) -> Vec<String> {
    let sig = format!("fn {name}(");
    text.lines()
        .skip_while(|l| !l.contains(&sig))
        .skip_while(|l| !l.trim_end().ends_with('{'))
        .skip(1)
        .take_while(|l| !l.starts_with('}'))
        .map(str::to_string)
        .collect()
}

/// What exercise `name` gives away: the normalised telling lines of the anchors it declares
/// in `exercise.toml` and of the body of its reference solution, and each declared anchor
/// whole (normalised as one block).
struct Answer {
    lines: Vec<String>,
    blocks: Vec<String>,
}

fn answer_lines(name: &str) -> Result<Answer, Box<dyn std::error::Error>> {
    let (_, regions) = reveal::exercises()
        .iter()
        .find(|(g, _)| g.exercise == name)
        .ok_or_else(|| format!("{name}: not in any exercise.toml"))?;
    let mut lines: Vec<String> = Vec::new();
    let mut blocks = Vec::new();
    for region in regions {
        let (_, code) = anchor::find(region).ok_or_else(|| format!("no anchor {region}"))?;
        lines.extend(code.lines().map(normalised));
        blocks.push(normalised_block(&code));
    }
    let meta = ppo_tutor::grade::find(name)?.meta();
    let file = format!("lessons/{}/{}", meta.lesson, meta.solution);
    let solution = std::fs::read_to_string(root().join(&file))?;
    let body = fn_body(&solution, name);
    if body.is_empty() {
        return Err(format!("{file}: no `fn {name}(`").into());
    }
    lines.extend(body.iter().map(|l| normalised(l)));
    lines.retain(|l| telling(l));
    lines.sort();
    lines.dedup();
    blocks.sort();
    blocks.dedup();
    Ok(Answer { lines, blocks })
}

/// How `text` gives away `answer`: each line equal to one of its lines once normalised, or
/// holding a long one (a line of the answer inside a longer line); and each declared anchor
/// found whole.
fn spoiled(text: &str, answer: &Answer) -> Vec<String> {
    let mut hits = Vec::new();
    for line in text.lines() {
        let n = normalised(line);
        if let Some(a) = answer
            .lines
            .iter()
            .find(|a| n == **a || (a.chars().count() >= 24 && n.contains(a.as_str())))
        {
            hits.push(format!("{} (the answer's `{a}`)", line.trim()));
        }
    }
    let whole = normalised_block(text);
    for block in &answer.blocks {
        if whole.contains(block.as_str()) {
            hits.push(format!("the whole of `{block}`"));
        }
    }
    hits
}

/// Every exercise of the course, in course order, with its lesson's order.
fn exercises_in_order() -> Vec<(String, u32)> {
    reveal::exercises()
        .iter()
        .map(|(g, _)| (g.exercise.clone(), g.lesson))
        .collect()
}

/// Each code pane and each `ppo-tutor show` of a step, in both languages, for a learner who
/// has passed the exercises for which `passed` holds: `(where, text)`.
fn app_panes(
    passed: &dyn Fn(&str) -> bool,
) -> Result<Vec<(String, String)>, Box<dyn std::error::Error>> {
    let mut panes = Vec::new();
    for lang in Lang::ALL {
        let _lang = lang.scoped();
        let course = Course::embedded()?;
        for (i, lesson) in course.lessons.iter().enumerate() {
            for k in 0..lesson.steps.len() {
                let at = format!("{} {} step {}", lang.code(), build::folder(lesson), k + 1);
                let pane = ppo_tutor::tui::ui::code_pane_text(lesson, k, passed);
                panes.push((format!("{at}, code pane"), pane));
                let shown = ppo_tutor::cli::lessons::render_step(
                    &course,
                    i,
                    k,
                    &ppo_tutor::lesson::Snapshot::default(),
                    passed,
                );
                panes.push((format!("{at}, ppo-tutor show"), shown));
            }
        }
    }
    Ok(panes)
}

/// The code of each exercise shows in no code pane of the app (and no `ppo-tutor show`)
/// while it is not passed: with an empty progress file, every step of the course in both
/// languages, each exercise's declared code and reference solution, line by line.
#[test]
fn no_step_of_the_app_shows_an_answer_before_its_pass() -> TestResult {
    let panes = app_panes(&|_| false)?;
    let mut problems = Vec::new();
    for (name, _) in exercises_in_order() {
        let answers = answer_lines(&name)?;
        for (at, text) in &panes {
            for hit in spoiled(text, &answers) {
                problems.push(format!("{at}: shows `{name}`'s answer: {hit}"));
            }
        }
    }
    assert!(
        problems.is_empty(),
        "{}\n(wrap the lines in a nested anchor and list it under `reveals` in the \
         exercise's exercise.toml)",
        problems.join("\n")
    );
    Ok(())
}

/// The check above can fail: without the gate (every anchor shown whole), it finds the
/// answer of every exercise that declares code in some step of the course.
#[test]
fn the_app_spoiler_check_finds_every_declared_answer_when_nothing_is_hidden() -> TestResult {
    let course = Course::embedded_in(Lang::En)?;
    let whole: Vec<String> = course
        .lessons
        .iter()
        .flat_map(|l| &l.steps)
        .filter_map(|s| anchor::find(&s.code).map(|(_, code)| code))
        .collect();
    for (gate, regions) in reveal::exercises() {
        if regions.is_empty() {
            continue;
        }
        let answers = answer_lines(&gate.exercise)?;
        assert!(
            whole.iter().any(|code| !spoiled(code, &answers).is_empty()),
            "{}: no step shows its declared code {regions:?} even ungated",
            gate.exercise
        );
    }
    Ok(())
}

/// After a pass the crate's version shows: with every exercise passed no pane holds a note,
/// every declared region's code is in some step's pane, and each step of the exercise's
/// lesson that shows it points to the learner's own file.
#[test]
fn after_a_pass_the_crate_s_version_shows() -> TestResult {
    let all = exercises_in_order();
    let passed = |e: &str| all.iter().any(|(n, _)| n == e);
    let panes = app_panes(&passed)?;
    for (at, text) in &panes {
        assert!(
            !text.contains("to see the crate's version") && !text.contains("本库的写法"),
            "{at}: a note with every exercise passed:\n{text}"
        );
    }
    let joined: String = panes.iter().map(|(_, t)| normalised_block(t)).collect();
    for (gate, regions) in reveal::exercises() {
        for region in regions {
            let (_, code) = anchor::find(region).ok_or("no anchor")?;
            assert!(
                joined.contains(&normalised_block(&code)),
                "{}: `{region}` shows in no step after the pass",
                gate.exercise
            );
        }
    }
    // One exercise at a time: passing `compute_advantage` alone opens its lines and names
    // the file.
    let _en = Lang::En.scoped();
    let course = Course::embedded()?;
    let lesson = course.get("gae").ok_or("no gae")?;
    let k = lesson
        .steps
        .iter()
        .position(|s| s.code == "compute_advantage")
        .ok_or("no compute_advantage step")?;
    let before = ppo_tutor::tui::ui::code_pane_text(lesson, k, &|_| false);
    let after = ppo_tutor::tui::ui::code_pane_text(lesson, k, &|e| e == "compute_advantage");
    assert!(
        before.contains("solve exercise `compute_advantage` (lesson 8)"),
        "{before}"
    );
    assert!(!before.contains("adv = coef * adv + delta"), "{before}");
    assert!(after.contains("adv = coef * adv + delta"), "{after}");
    assert!(
        after.contains("// your compute_advantage: lessons/08-gae/exercise.rs"),
        "{after}"
    );
    Ok(())
}

/// The cells of `lesson`'s notebook (current language), split where its exercise begins:
/// before it, and from it on (empty without an exercise).
fn notebook_halves(
    lesson: &ppo_tutor::lesson::Lesson,
) -> Result<(Vec<build::Cell>, Vec<build::Cell>), Box<dyn std::error::Error>> {
    let cells = build::notebook_cells(&root(), lesson)?;
    let exercise = build::exercise_code_cells(&root(), lesson)?;
    let Some(first) = exercise.first() else {
        return Ok((cells, Vec::new()));
    };
    let at = cells
        .iter()
        .position(|c| matches!(c, build::Cell::Code(code) if code == first))
        .ok_or("the exercise's starter is not in the notebook")?;
    // The exercise's own markdown (its title and hints) comes just before the starter.
    let at = at.saturating_sub(1);
    let after = cells[at..].to_vec();
    let mut before = cells;
    before.truncate(at);
    Ok((before, after))
}

fn cell_text(cell: &build::Cell) -> &str {
    match cell {
        build::Cell::Markdown(t) | build::Cell::Code(t) => t,
    }
}

/// No notebook cell, markdown or code, before a lesson's exercise shows that exercise's
/// answer, and no cell of an earlier lesson's notebook shows it at all; in both languages.
#[test]
fn no_notebook_cell_shows_an_answer_before_its_exercise() -> TestResult {
    let exercises = exercises_in_order();
    let mut problems = Vec::new();
    for lang in Lang::ALL {
        let _lang = lang.scoped();
        let course = Course::embedded()?;
        for lesson in &course.lessons {
            let (before, after) = notebook_halves(lesson)?;
            let file = build::notebook_file(&build::folder(lesson));
            for (name, order) in &exercises {
                let cells: Vec<&build::Cell> = match (*order).cmp(&lesson.order) {
                    std::cmp::Ordering::Less => continue,
                    std::cmp::Ordering::Equal => before.iter().collect(),
                    std::cmp::Ordering::Greater => before.iter().chain(&after).collect(),
                };
                let answers = answer_lines(name)?;
                for (i, cell) in cells.into_iter().enumerate() {
                    for hit in spoiled(cell_text(cell), &answers) {
                        problems.push(format!("{file}, cell {i}: shows `{name}`'s answer: {hit}"));
                    }
                }
            }
        }
    }
    assert!(problems.is_empty(), "{}", problems.join("\n"));
    Ok(())
}

/// After its exercise's grading cells, a notebook shows the crate's version: every region
/// its exercises declare that no later exercise also declares, in both languages.
#[test]
fn a_notebook_shows_the_crate_s_version_after_the_exercise() -> TestResult {
    for lang in Lang::ALL {
        let _lang = lang.scoped();
        let course = Course::embedded()?;
        for lesson in &course.lessons {
            let Some(ex) = &lesson.exercise else { continue };
            let (_, after) = notebook_halves(lesson)?;
            let file = build::notebook_file(&build::folder(lesson));
            let last_grade = after
                .iter()
                .rposition(
                    |c| matches!(c, build::Cell::Code(code) if code.starts_with("ppo_grade::")),
                )
                .ok_or("no grading cell")?;
            let shown: String = after[last_grade..]
                .iter()
                .filter(|c| matches!(c, build::Cell::Markdown(_)))
                .map(|c| normalised_block(cell_text(c)))
                .collect();
            for (gate, regions) in reveal::exercises() {
                if !ex.names().contains(&gate.exercise.as_str()) {
                    continue;
                }
                for region in regions {
                    if reveal::gates_of(region)
                        .iter()
                        .any(|g| g.lesson > lesson.order)
                    {
                        continue;
                    }
                    // A region that no step of the course up to here shows needs no reveal.
                    let seen = course
                        .lessons
                        .iter()
                        .filter(|l| l.order <= lesson.order)
                        .flat_map(|l| &l.steps)
                        .any(|s| s.code == *region || anchor::nested(&s.code).contains(region));
                    if !seen {
                        continue;
                    }
                    let (_, code) = anchor::find(region).ok_or("no anchor")?;
                    assert!(
                        shown.contains(&normalised_block(&code)),
                        "{file}: `{region}` ({}) does not show after the grading cells",
                        gate.exercise
                    );
                }
            }
        }
    }
    Ok(())
}
