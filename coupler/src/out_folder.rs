//! The output folder of a run, held for the run: a second run into it is refused, naming the
//! first one's pid, and a folder that holds an earlier run's files is refused unless the user asks
//! (`--overwrite`) to have them deleted first — so two runs never mix their files.
//!
//! The hold is an advisory lock (flock(2)) on `.coupler.lock` in the folder, which holds the pid of
//! the run. The kernel lets go of it when the process ends, however it ends, so a killed run never
//! leaves a stale lock behind.

use crate::error::CouplerError;
use std::fs::{File, OpenOptions};
use std::io::{Read, Seek, Write};
use std::os::unix::io::AsRawFd;
use std::path::{Path, PathBuf};

/// Refuses an output folder that cannot be one, before anything runs: a path through a file
/// (`--out results.csv`, `--out results.csv/run`), or a place on a file system that holds no
/// files (`/proc`, `/sys`), where the free-space check would read 0 B and call the run too large.
pub fn check_place(dir: &Path) -> Result<(), CouplerError> {
    let existing = nearest_existing(dir);
    if !existing.is_dir() {
        return Err(CouplerError::Usage(format!(
            "the output folder {} cannot be made: {} is a file, not a folder; choose another --out",
            dir.display(),
            existing.display()
        )));
    }
    if file_system(existing).is_none_or(|fs| fs.f_blocks > 0) {
        Ok(())
    } else {
        Err(CouplerError::Usage(format!(
            "the output folder {} cannot be made: {} is on a file system that holds no files (such as /proc); \
             choose another --out",
            dir.display(),
            existing.display()
        )))
    }
}

/// The nearest path at or above `dir` that exists (the working folder when no part of a relative
/// `dir` does): where the output folder would be made.
pub fn nearest_existing(dir: &Path) -> &Path {
    dir.ancestors()
        .find(|p| !p.as_os_str().is_empty() && p.exists())
        .unwrap_or(Path::new("."))
}

/// statvfs(3) of the file system that holds `path`; None when it cannot be read.
pub fn file_system(path: &Path) -> Option<libc::statvfs> {
    let c_path = std::ffi::CString::new(path.as_os_str().as_encoded_bytes()).ok()?;
    let mut stat: libc::statvfs = unsafe { std::mem::zeroed() };
    // SAFETY: a NUL-terminated path and a statvfs struct owned here.
    let rc = unsafe { libc::statvfs(c_path.as_ptr(), &mut stat) };
    (rc == 0).then_some(stat)
}

/// The lock file's name inside the output folder.
pub const LOCK_FILE: &str = ".coupler.lock";

/// An output folder held by this process; dropping it lets go.
#[derive(Debug)]
pub struct OutputFolder {
    pub dir: PathBuf,
    _lock: File,
}

impl OutputFolder {
    /// Creates `dir` if needed, takes it for this run, and deletes an earlier run's files when
    /// `overwrite` is set (refuses them otherwise).
    pub fn take(dir: &Path, overwrite: bool) -> Result<OutputFolder, CouplerError> {
        let io = |what: &str, e: std::io::Error| CouplerError::Io(format!("{what} {}: {e}", dir.display()));
        std::fs::create_dir_all(dir).map_err(|e| io("cannot create the output folder", e))?;
        let mut lock = Self::lock(dir)?;
        let earlier: Vec<PathBuf> = std::fs::read_dir(dir)
            .map_err(|e| io("cannot read the output folder", e))?
            .filter_map(Result::ok)
            .map(|e| e.path())
            .filter(|p| p.file_name().is_some_and(|n| n != LOCK_FILE))
            .collect();
        if !earlier.is_empty() {
            if !overwrite {
                let mut names: Vec<String> = earlier
                    .iter()
                    .filter_map(|p| p.file_name().map(|n| n.to_string_lossy().into_owned()))
                    .collect();
                names.sort();
                names.truncate(4);
                return Err(CouplerError::Usage(format!(
                    "{} already holds {} files or folders of an earlier run ({}{}); pass --overwrite to delete them \
                     first, --resume {} to continue it from its last checkpoint, or choose another --out",
                    dir.display(),
                    earlier.len(),
                    names.join(", "),
                    if earlier.len() > names.len() { ", …" } else { "" },
                    dir.display()
                )));
            }
            for p in &earlier {
                let removed = if p.is_dir() {
                    std::fs::remove_dir_all(p)
                } else {
                    std::fs::remove_file(p)
                };
                removed.map_err(|e| {
                    CouplerError::Io(format!("--overwrite: cannot delete {}: {e}", p.display()))
                })?;
            }
        }
        lock.set_len(0)
            .and_then(|()| lock.rewind())
            .and_then(|()| writeln!(lock, "{}", std::process::id()))
            .map_err(|e| io("cannot lock the output folder", e))?;
        Ok(OutputFolder {
            dir: dir.to_path_buf(),
            _lock: lock,
        })
    }

    /// Takes an existing output folder for a resumed run: locked like [`OutputFolder::take`], its
    /// files kept.
    pub fn hold(dir: &Path) -> Result<OutputFolder, CouplerError> {
        if !dir.is_dir() {
            return Err(CouplerError::Usage(format!(
                "--resume {}: there is no such output folder",
                dir.display()
            )));
        }
        let mut lock = Self::lock(dir)?;
        lock.set_len(0)
            .and_then(|()| lock.rewind())
            .and_then(|()| writeln!(lock, "{}", std::process::id()))
            .map_err(|e| CouplerError::Io(format!("cannot lock the output folder {}: {e}", dir.display())))?;
        Ok(OutputFolder {
            dir: dir.to_path_buf(),
            _lock: lock,
        })
    }

    /// Takes the folder's lock, or says which run holds it.
    fn lock(dir: &Path) -> Result<File, CouplerError> {
        let io = |what: &str, e: std::io::Error| CouplerError::Io(format!("{what} {}: {e}", dir.display()));
        let lock_path = dir.join(LOCK_FILE);
        let mut lock = OpenOptions::new()
            .read(true)
            .write(true)
            .create(true)
            .truncate(false)
            .open(&lock_path)
            .map_err(|e| io("cannot lock the output folder", e))?;
        // SAFETY: flock(2) on a descriptor this function owns.
        let held = unsafe { libc::flock(lock.as_raw_fd(), libc::LOCK_EX | libc::LOCK_NB) } == 0;
        if !held {
            let mut pid = String::new();
            let _ = lock.read_to_string(&mut pid);
            return Err(CouplerError::Usage(format!(
                "{} is the output folder of a run still going on (coupler pid {}); wait for it to end, stop it, \
                 or choose another --out",
                dir.display(),
                pid.trim()
            )));
        }
        Ok(lock)
    }
}
