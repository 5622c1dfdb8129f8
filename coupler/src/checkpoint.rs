//! Checkpoints of a coupled run and what `coupler run CASE --resume OUT` does with them.
//!
//! At the end of every `coupling.checkpoint_interval` the coupler asks each participant to write
//! its state (`OUT/checkpoint/NAME-WINDOW.bin`, [`schemas::checkpoint`]), then writes its own
//! [`Manifest`] (`coupler-WINDOW.bin`) last: the window, its own state (the last window's outputs,
//! the accelerator, the magnitudes of the convergence measure, the ledger's worst balance, the
//! counts) and the length of every output file at that moment. A checkpoint is complete only when
//! its manifest exists; the last two are kept. A run whose end time is a whole number of checkpoint
//! intervals also takes one at its end (before the participants write what they write at `Finish`),
//! as a longer run would take it there: it can be extended from there (`coupler run CASE --resume
//! OUT --end-time T`). Where a longer run would take no checkpoint, none is taken: writing one
//! changes the arithmetic that follows (a beam frame factorises anew), so the extended run would
//! not be that longer run.
//!
//! Resuming cuts every output file back to its length in the last complete manifest, deletes the
//! files written after it, starts the participants with `--resume THEIR-FILE`, and runs the windows
//! after it, appending to every file: the outputs end as those of a run that never stopped. The
//! logs (`NAME.log`) are not cut: they are appended to, and keep the first run's lines.
//!
//! A resumed run goes to `--end-time` when given, else to the case's `end_time` (which a resume
//! does not compare: [`schemas::case::Case::input_hashes`]); it must lie after the checkpoint.
//! Extending a finished run is the same resume: the files written at its end (after the
//! checkpoint) are cut off, and the outputs continue as those of a run started with the later end
//! time. A finished run whose end is not a checkpoint time is extended from its last checkpoint
//! before the end (its last windows are run again). A run resumed to the time of a checkpoint
//! taken at its end (it finished, or was stopped while its solvers wrote their end-of-run output)
//! continues from the checkpoint before that one, and ends as it did.

use crate::error::CouplerError;
use crate::out_folder::LOCK_FILE;
use schemas::checkpoint::{self, FOLDER};
use schemas::participant::DiscardProgress;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// The coupler's state at a window end, as a resumed run needs it.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct CouplerState {
    /// The window the resumed run starts with.
    pub next_window: u64,
    /// Each participant's outputs over the last window (bincode of `Vec<Waveform>`).
    pub last: Vec<u8>,
    /// Each participant's member geometry (bincode of `Vec<Option<Geometry>>`).
    pub geometry: Vec<u8>,
    /// What the accelerator keeps across windows ([`crate::acceleration::Accelerator::save`]).
    pub accelerator: Vec<u8>,
    /// Largest RMS of each participant's output arrays so far ([`crate::state::Magnitudes`]).
    pub magnitudes: Vec<(usize, String, f64)>,
    /// The ledger's worst balance and the windows above its tolerance.
    pub worst_balance: f64,
    pub balance_violations: u64,
    /// Windows, sweeps, and the most sweeps in a window so far.
    pub windows: u64,
    pub iterations: u64,
    pub max_iterations: u32,
    /// The coupling-instability detector's account ([`crate::stability::Detector::save`]).
    pub detector: Vec<u8>,
    /// What each interface law keeps across windows ([`crate::laws::Law::save`]).
    pub laws: Vec<Vec<u8>>,
}

/// A complete checkpoint: written after every participant's file.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Manifest {
    /// What the run was started with: the case's settings and each file it names, hashed
    /// ([`schemas::case::Case::input_hashes`]).
    pub inputs: Vec<(String, u64)>,
    /// The last window done (from 0), and its end time.
    pub window: u64,
    pub time: f64,
    /// The end time the run was going to.
    pub end_time: f64,
    /// Wall seconds since the run started, at the checkpoint.
    pub wall: f64,
    /// Participants in serial order.
    pub participants: Vec<String>,
    pub coupler: CouplerState,
    /// Every output file (path relative to the output folder) with its length in bytes.
    pub files: Vec<(String, u64)>,
}

/// Checkpoints kept in the folder (older ones are deleted once a newer one is complete).
pub const KEEP: usize = 2;

/// The manifest's name for the coupler's file of a window.
const COUPLER: &str = "coupler";

