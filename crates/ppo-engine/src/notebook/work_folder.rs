//! One kernel per evcxr work folder.
//!
//! `notebooks/evcxr.toml` gives every kernel of a notebook folder the same work folder
//! (`.evcxr`), so a fresh kernel reuses the last one's build. evcxr writes each cell's code
//! to that folder's `src/lib.rs` and builds it there: two kernels compiling at the same
//! moment overwrite each other's cells (measured: one kernel ran the other's cells, another
//! failed to load its own). The first cell of every notebook calls [`claim_work_folder`],
//! which holds a lock on the folder for the kernel's lifetime and warns when another live
//! kernel holds it.

use std::fs::{File, OpenOptions, TryLockError};
use std::path::{Path, PathBuf};

use crate::tr;

/// The lock file inside the work folder.
const LOCK: &str = "kernel.lock";

/// Whether this kernel now holds its folder's work folder.
#[derive(Debug, PartialEq, Eq)]
pub enum Claim {
    /// The folder has no `evcxr.toml` (or it names no `tmpdir`): kernels there build in
    /// folders of their own, nothing to share.
    NotShared,
    /// This kernel holds the lock until it stops.
    Held(PathBuf),
    /// Another live kernel holds it: this one should not run cells at the same time.
    Busy(PathBuf),
}

/// The work folder `dir/evcxr.toml` names (relative paths against `dir`, as evcxr reads
/// them), if any.
fn work_folder(dir: &Path) -> Option<PathBuf> {
    let text = std::fs::read_to_string(dir.join("evcxr.toml")).ok()?;
    let table: toml::Table = text.parse().ok()?;
    let tmpdir = table.get("evcxr")?.get("tmpdir")?.as_str()?;
    Some(dir.join(tmpdir))
}

/// Takes the lock on the work folder `dir/evcxr.toml` names, and keeps it (the file stays
/// open until the process ends, which releases the lock).
///
/// # Errors
/// The lock file cannot be created or locked for another reason than another holder.
pub fn claim_in(dir: &Path) -> std::io::Result<Claim> {
    let Some(work) = work_folder(dir) else {
        return Ok(Claim::NotShared);
    };
    std::fs::create_dir_all(&work)?;
    let file: File = OpenOptions::new()
        .create(true)
        .truncate(false)
        .write(true)
        .open(work.join(LOCK))?;
    match file.try_lock() {
        Ok(()) => {
            // Held for the kernel's lifetime: the descriptor is never closed.
            std::mem::forget(file);
            Ok(Claim::Held(work))
        }
        Err(TryLockError::WouldBlock) => Ok(Claim::Busy(work)),
        Err(TryLockError::Error(e)) => Err(e),
    }
}

/// What the first cell prints: nothing while this kernel has its work folder to itself, a
/// warning when another kernel of the same folder is alive. A notebook opened outside a
/// folder with `evcxr.toml` prints nothing.
pub fn claim_work_folder() {
    let Ok(dir) = std::env::current_dir() else {
        return;
    };
    match claim_in(&dir) {
        Ok(Claim::Busy(work)) => println!("{}", busy_warning(&work)),
        Ok(Claim::Held(_) | Claim::NotShared) => {}
        Err(e) => println!(
            "{}",
            tr!(
                "Note: could not lock evcxr's work folder ({e}); run cells in one notebook at \
                 a time.",
                "注意：无法锁定 evcxr 的工作文件夹（{e}）；请一次只在一个笔记本里运行单元格。",
                e = e
            )
        ),
    }
}

/// The warning for a work folder another kernel holds.
fn busy_warning(work: &Path) -> String {
    tr!(
        "Warning: another kernel of this folder is still running and builds in {work} too. \
         Two kernels compiling cells at the same moment overwrite each other's code: shut the \
         other one down (JupyterLab: the Running tab) or run cells in one notebook at a time.",
        "警告：本文件夹还有另一个内核在运行，它同样在 {work} 中编译。两个内核同时编译单元格会互相覆盖代码：\
         请关闭另一个内核（JupyterLab 的“运行中”标签页），或一次只在一个笔记本里运行单元格。",
        work = work.display()
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn folder(name: &str, toml: Option<&str>) -> PathBuf {
        let dir = std::env::temp_dir().join(format!(
            "ppo-engine-work-folder-{name}-{}",
            std::process::id()
        ));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).ok();
        if let Some(text) = toml {
            std::fs::write(dir.join("evcxr.toml"), text).ok();
        }
        dir
    }

    #[test]
    fn the_first_kernel_holds_the_folder_and_a_second_is_warned() -> std::io::Result<()> {
        let dir = folder("shared", Some("[evcxr]\ntmpdir = \".evcxr\"\n"));
        let work = dir.join(".evcxr");
        assert_eq!(claim_in(&dir)?, Claim::Held(work.clone()));
        // A second claim opens the file anew, as another kernel's process would: the lock
        // (per open file) is still held by the first.
        assert_eq!(claim_in(&dir)?, Claim::Busy(work.clone()));
        assert!(busy_warning(&work).contains(&work.display().to_string()));
        Ok(())
    }

    #[test]
    fn a_folder_without_a_shared_work_folder_needs_no_lock() -> std::io::Result<()> {
        assert_eq!(claim_in(&folder("none", None))?, Claim::NotShared);
        assert_eq!(
            claim_in(&folder("no-tmpdir", Some("[evcxr]\nopt_level = \"2\"\n")))?,
            Claim::NotShared
        );
        Ok(())
    }
}
