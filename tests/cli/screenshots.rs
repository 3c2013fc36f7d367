//! `dev screenshots`: the READMEs' pictures are the app's own screens as it draws them now.
//! Each is drawn again through the library, as the command draws it (a real training run, a
//! real grading, the bundled fonts), and compared pixel for pixel with the committed file,
//! as the insta snapshots of `tests/tui.rs` are for the screens' text.

use std::path::Path;

use ppo_tutor::i18n::Lang;
use ppo_tutor::screenshot::{self, Picture, REGENERATE};

type TestResult = Result<(), Box<dyn std::error::Error>>;

const ROOT: &str = env!("CARGO_MANIFEST_DIR");

#[test]
fn the_committed_pictures_are_the_screens_the_app_draws_now() -> TestResult {
    let root = Path::new(ROOT);
    let drawn = screenshot::draw_all(root)?;
    assert_eq!(drawn.len(), Picture::all().len());
    // Each language's pictures show that language's screens.
    for d in &drawn {
        let chinese = d
            .buffer
            .content
            .iter()
            .filter(|c| {
                c.symbol()
                    .chars()
                    .any(|c| ('\u{4e00}'..='\u{9fff}').contains(&c))
            })
            .count();
        let path = d.picture.path();
        match d.picture.lang {
            // The key bar's `L 中文` and nothing more.
            Lang::En => assert!(chinese <= 2, "{path}: {chinese} Chinese cells"),
            Lang::Zh => assert!(chinese > 300, "{path}: {chinese} Chinese cells"),
        }
    }
    let stale = screenshot::stale(root, &drawn);
    assert!(
        stale.is_empty(),
        "{}\nThe app's screens changed: redraw the pictures with `{REGENERATE}`, look at them, \
         and commit them.",
        stale.join("\n")
    );
    Ok(())
}

#[test]
fn each_readme_shows_the_pictures_of_its_language() -> TestResult {
    for (readme, lang) in [("README.md", Lang::En), ("README.zh-CN.md", Lang::Zh)] {
        let text = std::fs::read_to_string(Path::new(ROOT).join(readme))?;
        for picture in Picture::all() {
            let shown = text.contains(&format!("]({})", picture.path()));
            assert_eq!(
                shown,
                picture.lang == lang,
                "{readme} and {}: each README shows its own language's pictures",
                picture.path()
            );
        }
    }
    Ok(())
}
