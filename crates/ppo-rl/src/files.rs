//! Writing the files a run leaves behind (checkpoints, the progress file, JSON results):
//! atomically, and with the permissions any program's new file gets.
//!
//! [`write_atomically`] writes a hidden sibling temporary file and renames it over the
//! target, so a crash or a full disk never leaves half a file, and removes the temporary
//! file on every failure. The file is created as `File::create` would create it (mode
//! `0o666` less the umask: `0o644` under the usual umask `022`), not `0o600` as a
//! `tempfile::NamedTempFile` is.
//!
//! ```
//! # fn main() -> std::io::Result<()> {
//! let dir = std::env::temp_dir().join(format!("ppo-engine-doc-{}", std::process::id()));
//! std::fs::create_dir_all(&dir)?;
//! let path = dir.join("out.json");
//! ppo_rl::files::write_atomically(&path, b"{}\n")?;
//! assert_eq!(std::fs::read(&path)?, b"{}\n");
//! // Nothing else is left in the folder.
//! assert_eq!(std::fs::read_dir(&dir)?.count(), 1);
//! # std::fs::remove_dir_all(&dir)
//! # }
//! ```

use std::io::Write as _;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};

/// Writes `bytes` to `path` through a sibling temporary file renamed over it; on any
/// failure the temporary file is removed and `path` is left as it was.
///
/// # Errors
/// The folder cannot be written, the disk is full, or `path` cannot be replaced (it is a
/// folder, say). The error is the file system's; the caller names `path`.
pub fn write_atomically(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    let tmp = temporary_sibling(path);
    let written = (|| {
        let mut file = std::fs::OpenOptions::new()
            .write(true)
            .create_new(true)
            .open(&tmp)?;
        file.write_all(bytes)?;
        file.sync_all()?;
        drop(file);
        std::fs::rename(&tmp, path)
    })();
    if written.is_err() {
        // Nothing to say if it never existed.
        let _ = std::fs::remove_file(&tmp);
    }
    written
}

/// A fresh hidden name beside `path` that ends like it (`.tmp-PID-N-returns.png` beside
/// `returns.png`, so that a writer choosing the format by the extension still can), for a
/// file to be renamed over `path` once written whole.
#[must_use]
pub fn temporary_sibling(path: &Path) -> PathBuf {
    static COUNT: AtomicUsize = AtomicUsize::new(0);
    let n = COUNT.fetch_add(1, Ordering::Relaxed);
    let name = path
        .file_name()
        .map_or_else(|| "file".into(), |n| n.to_string_lossy().into_owned());
    let tmp = format!(".tmp-{}-{n}-{name}", std::process::id());
    match path.parent() {
        Some(folder) if !folder.as_os_str().is_empty() => folder.join(tmp),
        _ => PathBuf::from(tmp),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_failure_leaves_nothing_behind() -> Result<(), Box<dyn std::error::Error>> {
        let dir = tempfile::tempdir()?;
        // The target is a folder: the rename fails, and the temporary file goes.
        let folder = dir.path().join("a-folder");
        std::fs::create_dir(&folder)?;
        assert!(write_atomically(&folder, b"x").is_err());
        assert!(folder.is_dir());
        let left: Vec<_> = std::fs::read_dir(dir.path())?.collect::<Result<_, _>>()?;
        assert_eq!(left.len(), 1, "{left:?}");
        // A missing folder: nothing is created.
        assert!(write_atomically(&dir.path().join("no/such/file"), b"x").is_err());
        // A file is replaced whole.
        let file = dir.path().join("f.txt");
        write_atomically(&file, b"first")?;
        write_atomically(&file, b"second")?;
        assert_eq!(std::fs::read(&file)?, b"second");
        Ok(())
    }

    /// The file gets the mode `File::create` gives a new file here (the umask applies).
    #[cfg(unix)]
    #[test]
    fn the_mode_is_that_of_a_new_file() -> Result<(), Box<dyn std::error::Error>> {
        use std::os::unix::fs::PermissionsExt as _;
        let dir = tempfile::tempdir()?;
        let reference = dir.path().join("reference");
        std::fs::File::create(&reference)?;
        let path = dir.path().join("written");
        write_atomically(&path, b"x")?;
        let mode = |p: &Path| std::fs::metadata(p).map(|m| m.permissions().mode() & 0o777);
        assert_eq!(mode(&path)?, mode(&reference)?);
        Ok(())
    }
}
