//! Grading on save: watch exercise files and report when one is saved, debounced, as
//! rustlings does. The terminal app and `ppo-tutor watch` both use [`SaveWatcher`].
//!
//! Editors save in different ways (write in place, or write a temporary file and rename it
//! over the original), so the watcher watches each file's folder and reports the watched
//! files that changed in it, once per burst of events ([`DEBOUNCE`]).
//!
//! The system reports reads too (opening a file is an event on Linux), and the grader reads
//! the file it grades: a watcher that took every event for a save graded again and again
//! with no save at all. A file counts as saved only when its content changed since it was
//! last seen: its length and modification time are compared first (a `stat`, which is no
//! event), then its content's hash, so a read, or a save that writes the same text, is not a
//! save.

use std::path::{Path, PathBuf};
use std::time::Duration;

use notify_debouncer_mini::notify::{RecommendedWatcher, RecursiveMode};
use notify_debouncer_mini::{DebounceEventResult, DebouncedEventKind, Debouncer, new_debouncer};

/// How long a file must be quiet after an event before it counts as saved.
pub const DEBOUNCE: Duration = Duration::from_millis(300);

/// Watches files and calls back with the ones saved, until dropped.
pub struct SaveWatcher {
    files: Vec<PathBuf>,
    _debouncer: Debouncer<RecommendedWatcher>,
}

impl std::fmt::Debug for SaveWatcher {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("SaveWatcher")
            .field("files", &self.files)
            .finish_non_exhaustive()
    }
}

/// Why files cannot be watched.
#[derive(Debug)]
pub struct WatchError {
    /// The folder that could not be watched.
    pub folder: PathBuf,
    /// The file watcher's message.
    pub reason: String,
}

impl std::error::Error for WatchError {}

impl std::fmt::Display for WatchError {
    /// The message in the current language (the folder as it is).
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let (folder, reason) = (self.folder.display(), &self.reason);
        f.write_str(&crate::tr!(
            "cannot watch {folder} for saves: {reason}",
            "无法监视 {folder} 中的保存：{reason}"
        ))
    }
}

impl SaveWatcher {
    /// Watches `files` (their folders must exist) and calls `on_save` with those saved,
    /// on the watcher's own thread.
    ///
    /// # Errors
    /// A folder cannot be watched (it does not exist, or the system's watch limit is hit).
    pub fn new(
        files: &[PathBuf],
        mut on_save: impl FnMut(Vec<PathBuf>) + Send + 'static,
    ) -> Result<Self, WatchError> {
        let files: Vec<PathBuf> = files.iter().map(|f| absolute(f)).collect();
        let wanted = files.clone();
        let mut seen: Vec<Seen> = files.iter().map(|f| Seen::of(f)).collect();
        let mut debouncer = new_debouncer(DEBOUNCE, move |result: DebounceEventResult| {
            let Ok(events) = result else { return };
            let mut saved: Vec<PathBuf> = Vec::new();
            for (f, last) in wanted.iter().zip(seen.iter_mut()) {
                let touched = events
                    .iter()
                    .any(|e| e.kind == DebouncedEventKind::Any && same_file(&e.path, f));
                if touched && last.changed(f) {
                    saved.push(f.clone());
                }
            }
            saved.dedup();
            if !saved.is_empty() {
                on_save(saved);
            }
        })
        .map_err(|e| WatchError {
            folder: PathBuf::from("."),
            reason: e.to_string(),
        })?;
        let mut folders: Vec<PathBuf> = files
            .iter()
            .map(|f| {
                f.parent()
                    .map_or_else(|| PathBuf::from("."), Path::to_path_buf)
            })
            .collect();
        folders.sort();
        folders.dedup();
        for folder in folders {
            debouncer
                .watcher()
                .watch(&folder, RecursiveMode::NonRecursive)
                .map_err(|e| WatchError {
                    folder: folder.clone(),
                    reason: e.to_string(),
                })?;
        }
        Ok(Self {
            files,
            _debouncer: debouncer,
        })
    }

    /// The files watched (absolute).
    #[must_use]
    pub fn files(&self) -> &[PathBuf] {
        &self.files
    }
}

/// What the watcher last saw of a file: its length and modification time, and its
/// content's hash (`None` while the file does not exist).
#[derive(Debug, Clone, PartialEq, Eq)]
struct Seen {
    stat: Option<(u64, Option<std::time::SystemTime>)>,
    hash: Option<u64>,
}

impl Seen {
    fn stat(path: &Path) -> Option<(u64, Option<std::time::SystemTime>)> {
        let m = std::fs::metadata(path).ok()?;
        Some((m.len(), m.modified().ok()))
    }

