//! A standalone run of a small case on one backend, read back as its probe CSV's rows: what the
//! tests of probes on the GPU path compare with the CPU's.

use fluid_solver::run::run_case;
use schemas::case::Case;
use std::path::{Path, PathBuf};

/// Runs `text` (a fluid-only case whose section is `section` and whose first `spacing = …` line
/// gets the backend) on `backend`; returns the rows of its probe CSV and the run's whole copies
/// from the GPU.
pub fn probe_rows(text: &str, section: &str, backend: &str) -> (Vec<Vec<f64>>, u64) {
    let text = text.replacen(
        "\nspacing = ",
        &format!("\nbackend = \"{backend}\"\nspacing = "),
        1,
    );
    let case = Case::parse(Path::new("probes.toml"), text).unwrap_or_else(|e| panic!("{e}"));
    let out = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(format!("probe_rows_{section}_{backend}"));
    let summary = run_case(&case, &out, false).unwrap_or_else(|e| panic!("{e}"));
    let path = out.join(format!("{section}_probes.csv"));
    let csv = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let rows = csv
        .lines()
        .skip(1)
        .map(|l| {
            l.split(',')
                .map(|v| v.parse().unwrap_or_else(|e| panic!("{v}: {e}")))
                .collect()
        })
        .collect();
    (rows, summary.host_copies.0)
}
