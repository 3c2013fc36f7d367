//! End to end: the real binary in a pseudo-terminal (portable-pty), its screen parsed
//! with a vt100 emulator. Walks every step of every lesson, trains, opens help, quits; once
//! in English and once in Chinese (`PPO_TUTOR_LANG=zh`), which also switches to English
//! live with `L`.

use std::io::{Read, Write};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use portable_pty::{CommandBuilder, PtySize, native_pty_system};
use ppo_tutor::i18n::Lang;
use ppo_tutor::lesson::Course;
use ppo_tutor::lesson::quiz::{Answer, QuestionKind, letter_of};

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

/// What the walk looks for on the screen, in one language.
struct Words {
    lang: Lang,
    /// The header's step counter: `step 2/6`.
    step: fn(usize, usize) -> String,
    /// The quiz's question counter: `question 1/3`.
    question: fn(usize, usize) -> String,
    /// The header's episode counter before its number: `episode `.
    episode: &'static str,
    /// The status after a right answer.
    right: &'static str,
    /// The header while training.
    training: &'static str,
    /// The help overlay's title.
    help: &'static str,
}

const ENGLISH: Words = Words {
    lang: Lang::En,
    step: |i, n| format!("step {i}/{n}"),
    question: |i, n| format!("question {i}/{n}"),
    episode: "episode ",
    right: "✓ Right",
    training: "training",
    help: "keys (Esc closes)",
};

const CHINESE: Words = Words {
    lang: Lang::Zh,
    step: |i, n| format!("第 {i}/{n} 节"),
    question: |i, n| format!("第 {i}/{n} 题"),
    episode: "回合 ",
    right: "答对了",
    training: "训练中",
    help: "按键（Esc 关闭）",
};

/// The episode count in the header (`episode N · ...`, `回合 N · ...`), 0 if absent.
fn episode_on(text: &str, word: &str) -> usize {
    text.split(word)
        .filter_map(|rest| rest.split_whitespace().next()?.parse().ok())
        .max()
        .unwrap_or(0)
}

#[test]
fn walk_the_whole_course_in_a_real_terminal() -> TestResult {
    walk(&ENGLISH)
}

#[test]
fn walk_the_whole_course_in_chinese_in_a_real_terminal() -> TestResult {
    // The first lesson's Chinese title, as its lesson.zh.md writes it.
    let zh = include_str!("../lessons/01-what-is-ppo/lesson.zh.md");
    let title = zh
        .lines()
        .find_map(|l| l.strip_prefix("title = "))
        .ok_or("no title in lesson.zh.md")?
        .trim_matches('"');
    assert_eq!(Course::embedded_in(Lang::Zh)?.lessons[0].title, title);
    walk(&CHINESE)
}