    fn hash(path: &Path) -> Option<u64> {
        use std::hash::{Hash as _, Hasher as _};
        let bytes = std::fs::read(path).ok()?;
        let mut h = std::collections::hash_map::DefaultHasher::new();
        bytes.hash(&mut h);
        Some(h.finish())
    }

    fn of(path: &Path) -> Self {
        Self {
            stat: Self::stat(path),
            hash: Self::hash(path),
        }
    }

    /// Whether the file's content differs from what was last seen (a file that appeared or
    /// disappeared changed); remembers what it sees now. A read changes nothing: the length
    /// and time are the same, so the file is not even read.
    fn changed(&mut self, path: &Path) -> bool {
        let stat = Self::stat(path);
        if stat == self.stat {
            return false;
        }
        self.stat = stat;
        let hash = Self::hash(path);
        if hash == self.hash {
            return false;
        }
        self.hash = hash;
        true
    }
}

fn absolute(path: &Path) -> PathBuf {
    std::path::absolute(path).unwrap_or_else(|_| path.to_path_buf())
}

/// Whether an event's path is `file` (events may name the file through another spelling of
/// its folder, e.g. a symlinked temporary directory).
fn same_file(event: &Path, file: &Path) -> bool {
    event == file
        || (event.file_name() == file.file_name()
            && event.parent().and_then(|p| p.canonicalize().ok())
                == file.parent().and_then(|p| p.canonicalize().ok()))
}

#[cfg(test)]
mod tests {
    use std::sync::mpsc;

    use super::*;

    #[test]
    fn a_save_is_reported_once_and_other_files_are_ignored()
    -> Result<(), Box<dyn std::error::Error>> {
        let dir = tempfile::tempdir()?;
        let watched = dir.path().join("exercise.rs");
        let other = dir.path().join("notes.txt");
        std::fs::write(&watched, "// start\n")?;
        let (tx, rx) = mpsc::channel();
        let _watcher = SaveWatcher::new(std::slice::from_ref(&watched), move |saved| {
            let _ = tx.send(saved);
        })?;
        std::thread::sleep(Duration::from_millis(100));
        std::fs::write(&other, "ignored")?;
        for i in 0..3 {
            // A burst of writes, as an editor's save can be, is one save.
            std::fs::write(&watched, format!("// edit {i}\n"))?;
        }
        let saved = rx.recv_timeout(Duration::from_secs(5))?;
        assert_eq!(saved.len(), 1);
        assert!(same_file(&saved[0], &watched), "{saved:?}");
        assert!(
            rx.recv_timeout(DEBOUNCE * 3).is_err(),
            "one burst, one report; the other file is not watched"
        );
        // Saving by renaming a temporary file over the original counts too.
        let tmp = dir.path().join(".exercise.rs.swp");
        std::fs::write(&tmp, "// renamed\n")?;
        std::fs::rename(&tmp, &watched)?;
        assert!(rx.recv_timeout(Duration::from_secs(5)).is_ok());
        Ok(())
    }

    #[test]
    fn reading_the_file_or_saving_the_same_text_is_not_a_save()
    -> Result<(), Box<dyn std::error::Error>> {
        let dir = tempfile::tempdir()?;
        let watched = dir.path().join("exercise.rs");
        std::fs::write(&watched, "// start\n")?;
        let (tx, rx) = mpsc::channel();
        let _watcher = SaveWatcher::new(std::slice::from_ref(&watched), move |saved| {
            let _ = tx.send(saved);
        })?;
        std::thread::sleep(Duration::from_millis(100));
        // What a grader does: open and read the file, several times.
        for _ in 0..5 {
            let _ = std::fs::read_to_string(&watched)?;
            std::thread::sleep(Duration::from_millis(50));
        }
        assert!(
            rx.recv_timeout(DEBOUNCE * 4).is_err(),
            "a read was taken for a save"
        );
        // The same text written again (an editor's save with no edit).
        std::fs::write(&watched, "// start\n")?;
        assert!(
            rx.recv_timeout(DEBOUNCE * 4).is_err(),
            "the same text was taken for a save"
        );
        // A real edit is a save, once, and reading it afterwards is not another.
        std::fs::write(&watched, "// edited\n")?;
        assert!(
            rx.recv_timeout(Duration::from_secs(5)).is_ok(),
            "the edit was missed"
        );
        let _ = std::fs::read_to_string(&watched)?;
        assert!(
            rx.recv_timeout(DEBOUNCE * 4).is_err(),
            "reading the saved file was taken for another save"
        );
        Ok(())
    }

    #[test]
    fn a_missing_folder_is_named() {
        let e = SaveWatcher::new(&[PathBuf::from("/no/such/folder/exercise.rs")], |_| {});
        let message = e.err().map(|e| e.to_string()).unwrap_or_default();
        assert!(message.contains("/no/such/folder"), "{message}");
    }
}
