//! [`Output`]: everything a structure run writes to its folder — the CSV histories
//! ([`HistoryWriter`]), the frame's VTU series ([`VtuSeries`]) at the history times, and
//! `releases.csv` (one row per support: body, release time or empty) at the end.

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
    vtu: Option<VtuSeries>,
}

impl Output {
    /// Creates `dir` and the history files declared in `cfg`.
    pub fn create(dir: &Path, cfg: &StructureConfig, s: &Structure) -> Result<Self, String> {
        std::fs::create_dir_all(dir).map_err(|e| format!("cannot create {}: {e}", dir.display()))?;
        let history = cfg
            .history
            .as_ref()
            .map(|h| HistoryWriter::create(dir, h, s))
            .transpose()?;
        let vtu = s.frame().map(|_| VtuSeries::new(dir));
        Ok(Self {
            dir: dir.to_path_buf(),
            history,
            vtu,
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
        if let (Some(series), Some(frame)) = (&mut self.vtu, s.frame()) {
            series
                .write(frame, s.time())
                .map_err(|e| format!("writing to {}: {e}", self.dir.display()))?;
        }
        Ok(())
    }

    /// Flushes the histories and writes `releases.csv` when there are supports.
    pub fn finish(&mut self, s: &Structure) -> Result<(), String> {
        if let Some(h) = &mut self.history {
            h.flush()
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
