//! Helpers shared by the integration tests: loading the cases of `cases/`.

use schemas::case::{Case, FluidConfig};
use std::path::PathBuf;

/// Loads `cases/<name>/case.toml` and returns the case with its single fluid section.
pub fn load_case(name: &str) -> (Case, FluidConfig) {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../cases")
        .join(name)
        .join("case.toml");
    let case = Case::load(&path).unwrap_or_else(|e| panic!("{e}"));
    let cfg = case
        .fluid
        .values()
        .next()
        .cloned()
        .unwrap_or_else(|| panic!("{name} has no fluid section"));
    (case, cfg)
}