/// Writes `manifest` (durably, whole or not at all) and deletes checkpoints older than the last
/// [`KEEP`].
pub fn write_manifest(out: &Path, manifest: &Manifest) -> Result<(), CouplerError> {
    let path = checkpoint::file(out, COUPLER, manifest.window);
    checkpoint::write(&path, manifest, &mut DiscardProgress)
        .map_err(|e| CouplerError::Io(format!("cannot write the checkpoint {}: {e}", path.display())))?;
    prune(out);
    Ok(())
}

/// Creates the checkpoint folder.
pub fn create_folder(out: &Path) -> Result<(), CouplerError> {
    let dir = out.join(FOLDER);
    std::fs::create_dir_all(&dir)
        .map_err(|e| CouplerError::Io(format!("cannot create {}: {e}", dir.display())))
}

/// The window of a checkpoint file `NAME-WINDOW.bin`, and whether it is a manifest.
fn window_of(file: &Path) -> Option<(u64, bool)> {
    let name = file.file_name()?.to_str()?.strip_suffix(".bin")?;
    let (who, window) = name.rsplit_once('-')?;
    Some((window.parse().ok()?, who == COUPLER))
}

/// Manifests in the folder, newest first.
fn manifests(out: &Path) -> Vec<(u64, PathBuf)> {
    let mut found: Vec<(u64, PathBuf)> = std::fs::read_dir(out.join(FOLDER))
        .map(|entries| {
            entries
                .filter_map(Result::ok)
                .map(|e| e.path())
                .filter_map(|p| match window_of(&p) {
                    Some((w, true)) => Some((w, p)),
                    _ => None,
                })
                .collect()
        })
        .unwrap_or_default();
    found.sort_by_key(|m| std::cmp::Reverse(m.0));
    found
}

/// Deletes every checkpoint file of a window before the [`KEEP`] newest complete ones. Files that
/// cannot be deleted stay (they only take space).
fn prune(out: &Path) {
    let kept = manifests(out);
    let Some(&(oldest_kept, _)) = kept.get(KEEP - 1) else {
        return;
    };
    if let Ok(entries) = std::fs::read_dir(out.join(FOLDER)) {
        for p in entries.filter_map(Result::ok).map(|e| e.path()) {
            if window_of(&p).is_some_and(|(w, _)| w < oldest_kept) {
                let _ = std::fs::remove_file(p);
            }
        }
    }
}

/// The newest complete checkpoint in `out` of a window before `window`, if one reads back whole.
pub fn latest_before(out: &Path, window: u64) -> Option<Manifest> {
    manifests(out)
        .iter()
        .filter(|(w, _)| *w < window)
        .find_map(|(_, path)| checkpoint::read::<Manifest>(path).ok())
}

/// The last complete checkpoint in `out`: the newest manifest that reads back whole.
pub fn latest(out: &Path) -> Result<Manifest, CouplerError> {
    let found = manifests(out);
    let mut damaged = Vec::new();
    for (_, path) in &found {
        match checkpoint::read::<Manifest>(path) {
            Ok(m) => return Ok(m),
            Err(e) => damaged.push(e),
        }
    }
    Err(CouplerError::Usage(if damaged.is_empty() {
        format!(
            "--resume {}: the folder holds no complete checkpoint (no {}/{COUPLER}-*.bin); the run can only be \
             started again (with --overwrite); set coupling.checkpoint_interval for a run that can resume",
            out.display(),
            FOLDER
        )
    } else {
        format!(
            "--resume {}: no checkpoint reads back whole: {}",
            out.display(),
            damaged.join("; ")
        )
    }))
}

/// The file of participant `name`'s state in the checkpoint of `manifest`.
pub fn participant_file(out: &Path, name: &str, manifest: &Manifest) -> Result<PathBuf, CouplerError> {
    let path = checkpoint::file(out, name, manifest.window);
    if path.is_file() {
        Ok(path)
    } else {
        Err(CouplerError::Usage(format!(
            "--resume {}: the checkpoint of window {} lacks {}",
            out.display(),
            manifest.window,
            path.display()
        )))
    }
}

