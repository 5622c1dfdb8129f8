//! The record a validation test writes: one measured comparison against an independent reference,
//! stored as `out/validation/<id>.toml` and collected into `docs/validation/records/` by
//! `coupler validation --collect`, which renders them as the rows of docs/validation.md.

use std::path::{Path, PathBuf};
use std::time::{SystemTime, UNIX_EPOCH};

/// One measured comparison against an independent reference: a row of docs/validation.md.
#[derive(Debug, Clone, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Record {
    /// Unique, stable id, lowercase-with-dashes, e.g. "emps-front-martin-moyce-l10".
    pub id: String,
    /// What capability is validated, e.g. "E-MPS dam-break front", "ASI-Gauss cantilever tip".
    pub capability: String,
    /// The independent reference, e.g. "Martin & Moyce (1952) experiment", "Timoshenko closed form".
    pub reference: String,
    /// The case or scene, e.g. "cases/dam-break-koshizuka" or "closed box, 8 cm cube drop".
    pub case: String,
    /// Method and resolution, e.g. "E-MPS, Δs = L/10 (2 000 particles)".
    pub resolution: String,
    /// What the error measures, e.g. "RMS of front position / L".
    pub measure: String,
    /// The measured error (in `unit`); NaN when the comparison is not reproduced (see `note`).
    pub value: f64,
    /// The bound the test asserts (None: reported, not asserted).
    pub bound: Option<f64>,
    /// Where the bound comes from (the reference's own spread, the paper, a measured spread …).
    pub bound_source: String,
    /// Unit of value and bound ("" for dimensionless, "%" for percent, "N s", …).
    pub unit: String,
    /// "crate/tests/file.rs::test_name" for a test, or the command for a one-off run.
    pub source: String,
    /// Wall time of the run that produced the value [s].
    pub run_time_s: f64,
    /// UTC date of the measurement, "YYYY-MM-DD" (filled by `record`).
    pub date: String,
    /// The machine, e.g. "2 cores, AMD EPYC 7B13, 24 GiB" (filled by `record`).
    pub machine: String,
    /// A remark shown with the row, e.g. why a comparison is not reproduced (`value` NaN).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub note: Option<String>,
}

/// The variable that, when set, names the folder records are written to instead of
/// `<workspace>/out/validation`.
pub const RECORDS_DIR_VAR: &str = "VALIDATION_RECORDS";

/// Writes `record` (date and machine filled in here when empty) to `<workspace>/out/validation/<id>.toml`,
/// or to `$VALIDATION_RECORDS/<id>.toml` when that variable is set. An I/O failure is printed to
/// stderr, never panics: a test's verdict is its own assertions, not whether the record could be written.
pub fn record(mut record: Record) {
    if record.date.is_empty() {
        record.date = utc_date(SystemTime::now());
    }
    if record.machine.is_empty() {
        record.machine = machine();
    }
    let dir = match std::env::var_os(RECORDS_DIR_VAR) {
        Some(dir) => PathBuf::from(dir),
        None => workspace_root().join("out").join("validation"),
    };
    if let Err(e) = write(&dir, &record) {
        eprintln!(
            "validation record {}: not written to {}: {e}",
            record.id,
            dir.display()
        );
    }
}

/// Writes `record` as `<dir>/<id>.toml`, creating `dir`.
pub fn write(dir: &Path, record: &Record) -> std::io::Result<()> {
    let text = toml::to_string(record).map_err(std::io::Error::other)?;
    std::fs::create_dir_all(dir)?;
    crate::atomic_file::write(&dir.join(format!("{}.toml", record.id)), text)
}

/// Reads a record written by [`write`].
pub fn read(path: &Path) -> Result<Record, String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))?;
    toml::from_str(&text).map_err(|e| format!("{}: {e}", path.display()))
}

