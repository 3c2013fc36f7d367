//! Drawing cost of the terminal app's screens at 160×50 (in English, and in Chinese, whose
//! lines the app wraps itself between characters), and input-to-frame latency (key →
//! `App::update` → full redraw) while a training worker runs on another thread.
//! Target: under 2 ms per frame. Run: `cargo bench --bench tui`.

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

use criterion::{Criterion, criterion_group, criterion_main};
use ppo_tutor::i18n::Lang;
use ppo_tutor::lesson::{Course, Progress, Session};
use ppo_tutor::ppo::{PpoConfig, Trainer};
use ppo_tutor::tui::app::App;
use ppo_tutor::tui::keys::Action;
use ppo_tutor::tui::theme::Theme;
use ppo_tutor::tui::ui::View;
use ratatui::Terminal;
use ratatui::backend::TestBackend;

fn app_at(lesson: &str, step: usize) -> Option<App> {
    let course = Course::embedded().ok()?;
    let progress = Progress {
        lesson: lesson.into(),
        step,
        ..Progress::default()
    };
    let mut app = App::new(course, progress, None);
    // A long episode's batch: the heaviest tensors and clip charts.
    app.show(Session::run(PpoConfig::default(), 0, 120).ok()?);
    Some(app)
}

#[allow(irrefutable_let_patterns)] // TestBackend never fails
fn draw(c: &mut Criterion) {
    let theme = Theme { color: true };
    for (name, lesson, step) in [
        ("clip_chart", "clipping", 3),
        ("plot", "training", 1),
        ("tensors", "ratio", 2),
    ] {
        let Some(app) = app_at(lesson, step) else {
            return;
        };
        let Ok(mut terminal) = Terminal::new(TestBackend::new(160, 50)) else {
            return;
        };
        c.bench_function(&format!("draw_{name}_160x50"), |b| {
            b.iter(|| {
                terminal
                    .draw(|f| f.render_widget(&View { app: &app, theme }, f.area()))
                    .map(|_| ())
            });
        });
    }
}

#[allow(irrefutable_let_patterns)]
fn latency_while_training(c: &mut Criterion) {
    let Some(mut app) = app_at("clipping", 3) else {
        return;
    };
    let Ok(mut terminal) = Terminal::new(TestBackend::new(160, 50)) else {
        return;
    };
    let stop = Arc::new(AtomicBool::new(false));
    let flag = Arc::clone(&stop);
    let worker = std::thread::spawn(move || {
        let Ok(mut trainer) = Trainer::new(
            PpoConfig {
                num_episodes: 100_000,
                ..PpoConfig::default()
            },
            1,
        ) else {
            return;
        };
        while !flag.load(Ordering::Relaxed) {
            if !matches!(trainer.next_episode(), Ok(Some(_))) {
                return;
            }
        }
    });
    let theme = Theme { color: true };
    let mut forward = true;
    c.bench_function("key_to_frame_while_training_160x50", |b| {
        b.iter(|| {
            app.update(if forward { Action::Next } else { Action::Prev });
            forward = !forward;
            terminal
                .draw(|f| f.render_widget(&View { app: &app, theme }, f.area()))
                .map(|_| ())
        });
    });
    stop.store(true, Ordering::Relaxed);
    let _ = worker.join();
}

/// The longest Chinese text screens: a step's prose wrapped by the app, and the quiz.
#[allow(irrefutable_let_patterns)] // TestBackend never fails
fn draw_chinese(c: &mut Criterion) {
    let _zh = Lang::Zh.scoped();
    let theme = Theme { color: true };
    for (name, lesson, step) in [("text_zh", "what-is-ppo", 0), ("tensors_zh", "gae", 1)] {
        let Some(app) = app_at(lesson, step) else {
            return;
        };
        let Ok(mut terminal) = Terminal::new(TestBackend::new(160, 50)) else {
            return;
        };
        c.bench_function(&format!("draw_{name}_160x50"), |b| {
            b.iter(|| {
                terminal
                    .draw(|f| f.render_widget(&View { app: &app, theme }, f.area()))
                    .map(|_| ())
            });
        });
    }
}

criterion_group!(benches, draw, draw_chinese, latency_while_training);
criterion_main!(benches);
