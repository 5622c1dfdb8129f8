//! [`Output`]: everything a structure run writes to its folder — the CSV histories
//! ([`HistoryWriter`]), the frame's tables ([`FrameTables`]: section forces at the history times,
//! hinge events), the frame's VTU series ([`VtuSeries`]) at the history times (or every
//! `vtu_interval`, or none), and `releases.csv` (`body,release_time`: a row per release, written
//! at the first record after it, and at the end a row with an empty time per body never released).
//! Every row reaches its file whole when it is written, so a run that ends abnormally, even killed,
//! leaves whole rows.

use crate::frame_tables::FrameTables;
use crate::history::HistoryWriter;
use crate::structure::Structure;
use crate::vtu_series::VtuSeries;
use schemas::case::structure::StructureConfig;
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

/// Where each output of a structure participant stands at a checkpoint.
#[derive(Clone, Debug, Default, serde::Serialize, serde::Deserialize)]
pub struct OutputState {
    /// Hinge events written to `hinge-events.csv`.
    events_written: usize,
    /// Time and file of each frame snapshot listed in `frame.pvd`.
    vtu_frames: Vec<(f64, String)>,
    /// The next time a snapshot is due (with `vtu_interval`).
    vtu_due: f64,
    /// Which supports' releases `releases.csv` has.
    releases_written: Vec<bool>,
}

/// The output folder of one structure participant.
pub struct Output {
    dir: PathBuf,
    history: Option<HistoryWriter>,
    tables: Option<FrameTables>,
    /// `releases.csv` (when there are supports) and which supports' releases it has.
    releases: Option<(BufWriter<File>, Vec<bool>)>,
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
        let releases = (!s.supports().is_empty())
            .then(|| -> std::io::Result<_> {
                let mut w = BufWriter::new(File::create(dir.join("releases.csv"))?);
                w.write_all(b"body,release_time\n")?;
                w.flush()?;
                Ok((w, vec![false; s.supports().len()]))
            })
            .transpose()
            .map_err(|e| format!("cannot create {}: {e}", dir.join("releases.csv").display()))?;
        Ok(Self {
            dir: dir.to_path_buf(),
            history,
            tables,
            releases,
            vtu,
            vtu_interval: h.and_then(|h| h.vtu_interval),
            vtu_due: 0.0,
        })
    }

    /// Where each output stands, for a checkpoint: what [`Output::resume`] continues from.
    pub fn state(&self) -> OutputState {
        OutputState {
            events_written: self.tables.as_ref().map_or(0, FrameTables::events_written),
            vtu_frames: self.vtu.as_ref().map(|v| v.frames().to_vec()).unwrap_or_default(),
            vtu_due: self.vtu_due,
            releases_written: self.releases.as_ref().map(|(_, w)| w.clone()).unwrap_or_default(),
        }
    }

    /// Continues the output of a resumed run in `dir` from `state` (the coupler has cut every file
    /// back to its length at the checkpoint): the histories, the frame tables and `releases.csv`
    /// are appended to, and the frame's `.pvd` is rewritten to list the snapshots written before
    /// the checkpoint.
    pub fn resume(
        dir: &Path,
        cfg: &StructureConfig,
        s: &Structure,
        state: &OutputState,
    ) -> Result<Self, String> {
        let history = cfg
            .history
            .as_ref()
            .map(|h| HistoryWriter::append(dir, h, s))
            .transpose()?;
        let h = cfg.history.as_ref();
        let tables = s
            .frame()
            .map(|f| {
                FrameTables::append(
                    dir,
                    h.is_some_and(|h| h.section_forces),
                    f.energy().is_some(),
                    state.events_written,
                )
            })
            .transpose()
            .map_err(|e| format!("cannot continue the frame tables in {}: {e}", dir.display()))?;
        let vtu = s
            .frame()
            .filter(|_| h.is_none_or(|h| h.vtu))
            .map(|_| VtuSeries::resumed(dir, state.vtu_frames.clone()))
            .transpose()
            .map_err(|e| format!("cannot continue the frame series in {}: {e}", dir.display()))?;
        let releases = (!s.supports().is_empty())
            .then(|| -> std::io::Result<_> {
                let w = BufWriter::new(schemas::checkpoint::append(&dir.join("releases.csv"))?);
                let mut written = state.releases_written.clone();
                written.resize(s.supports().len(), false);
                Ok((w, written))
            })
            .transpose()
            .map_err(|e| format!("cannot continue {}: {e}", dir.join("releases.csv").display()))?;
        Ok(Self {
            dir: dir.to_path_buf(),
            history,
            tables,
            releases,
            vtu,
            vtu_interval: h.and_then(|h| h.vtu_interval),
            vtu_due: state.vtu_due,
        })
    }

    pub fn dir(&self) -> &Path {
        &self.dir
    }

    /// Writes one history row per file, the releases since the last record and a frame snapshot
    /// for the state `s`.
    pub fn record(&mut self, s: &Structure) -> Result<(), String> {
        if let Some(h) = &mut self.history {
            h.record(s).map_err(|e| self.error(e))?;
        }
        self.write_releases(s, false).map_err(|e| self.error(e))?;
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

    /// Flushes the histories and ends `releases.csv` (a row per body never released).
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
        self.write_releases(s, true).map_err(|e| self.error(e))
    }

    /// Writes a `body,release_time` row, and flushes it, for every support of `s` released since
    /// the last call; with `end`, also one with an empty time for every support never released.
    fn write_releases(&mut self, s: &Structure, end: bool) -> std::io::Result<()> {
        let Some((w, written)) = &mut self.releases else {
            return Ok(());
        };
        for (support, written) in s.supports().iter().zip(written.iter_mut()) {
            let time = match support.released_at {
                Some(t) => t.to_string(),
                None if end => String::new(),
                None => continue,
            };
            if !*written {
                let row = format!("{},{time}\n", s.bodies()[support.body].name);
                w.write_all(row.as_bytes())?;
                w.flush()?;
                *written = true;
            }
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
