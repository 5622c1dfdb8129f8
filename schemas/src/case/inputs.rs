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

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::Path;

    const CASE: &str = "[case]\nname = \"m\"\nend_time = 1.0\n\n[structure.s]\nmax_step = 0.01\n\n\
                        [[structure.s.point_mass]]\nname = \"m\"\nmass = 2.0\nposition = [0, 0, 0]\n";

    fn hashes(text: &str) -> Vec<(String, u64)> {
        Case::parse(Path::new("case.toml"), text.to_string())
            .unwrap_or_else(|e| panic!("{e}"))
            .input_hashes()
    }

    #[test]
    fn comments_layout_and_the_end_time_leave_the_settings_hash_alone() {
        let before = hashes(CASE);
        let commented = format!(
            "# a note\n{}",
            CASE.replace("mass = 2.0", "mass   =   2.0   # kg")
        );
        assert_eq!(hashes(&commented), before, "comments and layout");
        let reordered = CASE.replace("name = \"m\"\nmass = 2.0", "mass = 2.0\nname = \"m\"");
        assert_ne!(reordered, CASE);
        assert_eq!(hashes(&reordered), before, "the order of keys in a table");
        assert_eq!(
            hashes(&CASE.replace("end_time = 1.0", "end_time = 3.5")),
            before,
            "case.end_time"
        );
    }

    #[test]
    fn a_changed_value_changes_the_settings_hash() {
        let before = hashes(CASE);
        let heavier = hashes(&CASE.replace("mass = 2.0", "mass = 2.5"));
        assert_eq!(heavier[0].0, SETTINGS);
        assert_ne!(heavier[0].1, before[0].1);
        let renamed = hashes(&CASE.replace("name = \"m\"\nend", "name = \"n\"\nend"));
        assert_ne!(renamed[0].1, before[0].1, "the rest of [case] still counts");
    }
}
