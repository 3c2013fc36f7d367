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
    ("td_target", &["td_target"]),
    ("td_delta", &["td_delta"]),
    ("compute_advantage", &["advantage"]),
    ("log_prob_of_actions", &["old_log_probs", "log_probs"]),
    ("ratio", &["ratio"]),
    ("actor_loss", &["surr1", "surr2", "actor_loss"]),
    ("zero_gradient_rows", &["surr1", "surr2"]),
    ("critic_loss", &["critic_loss"]),
    ("ppo_losses", &["actor_loss", "critic_loss"]),
    ("approx_kl", &["approx_kl"]),
    ("clip_fraction", &["clip_frac", "clipped"]),
    ("moving_average", &["moving_average"]),
    ("td_target_truncation", &["td_target"]),
    ("gae_rollout", &["advantage"]),
    ("normalize_advantage", &["advantage"]),
    ("gaussian_log_prob", &["old_log_probs", "log_probs"]),
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
