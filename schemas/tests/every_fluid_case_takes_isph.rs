//! Issue 12: "ISPH runs every case that E-MPS runs, selected by one key". Every shipped case file
//! with a fluid is still a valid case with `method = "isph"` in each `[fluid.NAME]` and nothing
//! else changed: the case check accepts its time step against ISPH's advective and viscous
//! limits, its walls, gates, open boundaries, bodies, probes and couplings, and its E-MPS-only
//! keys (`sound_speed`, `artificial_viscosity`) are named as unused, not refused
//! (`FluidConfig::unused_by_method`). (Each was also run with ISPH to its end or a shortened end;
//! README, "Session 14".)

use schemas::case::report::{check_settings, Settings};
use schemas::case::Case;
use std::path::PathBuf;

#[test]
fn every_shipped_fluid_case_is_valid_with_isph() {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../cases");
    let mut files: Vec<PathBuf> = std::fs::read_dir(&root)
        .unwrap_or_else(|e| panic!("{}: {e}", root.display()))
        .flatten()
        .filter(|e| e.path().is_dir())
        .flat_map(|dir| std::fs::read_dir(dir.path()).into_iter().flatten().flatten())
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    files.sort();
    let mut checked = 0;
    for file in &files {
        let case = Case::load(file).unwrap_or_else(|e| panic!("{}: {e}", file.display()));
        for name in case.fluid.keys() {
            let key = format!("fluid.{name}");
            let mut settings = Settings::new();
            settings.insert(format!("{key}.method"), toml::Value::String("isph".into()));
            check_settings(&case, &key, &settings, true)
                .unwrap_or_else(|e| panic!("{} with ISPH: `{}`: {}", file.display(), e.key, e.message));
            checked += 1;
        }
    }
    println!(
        "{checked} fluid sections of {} case files valid with ISPH",
        files.len()
    );
    assert!(checked >= 12, "only {checked} fluid sections found under cases/");
}