/// Whether `rel` (a path relative to the output folder) is an output file whose length a
/// checkpoint keeps: not the lock, a log, a checkpoint or a temporary file.
fn is_output(rel: &Path) -> bool {
    let name = rel.file_name().and_then(|n| n.to_str()).unwrap_or_default();
    !(rel.starts_with(FOLDER) || name == LOCK_FILE || name.ends_with(".log") || name.ends_with(".tmp"))
}

/// Every output file under `out` with its length, sorted by path.
pub fn output_files(out: &Path) -> Result<Vec<(String, u64)>, CouplerError> {
    fn walk(root: &Path, dir: &Path, found: &mut Vec<(String, u64)>) -> std::io::Result<()> {
        for entry in std::fs::read_dir(dir)? {
            let entry = entry?;
            let path = entry.path();
            let rel = path.strip_prefix(root).unwrap_or(&path).to_path_buf();
            if entry.file_type()?.is_dir() {
                if !rel.starts_with(FOLDER) {
                    walk(root, &path, found)?;
                }
            } else if is_output(&rel) {
                found.push((rel.display().to_string(), entry.metadata()?.len()));
            }
        }
        Ok(())
    }
    let mut found = Vec::new();
    walk(out, out, &mut found)
        .map_err(|e| CouplerError::Io(format!("cannot list the output folder {}: {e}", out.display())))?;
    found.sort();
    Ok(found)
}

/// Cuts every output file back to its length in `manifest` and deletes those written after it,
/// and the checkpoints of later windows (manifests first: a later manifest would describe outputs
/// that are no longer there). A file shorter than it was, or gone, cannot be continued: that is
/// an error naming it.
pub fn cut_back(out: &Path, manifest: &Manifest) -> Result<(), CouplerError> {
    let now = output_files(out)?;
    let io = |what: &str, path: &Path, e: std::io::Error| {
        CouplerError::Io(format!("--resume: cannot {what} {}: {e}", path.display()))
    };
    for (rel, len) in &manifest.files {
        let path = out.join(rel);
        let current = now.iter().find(|(r, _)| r == rel).map(|(_, l)| *l);
        match current {
            Some(l) if l >= *len => {
                if l > *len {
                    std::fs::OpenOptions::new()
                        .write(true)
                        .open(&path)
                        .and_then(|f| f.set_len(*len))
                        .map_err(|e| io("cut back", &path, e))?;
                }
            }
            Some(l) => {
                return Err(CouplerError::Usage(format!(
                    "--resume {}: {} holds {l} bytes, fewer than the {len} it held at the checkpoint of window {}; \
                     the output was changed after the run, so it cannot be continued",
                    out.display(),
                    path.display(),
                    manifest.window
                )))
            }
            None => {
                return Err(CouplerError::Usage(format!(
                    "--resume {}: {} is gone (it was written before the checkpoint of window {}); the output cannot \
                     be continued",
                    out.display(),
                    path.display(),
                    manifest.window
                )))
            }
        }
    }
    for (rel, _) in now
        .iter()
        .filter(|(r, _)| !manifest.files.iter().any(|(m, _)| m == r))
    {
        let path = out.join(rel);
        std::fs::remove_file(&path).map_err(|e| io("delete", &path, e))?;
    }
    for (_, path) in manifests(out).iter().filter(|(w, _)| *w > manifest.window) {
        std::fs::remove_file(path).map_err(|e| io("delete", path, e))?;
    }
    // checkpoint files cut short by the end of the first run, and those of later windows
    for entry in std::fs::read_dir(out.join(FOLDER))
        .into_iter()
        .flatten()
        .filter_map(Result::ok)
    {
        let later = window_of(&entry.path()).is_some_and(|(w, _)| w > manifest.window);
        if later || entry.file_name().to_string_lossy().ends_with(".tmp") {
            let _ = std::fs::remove_file(entry.path());
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn window_numbers_are_read_from_file_names() {
        assert_eq!(
            window_of(Path::new("checkpoint/coupler-000000012.bin")),
            Some((12, true))
        );
        assert_eq!(
            window_of(Path::new("checkpoint/my-tank-000000003.bin")),
            Some((3, false))
        );
        assert_eq!(window_of(Path::new("checkpoint/tank-3.bin.tmp")), None);
        assert!(!is_output(Path::new("tank.log")));
        assert!(!is_output(Path::new("checkpoint/tank-000000003.bin")));
        assert!(is_output(Path::new("tank/tank_probes.csv")));
    }
}
