//! The probe CSV of a fluid participant (in one process or on MPI ranks): rows sampled at the
//! window times they fall due, written once the window is accepted, so a repeated implicit
//! iteration never writes twice; the filtered probes' readings kept with the window's start.

use crate::sensors::probes::{ProbeFile, ProbeSet};
use crate::solver::FluidSolver;
use serde::{Deserialize, Serialize};
use std::collections::VecDeque;
use std::path::PathBuf;

/// What a checkpoint keeps of the probe rows: rows written, and the filtered probes' readings
/// (time, value) in their windows.
#[derive(Serialize, Deserialize)]
pub(crate) struct SavedProbes {
    written: u64,
    windows: Vec<Option<VecDeque<(f64, f64)>>>,
}

/// Probe rows of a participant and where they go.
pub(crate) struct ProbeRows {
    path: PathBuf,
    /// The file (none on the MPI ranks other than 0, which only read their probes).
    file: Option<ProbeFile>,
    pub probes: ProbeSet,
    /// The filters' readings at the window's start (an implicit window's checkpoint).
    saved: Option<ProbeSet>,
    interval: f64,
    /// Rows written so far.
    written: u64,
    /// Rows sampled in the window not yet accepted: time, values, fluid removed.
    pending: Vec<(f64, Vec<f64>, u64)>,
}

impl ProbeRows {
    /// Rows of `probes` into `file` at `path` every `interval`, from the first (a resumed run
    /// continues from its checkpoint's: [`ProbeRows::continue_from`]).
    pub fn new(path: PathBuf, file: Option<ProbeFile>, probes: ProbeSet, interval: f64) -> ProbeRows {
        ProbeRows {
            path,
            file,
            probes,
            saved: None,
            interval,
            written: 0,
            pending: Vec::new(),
        }
    }

    /// Whether a row falls due at `t` (the next row's time reached).
    pub fn due(&self, t: f64) -> bool {
        t >= self.next_row() - 1e-9 * self.interval
    }

    /// Time of the next row.
    pub fn next_row(&self) -> f64 {
        (self.written + self.pending.len() as u64) as f64 * self.interval
    }

    /// Samples every probe of `solver` now and keeps the row until the window is accepted.
    pub fn sample(&mut self, solver: &FluidSolver) {
        let values = self.probes.row(solver);
        self.keep(solver.time(), values, solver.removed());
    }

    /// Keeps the row `values` at `t` (with `removed` fluid particles) until the window is
    /// accepted.
    pub fn keep(&mut self, t: f64, values: Vec<f64>, removed: u64) {
        self.pending.push((t, values, removed));
    }

    /// Writes the rows kept back from the accepted window.
    pub fn commit(&mut self) -> Result<(), String> {
        for (t, values, removed) in self.pending.drain(..) {
            if let Some(file) = &mut self.file {
                file.row(t, &values, removed)
                    .map_err(|e| format!("cannot write {}: {e}", self.path.display()))?;
            }
            self.written += 1;
        }
        Ok(())
    }

    /// What a checkpoint keeps of these rows (after the accepted window's rows are written).
    pub fn saved(&self) -> SavedProbes {
        SavedProbes {
            written: self.written,
            windows: self.probes.windows().to_vec(),
        }
    }

    /// Continues from a checkpoint's `saved` rows (a resumed run).
    pub fn continue_from(&mut self, saved: SavedProbes) {
        self.written = saved.written;
        self.probes.set_windows(saved.windows);
    }

    /// Keeps the filters' readings (the window's start).
    pub fn save_filters(&mut self) {
        self.saved = Some(self.probes.clone());
    }

    /// Drops the rows of the window about to be repeated and goes back to the filters' readings
    /// at its start.
    pub fn restore_filters(&mut self) {
        self.pending.clear();
        if let Some(saved) = &self.saved {
            self.probes.clone_from(saved);
        }
    }
}
