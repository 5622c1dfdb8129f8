//! [`Output`]: everything a structure run writes to its folder — the CSV histories
//! ([`HistoryWriter`]), the frame's tables ([`FrameTables`]: section forces at the history times,
//! hinge events), the frame's VTU series ([`VtuSeries`]) at the history times (or every
//! `vtu_interval`, or none), and `releases.csv` (one row per support: body, release time or
//! empty) at the end.

use crate::frame_tables::FrameTables;
use crate::history::HistoryWriter;
use crate::structure::Structure;
use crate::vtu_series::VtuSeries;
use schemas::case::structure::StructureConfig;
use std::io::Write;
use std::path::{Path, PathBuf};

/// The output folder of one structure participant.
pub struct Output {
    dir: PathBuf,
    history: Option<HistoryWriter>,
    tables: Option<FrameTables>,
    vtu: Option<VtuSeries>,
    /// VTU interval [s] (`None`: every record) and the next time a snapshot is due.
    vtu_interval: Option<f64>,
    vtu_due: f64,
}

impl Output {
    /// Creates `dir` and the history files declared in `cfg`. The frame tables need the frame's
    /// hinge events recorded ([`Structure::record_hinge_events`]).
    pub fn create(dir: &Path, cfg: &StructureConfig, s: &Structure) -> Result<Self, String> {
        std::fs::create_dir_all(dir).map_err(|e| format!("cannot create {}: {e}", dir.display()))?;
        let history = cfg
            .history
            .as_ref()
            .map(|h| HistoryWriter::create(dir, h, s))
            .transpose()?;
        let h = cfg.history.as_ref();
        let tables = s
            .frame()
            .map(|f| FrameTables::create(dir, h.is_some_and(|h| h.section_forces), f.energy().is_some()))
            .transpose()
            .map_err(|e| format!("cannot create the frame tables in {}: {e}", dir.display()))?;
        let vtu = s
            .frame()
            .filter(|_| h.is_none_or(|h| h.vtu))
            .map(|_| VtuSeries::new(dir));
        Ok(Self {
            dir: dir.to_path_buf(),
            history,
            tables,
            vtu,
            vtu_interval: h.and_then(|h| h.vtu_interval),
            vtu_due: 0.0,
        })
    }

    /// Continues the output of a resumed run in `dir`: the histories are appended to. Structures
    /// with a frame do not resume (see [`crate::structure::Structure`]), so there are no frame
    /// tables or VTU series to continue.
    pub fn resume(dir: &Path, cfg: &StructureConfig, s: &Structure) -> Result<Self, String> {
        let history = cfg
            .history
            .as_ref()
            .map(|h| HistoryWriter::append(dir, h, s))
            .transpose()?;
        Ok(Self {
            dir: dir.to_path_buf(),
            history,
            tables: None,
            vtu: None,
            vtu_interval: None,
            vtu_due: 0.0,
        })
    }

    pub fn dir(&self) -> &Path {
        &self.dir
    }

    /// Writes one history row per file and a frame snapshot for the state `s`.
    pub fn record(&mut self, s: &Structure) -> Result<(), String> {
        if let Some(h) = &mut self.history {
            h.record(s).map_err(|e| self.error(e))?;
        }
        if let (Some(tables), Some(frame)) = (&mut self.tables, s.frame()) {
            tables
                .record(frame, s.time(), true)
                .map_err(|e| format!("writing to {}: {e}", self.dir.display()))?;
        }
        let t = s.time();
        let due = self.vtu_interval.is_none_or(|i| t >= self.vtu_due - 1e-9 * i);
        if let (Some(series), Some(frame), true) = (&mut self.vtu, s.frame(), due) {
            series
                .write(frame, t)
                .map_err(|e| format!("writing to {}: {e}", self.dir.display()))?;
            if let Some(i) = self.vtu_interval {
                self.vtu_due = ((t / i + 1e-9).floor() + 1.0) * i;
            }
        }
        Ok(())
    }

    /// Flushes the histories and writes `releases.csv` when there are supports.
    pub fn finish(&mut self, s: &Structure) -> Result<(), String> {
        if let Some(h) = &mut self.history {
            h.flush()
                .map_err(|e| format!("writing to {}: {e}", self.dir.display()))?;
        }
        if let (Some(tables), Some(frame)) = (&mut self.tables, s.frame()) {
            tables
                .record(frame, s.time(), false)
                .and_then(|()| tables.flush())
                .map_err(|e| format!("writing to {}: {e}", self.dir.display()))?;
        }
        if !s.supports().is_empty() {
            write_releases(&self.dir.join("releases.csv"), s).map_err(|e| self.error(e))?;
        }
        Ok(())
    }

    fn error(&self, e: std::io::Error) -> String {
        format!("writing to {}: {e}", self.dir.display())
    }
}

/// Output times of a history with `interval` up to `end`: interval, 2·interval, …, end.
pub fn output_times(interval: f64, end: f64) -> Vec<f64> {
    let n = crate::structure::equal_steps(end, interval);
    (1..=n)
        .map(|k| if k == n { end } else { interval * k as f64 })
        .collect()
}

/// `body,release_time` per support; the time is empty for a body never released.
fn write_releases(path: &Path, s: &Structure) -> std::io::Result<()> {
    let mut f = std::io::BufWriter::new(std::fs::File::create(path)?);
    writeln!(f, "body,release_time")?;
    for support in s.supports() {
        let time = support.released_at.map(|t| t.to_string()).unwrap_or_default();
        writeln!(f, "{},{time}", s.bodies()[support.body].name)?;
    }
    f.flush()
}