fn walk(words: &Words) -> TestResult {
    let course = Course::embedded_in(words.lang)?;
    let english = Course::embedded_in(Lang::En)?;
    let dir = tempfile::tempdir()?;
    let (mut child, screen, _, mut writer) =
        spawn_app(dir.path(), &[("PPO_TUTOR_LANG", words.lang.code())])?;
    let mut key = |bytes: &[u8]| -> std::io::Result<()> {
        writer.write_all(bytes)?;
        writer.flush()?;
        std::thread::sleep(Duration::from_millis(15));
        Ok(())
    };

    screen.wait_for(&course.lessons[0].title, 30)?;
    // the first episode arrives from the worker
    screen.wait_for(&format!("{}1 ·", words.episode), 30)?;
    for lesson in &course.lessons {
        for (i, step) in lesson.steps.iter().enumerate() {
            let header = format!(
                "{} · {}",
                lesson.title,
                (words.step)(i + 1, lesson.steps.len())
            );
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
            let header = (words.question)(i + 1, lesson.quiz.len());
            screen.wait_for(&header, 10)?;
            if let (
                0,
                QuestionKind::Choice {
                    answer: Answer::Letter(answer),
                    ..
                },
            ) = (i, &question.kind)
                && lesson.order == 1
            {
                key(letter_of(*answer).to_string().as_bytes())?;
                screen.wait_for(words.right, 10)?;
            }
            key(b"\x1b[C")?; // →
        }
    }
    // One more episode than the screen shows: the walk ends in a Pendulum lesson, whose run
    // started fresh (episode 0) when the walk entered the first Pendulum lesson.
    let before = episode_on(&screen.text(), words.episode);
    key(b"e")?;
    screen.wait_for(&format!("{}{} ·", words.episode, before + 1), 30)?;
    key(b"t")?;
    screen.wait_for(words.training, 10)?;
    // Training runs on the worker: the header's episode counter must climb.
    let deadline = Instant::now() + Duration::from_secs(60);
    while episode_on(&screen.text(), words.episode) < 10 {
        if Instant::now() > deadline {
            return Err(format!("training did not advance:\n{}", screen.text()).into());
        }
        std::thread::sleep(Duration::from_millis(50));
    }
    key(b"t")?;
    key(b"?")?;
    screen.wait_for(words.help, 10)?;
    key(b"\x1b")?;
    if words.lang == Lang::Zh {
        // L switches to English live, at the same lesson and step.
        let last = english.lessons.last().ok_or("no lessons")?;
        key(b"L")?;
        screen.wait_for(
            &format!(
                "{} · step {}/{}",
                last.title,
                last.steps.len(),
                last.steps.len()
            ),
            10,
        )?;
        screen.wait_for("L 中文", 10)?;
    }
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

/// The app in a 160×50 pseudo-terminal: its child, its screen, every byte it wrote, and
/// its keyboard (which keeps the terminal open).
type Spawned = (
    Box<dyn portable_pty::Child + Send + Sync>,
    Screen,
    Arc<Mutex<Vec<u8>>>,
    Keyboard,
);

/// Keys for the app: the pseudo-terminal's writer, and its master, kept open with it.
struct Keyboard {
    writer: Box<dyn Write + Send>,
    _master: Box<dyn portable_pty::MasterPty + Send>,
}

impl Keyboard {
    fn write_all(&mut self, bytes: &[u8]) -> std::io::Result<()> {
        self.writer.write_all(bytes)
    }

    fn flush(&mut self) -> std::io::Result<()> {
        self.writer.flush()
    }
}

/// The app started in `dir` (its progress file `state.json` there) in an English locale
/// with no language set, then with `env` set.
fn spawn_app(
    dir: &std::path::Path,
    env: &[(&str, &str)],
) -> Result<Spawned, Box<dyn std::error::Error>> {
    let pty = native_pty_system().openpty(PtySize {
        rows: 50,
        cols: 160,
        pixel_width: 0,
        pixel_height: 0,
    })?;
    let mut cmd = CommandBuilder::new(env!("CARGO_BIN_EXE_ppo-tutor"));
    cmd.env("PPO_TUTOR_STATE", dir.join("state.json"));
    cmd.env("TERM", "xterm-256color");
    cmd.env_remove("PPO_TUTOR_LANG");
    cmd.env("LANG", "C.UTF-8");
    cmd.env_remove("LC_ALL");
    cmd.env_remove("LC_MESSAGES");
    for (k, v) in env {
        cmd.env(k, v);
    }
    cmd.cwd(dir);
    let child = pty.slave.spawn_command(cmd)?;
    drop(pty.slave);
    let parser = Arc::new(Mutex::new(vt100::Parser::new(50, 160, 0)));
    let raw = Arc::new(Mutex::new(Vec::<u8>::new()));
    let mut reader = pty.master.try_clone_reader()?;
    let (sink, bytes) = (Arc::clone(&parser), Arc::clone(&raw));
    std::thread::spawn(move || {
        let mut buf = [0_u8; 8192];
        while let Ok(n) = reader.read(&mut buf) {
            if n == 0 {
                break;
            }
            if let Ok(mut p) = sink.lock() {
                p.process(&buf[..n]);
            }
            if let Ok(mut b) = bytes.lock() {
                b.extend_from_slice(&buf[..n]);
            }
        }
    });
    let writer = pty.master.take_writer()?;
    let keys = Keyboard {
        writer,
        _master: pty.master,
    };
    Ok((child, Screen { parser }, raw, keys))
}

/// Waits for `child` to exit (at most 20 s).
fn exit_of(
    child: &mut Box<dyn portable_pty::Child + Send + Sync>,
) -> Result<portable_pty::ExitStatus, Box<dyn std::error::Error>> {
    let deadline = Instant::now() + Duration::from_secs(20);
    loop {
        if let Some(status) = child.try_wait()? {
            return Ok(status);
        }
        if Instant::now() > deadline {
            child.kill()?;
            return Err("ppo-tutor did not exit".into());
        }
        std::thread::sleep(Duration::from_millis(50));
    }
}

/// SIGTERM and SIGHUP end the app as `q` does: the terminal leaves the alternate screen
/// with the cursor shown, the progress is saved, and the exit status is the shell's
/// 128 + the signal's number.
#[cfg(unix)]
#[test]
fn a_signal_restores_the_terminal_and_saves_the_progress() -> TestResult {
    for (signal, number) in [("TERM", 15), ("HUP", 1)] {
        let dir = tempfile::tempdir()?;
        let (mut child, screen, raw, mut writer) =
            spawn_app(dir.path(), &[("PPO_TUTOR_LANG", "en")])?;
        screen.wait_for("episode 1 ·", 30)?;
        // A step forward, so that the saved progress shows it was written at the end.
        writer.write_all(b"\x1b[C")?;
        writer.flush()?;
        screen.wait_for("step 2/", 10)?;
        let before = raw.lock().map(|b| b.len()).unwrap_or(0);
        let pid = child.process_id().ok_or("no pid")?;
        let sent = std::process::Command::new("kill")
            .args([format!("-{signal}"), pid.to_string()])
            .status()?;
        assert!(sent.success(), "kill -{signal} failed");
        let status = exit_of(&mut child)?;
        assert_eq!(status.exit_code(), 128 + number, "SIG{signal}: {status:?}");
        // The reader may still be draining the last bytes.
        std::thread::sleep(Duration::from_millis(200));
        let after: Vec<u8> = raw.lock().map(|b| b[before..].to_vec()).unwrap_or_default();
        let after = String::from_utf8_lossy(&after);
        assert!(
            after.contains("\u{1b}[?1049l"),
            "SIG{signal}: the alternate screen was not left: {after:?}"
        );
        assert!(
            after.contains("\u{1b}[?25h"),
            "SIG{signal}: the cursor was not shown again: {after:?}"
        );
        let saved = std::fs::read_to_string(dir.path().join("state.json"))?;
        assert!(saved.contains("\"step\": 1"), "SIG{signal}: {saved}");
    }
    Ok(())
}

/// `L` is kept: the next start (no `--lang`, no PPO_TUTOR_LANG, an English locale) opens
/// in the language chosen last; PPO_TUTOR_LANG still decides when it is set.
#[test]
fn the_language_chosen_with_l_is_kept_for_the_next_start() -> TestResult {
    let dir = tempfile::tempdir()?;
    let (mut child, screen, _, mut writer) = spawn_app(dir.path(), &[])?;
    screen.wait_for("episode 1 ·", 30)?;
    writer.write_all(b"L")?;
    writer.flush()?;
    screen.wait_for("回合 1 ·", 10)?;
    writer.write_all(b"q")?;
    writer.flush()?;
    assert!(exit_of(&mut child)?.success());
    let (mut child, screen, _, mut writer) = spawn_app(dir.path(), &[])?;
    screen.wait_for("回合 1 ·", 30)?;
    writer.write_all(b"q")?;
    writer.flush()?;
    assert!(exit_of(&mut child)?.success());
    let (mut child, screen, _, mut writer) = spawn_app(dir.path(), &[("PPO_TUTOR_LANG", "en")])?;
    screen.wait_for("episode 1 ·", 30)?;
    writer.write_all(b"q")?;
    writer.flush()?;
    assert!(exit_of(&mut child)?.success());
    Ok(())
}
