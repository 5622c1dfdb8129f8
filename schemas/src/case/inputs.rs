//! What a run's result depends on besides the code: the case's settings (its TOML as parsed, so
//! comments and layout do not count) and the bytes of every file it names (load tables, meshes,
//! height grids, stroke tables, inflow series). A checkpoint keeps their hashes, and a resume refuses a case
//! whose settings or files changed since, naming which ([`Case::input_hashes`]).
//!
//! `case.end_time` is not among the settings: it says how far the run goes, not what it computes
//! on the way, so a run resumed with a later end time (`coupler run --resume OUT --end-time T`,
//! or the case's `end_time` edited) continues the same run.

use super::{fnv1a, Case};
use std::path::PathBuf;

/// The name the case's settings go by in [`Case::input_hashes`].
pub const SETTINGS: &str = "the case's settings";

impl Case {
    /// Every file the case names that its solvers read, resolved against the case's folder:
    /// structure load tables, solid meshes, terrain grids, wave-maker stroke tables and inflow
    /// series (not the executables: a solver swapped for another is the user's call).
    pub fn named_files(&self) -> Vec<PathBuf> {
        let tables = self
            .structure
            .values()
            .flat_map(|s| s.load.iter().filter_map(|l| l.table.as_ref()));
        let meshes = self.fluid.values().flat_map(|f| f.solid.iter().map(|s| &s.mesh));
        let grids = self
            .fluid
            .values()
            .flat_map(|f| f.terrain.iter().filter_map(|t| t.grid.as_ref()));
        let strokes = self
            .fluid
            .values()
            .filter_map(|f| f.wave_maker.as_ref().and_then(|w| w.table.as_ref()));
        let series = self
            .fluid
            .values()
            .filter_map(|f| f.inflow.as_ref().and_then(|i| i.series.as_ref()));
        tables
            .chain(meshes)
            .chain(grids)
            .chain(strokes)
            .chain(series)
            .map(|p| self.resolve(p))
            .collect()
    }

    /// `(what, FNV-1a hash)` of the case's settings ([`SETTINGS`]: the parsed TOML but for
    /// `case.end_time`, written back without comments or layout) and of each of
    /// [`Case::named_files`] by its path (0 for a file that cannot be read).
    pub fn input_hashes(&self) -> Vec<(String, u64)> {
        let settings = toml::from_str::<toml::Value>(&self.text)
            .ok()
            .map(|mut v| {
                if let Some(info) = v.get_mut("case").and_then(toml::Value::as_table_mut) {
                    info.remove("end_time");
                }
                v
            })
            .and_then(|v| toml::to_string(&v).ok())
            .unwrap_or_else(|| self.text.clone());
        let mut hashes = vec![(SETTINGS.to_string(), fnv1a(settings.as_bytes()))];
        for file in self.named_files() {
            let hash = std::fs::read(&file).map_or(0, |bytes| fnv1a(&bytes));
            hashes.push((file.display().to_string(), hash));
        }
        hashes
    }
}
