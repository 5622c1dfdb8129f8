//! The probe CSV of a fluid participant (in one process or on MPI ranks): rows sampled at the
//! window times they fall due, written once the window is accepted, so a repeated implicit
//! iteration never writes twice; the filtered probes' readings kept with the window's start.

use crate::sensors::probes::{ProbeFile, ProbeSet};
use crate::solver::FluidSolver;
use std::path::PathBuf;

/// Probe rows of a participant and where they go.
pub(crate) struct ProbeRows {
    pub path: PathBuf,
    /// The file (none on the MPI ranks other than 0, which only read their probes).
    pub file: Option<ProbeFile>,
    pub probes: ProbeSet,
    /// The filters' readings at the window's start (an implicit window's checkpoint).
    saved: Option<ProbeSet>,
    interval: f64,
    /// Rows written so far.
    pub written: u64,
    /// Rows sampled in the window not yet accepted: time, values, fluid removed.
    pending: Vec<(f64, Vec<f64>, u64)>,
}

impl ProbeRows {
    /// Rows of `probes` into `file` at `path` every `interval`, `written` of them already there.
    pub fn new(
        path: PathBuf,
        file: Option<ProbeFile>,
        probes: ProbeSet,
        interval: f64,
        written: u64,
    ) -> ProbeRows {
        ProbeRows {
            path,
            file,
            probes,
            saved: None,
            interval,
            written,
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
