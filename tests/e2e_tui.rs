//! End to end: the real binary in a pseudo-terminal (portable-pty), its screen parsed
//! with a vt100 emulator. Walks every step of every lesson, trains, opens help, quits.

use std::io::{Read, Write};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use portable_pty::{CommandBuilder, PtySize, native_pty_system};
use ppo_tutor::lesson::Course;
use ppo_tutor::lesson::quiz::{QuestionKind, letter_of};

type TestResult = Result<(), Box<dyn std::error::Error>>;

struct Screen {
    parser: Arc<Mutex<vt100::Parser>>,
}

impl Screen {
    fn text(&self) -> String {
        self.parser
            .lock()
            .map(|p| p.screen().contents())
            .unwrap_or_default()
    }

    /// Waits until the screen contains `needle` (or times out with the screen in the error).
    fn wait_for(&self, needle: &str, secs: u64) -> Result<String, String> {
        let deadline = Instant::now() + Duration::from_secs(secs);
        loop {
            let text = self.text();
            if text.contains(needle) {
                return Ok(text);
            }
            if Instant::now() > deadline {
                return Err(format!("timed out waiting for {needle:?}; screen:\n{text}"));
            }
            std::thread::sleep(Duration::from_millis(20));
        }
    }
}

/// The episode count in the header (`episode N · ...`), 0 if absent.
fn episode_on(text: &str) -> usize {
    text.split("episode ")
        .filter_map(|rest| rest.split_whitespace().next()?.parse().ok())
        .max()
        .unwrap_or(0)
}

#[test]
fn walk_the_whole_course_in_a_real_terminal() -> TestResult {
    let course = Course::embedded()?;
    let dir = tempfile::tempdir()?;
    let pty = native_pty_system().openpty(PtySize {
        rows: 50,
        cols: 160,
        pixel_width: 0,
        pixel_height: 0,
    })?;
    let mut cmd = CommandBuilder::new(env!("CARGO_BIN_EXE_ppo-tutor"));
    cmd.env("PPO_TUTOR_STATE", dir.path().join("state.json"));
    cmd.env("TERM", "xterm-256color");
    cmd.cwd(dir.path());
    let mut child = pty.slave.spawn_command(cmd)?;
    drop(pty.slave);
    let parser = Arc::new(Mutex::new(vt100::Parser::new(50, 160, 0)));
    let mut reader = pty.master.try_clone_reader()?;
    let sink = Arc::clone(&parser);
    std::thread::spawn(move || {
        let mut buf = [0_u8; 8192];
        while let Ok(n) = reader.read(&mut buf) {
            if n == 0 {
                break;
            }
            if let Ok(mut p) = sink.lock() {
                p.process(&buf[..n]);
            }
        }
    });
    let mut writer = pty.master.take_writer()?;
    let screen = Screen { parser };
    let mut key = |bytes: &[u8]| -> std::io::Result<()> {
        writer.write_all(bytes)?;
        writer.flush()?;
        std::thread::sleep(Duration::from_millis(15));
        Ok(())
    };

    screen.wait_for(&course.lessons[0].title, 30)?;
    screen.wait_for("episode 1 ·", 30)?; // the first episode arrives from the worker
    for lesson in &course.lessons {
        for (i, step) in lesson.steps.iter().enumerate() {
            let header = format!("{} · step {}/{}", lesson.title, i + 1, lesson.steps.len());
            let text = screen.wait_for(&header, 10)?;
            let short: String = step.title.chars().take(20).collect();
            assert!(
                text.contains(&short),
                "step title {short:?} not on screen:\n{text}"
            );
            key(b"\x1b[C")?; // →
        }
        // After the last step come the lesson's questions; the first lesson's first one is
        // answered with its letter, the others skipped with →.
        for (i, question) in lesson.quiz.iter().enumerate() {
            let header = format!("question {}/{}", i + 1, lesson.quiz.len());
            screen.wait_for(&header, 10)?;
            if let (0, QuestionKind::Choice { answer, .. }) = (i, &question.kind)
                && lesson.order == 1
            {
                key(letter_of(*answer).to_string().as_bytes())?;
                screen.wait_for("✓ Right", 10)?;
            }
            key(b"\x1b[C")?; // →
        }
    }
    // One more episode than the screen shows: the walk ends in a Pendulum lesson, whose run
    // started fresh (episode 0) when the walk entered the first Pendulum lesson.
    let before = episode_on(&screen.text());
    key(b"e")?;
    screen.wait_for(&format!("episode {} ·", before + 1), 30)?;
    key(b"t")?;
    screen.wait_for("training", 10)?;
    // Training runs on the worker: the header's episode counter must climb.
    let deadline = Instant::now() + Duration::from_secs(60);
    while episode_on(&screen.text()) < 10 {
        if Instant::now() > deadline {
            return Err(format!("training did not advance:\n{}", screen.text()).into());
        }
        std::thread::sleep(Duration::from_millis(50));
    }
    key(b"t")?;
    key(b"?")?;
    screen.wait_for("keys (Esc closes)", 10)?;
    key(b"\x1b")?;
    key(b"q")?;
    let deadline = Instant::now() + Duration::from_secs(20);
    let status = loop {
        if let Some(status) = child.try_wait()? {
            break status;
        }
        if Instant::now() > deadline {
            child.kill()?;
            return Err("ppo-tutor did not exit after q".into());
        }
        std::thread::sleep(Duration::from_millis(50));
    };
    assert!(status.success(), "exit status {status:?}");
    let saved = std::fs::read_to_string(dir.path().join("state.json"))?;
    let last = course.lessons.last().ok_or("no lessons")?;
    assert!(saved.contains(&last.id), "progress not saved: {saved}");
    Ok(())
}