/// The workspace root: the first folder above the running crate's manifest (CARGO_MANIFEST_DIR at run
/// time, else this crate's) whose Cargo.toml declares `[workspace]`; the current folder if none does.
fn workspace_root() -> PathBuf {
    let start = std::env::var_os("CARGO_MANIFEST_DIR")
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from(env!("CARGO_MANIFEST_DIR")));
    start
        .ancestors()
        .find(|dir| {
            std::fs::read_to_string(dir.join("Cargo.toml"))
                .is_ok_and(|text| text.lines().any(|line| line.trim() == "[workspace]"))
        })
        .map(Path::to_path_buf)
        .unwrap_or_else(|| PathBuf::from("."))
}

/// `time` as a UTC calendar date, "YYYY-MM-DD".
pub fn utc_date(time: SystemTime) -> String {
    let days = time
        .duration_since(UNIX_EPOCH)
        .map_or(0, |d| d.as_secs() / 86_400) as i64;
    let (year, month, day) = civil_from_days(days);
    format!("{year:04}-{month:02}-{day:02}")
}

/// The proleptic Gregorian date `days` after 1970-01-01 (H. Hinnant's civil_from_days).
pub fn civil_from_days(days: i64) -> (i64, u32, u32) {
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z.rem_euclid(146_097);
    let yoe = (doe - doe / 1_460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let day = (doy - (153 * mp + 2) / 5 + 1) as u32;
    let month = if mp < 10 { mp + 3 } else { mp - 9 } as u32;
    let year = yoe + era * 400 + i64::from(month <= 2);
    (year, month, day)
}

/// This machine in words: "N cores, CPU MODEL, M GiB" (the parts Linux's /proc tells); what
/// [`record`] fills in, for a test that names more (e.g. its GPU) before it.
pub fn machine() -> String {
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    let mut parts = vec![format!("{cores} cores")];
    let cpuinfo = std::fs::read_to_string("/proc/cpuinfo").unwrap_or_default();
    if let Some(model) = proc_field(&cpuinfo, "model name") {
        parts.push(model.to_string());
    }
    let meminfo = std::fs::read_to_string("/proc/meminfo").unwrap_or_default();
    let kib =
        proc_field(&meminfo, "MemTotal").and_then(|v| v.trim_end_matches("kB").trim().parse::<f64>().ok());
    if let Some(kib) = kib {
        parts.push(format!("{:.0} GiB", kib / (1024.0 * 1024.0)));
    }
    parts.join(", ")
}

/// The value of the first `key: value` line of a /proc file.
fn proc_field<'a>(text: &'a str, key: &str) -> Option<&'a str> {
    text.lines()
        .filter_map(|line| line.split_once(':'))
        .find(|(k, _)| k.trim() == key)
        .map(|(_, v)| v.trim())
}

/// The largest |value| of `values`, NaN if any of them is NaN (0 for none): the error a record
/// reports over axes or samples. `fold(0.0, f64::max)` would skip a NaN and report the others'
/// largest, so a blown-up run could read as a small error.
pub fn largest_abs(values: impl IntoIterator<Item = f64>) -> f64 {
    largest(values.into_iter().map(f64::abs), 0.0)
}

/// The largest of `values` and `floor`, NaN if any of them is NaN (unlike `f64::max`, which
/// skips a NaN).
pub fn largest(values: impl IntoIterator<Item = f64>, floor: f64) -> f64 {
    values.into_iter().fold(floor, max_or_nan)
}

/// The larger of `a` and `b`, NaN if either is (for `fold`, where `f64::max` would skip a NaN).
pub fn max_or_nan(a: f64, b: f64) -> f64 {
    if a.is_nan() || b.is_nan() {
        f64::NAN
    } else {
        a.max(b)
    }
}

/// The smallest of `values` and `ceiling`, NaN if any of them is NaN (unlike `f64::min`).
pub fn smallest(values: impl IntoIterator<Item = f64>, ceiling: f64) -> f64 {
    -largest(values.into_iter().map(|v| -v), -ceiling)
}
