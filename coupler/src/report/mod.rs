//! `coupler report`: runs cases as a user would (`coupler run` with changed settings, the same
//! binaries and processes) and measures them from outside.
//!
//! - `coupler report CASE…`: each case's `[report]` ladders against its `[reference]`: the
//!   work–precision table (`accuracy.csv`, `accuracy.md`), observed orders, a summary and a
//!   plot per case (`CASE-work-precision.png`).
//! - `--stability`: the cases' families of stiff and extreme runs, each stable, stopped (with
//!   the diagnostic), refused by the case check, or failed silently (`stability.csv`,
//!   `stability.md`, maps as PNG).
//! - `--docs`: puts the latest report into docs/validation.md's fragments (`docs/validation/report-*.md`)
//!   and its figures into docs/img/; `coupler validation` then renders the page.
//!
//! Rows are written as each run finishes; Ctrl-C stops the running run, keeps the finished rows
//! and names the missing ones in the Markdown.

pub mod accuracy;
pub mod case_copy;
pub mod docs;
pub mod error_measure;
pub mod line_plot;
pub mod measure;
pub mod order;
pub mod plot;
pub mod progress;
pub mod stability;
pub mod summary;
pub mod table;
pub mod work;

use crate::error::CouplerError;
use schemas::case::Case;
use schemas::signals;
use std::fmt::Write as _;
use std::path::PathBuf;

/// What `coupler report` was asked to do.
pub struct ReportOptions {
    pub cases: Vec<PathBuf>,
    /// Report folder (default `out/report`).
    pub out: Option<PathBuf>,
    /// The full ladders and families instead of the CI-sized ones.
    pub full: bool,
    /// The stability families instead of the work–precision ladders.
    pub stability: bool,
    /// Timed runs after the warm-up, instead of each case's `report.repeats`.
    pub repeats: Option<u32>,
    /// Put the latest report into this docs folder's validation fragments instead of running anything.
    pub docs: Option<PathBuf>,
    /// Only the stability families of these names (all when empty).
    pub families: Vec<String>,
}

/// The report folder.
pub fn folder(opts: &ReportOptions) -> PathBuf {
    opts.out
        .clone()
        .unwrap_or_else(|| PathBuf::from("out").join("report"))
}

/// Runs the report; `Interrupted` after Ctrl-C (the finished rows are kept).
pub fn report(opts: &ReportOptions) -> Result<(), CouplerError> {
    let out = folder(opts);
    if let Some(docs_dir) = &opts.docs {
        let root = docs_dir.parent().unwrap_or(std::path::Path::new("."));
        let layout = crate::validation::layout::Layout::new(root);
        let done = docs::update(&layout, &out, opts.full).map_err(CouplerError::Io)?;
        crate::say!(
            "{}: {} from {}; now run `coupler validation` to render {}",
            layout.data().display(),
            done.join(", "),
            out.display(),
            layout.page().display()
        );
        return Ok(());
    }
    if opts.cases.is_empty() {
        return Err(CouplerError::Usage(
            "name at least one case: coupler report CASE… (or --docs)".into(),
        ));
    }
    let cases = opts
        .cases
        .iter()
        .map(|p| Case::load(p).map_err(CouplerError::from))
        .collect::<Result<Vec<_>, _>>()?;
    if !opts.stability {
        for case in &cases {
            accuracy::sections(case).map_err(CouplerError::Usage)?;
        }
    }
    std::fs::create_dir_all(&out)
        .map_err(|e| CouplerError::Io(format!("cannot create the report folder {}: {e}", out.display())))?;
    signals::install();
    let stamp = stamp();
    let missing = if opts.stability {
        run_stability(&cases, opts, &out, &stamp)?
    } else {
        run_accuracy(&cases, opts, &out, &stamp)?
    };
    if missing.is_empty() {
        crate::say!("report: {}", out.display());
        Ok(())
    } else {
        crate::say!(
            "report interrupted: the finished rows are in {}; missing: {}",
            out.display(),
            missing.join("; ")
        );
        Err(CouplerError::Interrupted { window: None })
    }
}

/// When and where the report was made.
fn stamp() -> String {
    let date = std::process::Command::new("date")
        .args(["-u", "+%Y-%m-%d %H:%M UTC"])
        .output()
        .ok()
        .map(|o| String::from_utf8_lossy(&o.stdout).trim().to_string())
        .unwrap_or_default();
    let cores = std::thread::available_parallelism().map_or(0, |n| n.get());
    let cpu = std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("model name"))
                .and_then(|l| l.split(':').nth(1))
                .map(|m| m.trim().to_string())
        })
        .unwrap_or_else(|| "unknown CPU".into());
    match load_average() {
        Some(load) if load > cores as f64 => format!(
            "{date}, {cores} cores ({cpu}), load {load:.1} at the start (1-minute average: \
             other work shared the cores, so wall times are inflated)"
        ),
        Some(load) => {
            format!("{date}, {cores} cores ({cpu}), load {load:.1} at the start (1-minute average)")
        }
        None => format!("{date}, {cores} cores ({cpu})"),
    }
}

/// The 1-minute load average (`/proc/loadavg`'s first field), None where it cannot be read.
fn load_average() -> Option<f64> {
    std::fs::read_to_string("/proc/loadavg")
        .ok()?
        .split_whitespace()
        .next()?
        .parse()
        .ok()
}

fn run_accuracy(
    cases: &[Case],
    opts: &ReportOptions,
    out: &std::path::Path,
    stamp: &str,
) -> Result<Vec<String>, CouplerError> {
    let io = CouplerError::Io;
    let total: usize = cases
        .iter()
        .filter_map(|c| accuracy::sections(c).ok())
        .map(|(r, p)| accuracy::jobs(p, opts.full).len() + usize::from(accuracy::reference_run(r)))
        .sum();
    let bar = progress::Bar::new(total as u64);
    let mut csv = table::CsvRows::create(&out.join("accuracy.csv")).map_err(io)?;
    let mut md = format!(
        "Work–precision report ({} ladders), {stamp}; made by `coupler report`. Wall time: the fastest of the timed runs after a warm-up \
         (runs over {} s: one run), with the spread of the timed runs; CPU: user + system of the coupler and its solvers; \
         peak memory: the sum of each process's peak resident set.\n\n",
        if opts.full { "full" } else { "CI-sized" },
        measure::LONG_RUN
    );
    let mut missing = Vec::new();
    for case in cases {
        let r = accuracy::run_case(case, out, opts.full, opts.repeats, &mut csv, &bar).map_err(io)?;
        md.push_str(&r.markdown);
        md.push('\n');
        missing.extend(r.missing.into_iter().map(|m| format!("{}: {m}", case.info.name)));
    }
    bar.finish();
    std::fs::write(out.join("accuracy.md"), md)
        .map_err(|e| CouplerError::Io(format!("cannot write accuracy.md: {e}")))?;
    Ok(missing)
}

fn run_stability(
    cases: &[Case],
    opts: &ReportOptions,
    out: &std::path::Path,
    stamp: &str,
) -> Result<Vec<String>, CouplerError> {
    let io = CouplerError::Io;
    let mut chosen = Vec::new();
    let mut skipped = Vec::new();
    for case in cases {
        let (families, lines) = stability::families(case, opts.full);
        let wanted = |f: &&schemas::case::report::Family| {
            opts.families.is_empty() || opts.families.contains(&f.family)
        };
        chosen.extend(families.into_iter().filter(wanted).map(|f| (case, f)));
        skipped.extend(lines);
    }
    if chosen.is_empty() {
        return Err(CouplerError::Usage(
            "none of the cases has a [[report.stability]] family (to run with these options)".into(),
        ));
    }
    let total: usize = chosen.iter().map(|(_, f)| f.runs().len()).sum();
    let bar = progress::Bar::new(total as u64);
    let path = out.join("stability.csv");
    let mut csv = std::fs::File::create(&path)
        .map_err(|e| CouplerError::Io(format!("cannot create {}: {e}", path.display())))?;
    {
        use std::io::Write;
        writeln!(csv, "case,family,run,state,wall_s,diagnostic")
            .map_err(|e| CouplerError::Io(e.to_string()))?;
    }
    let mut outcomes = Vec::new();
    let mut missing = Vec::new();
    for (case, family) in &chosen {
        let (o, m) = stability::run_family(case, family, out, &mut csv, &bar).map_err(io)?;
        outcomes.extend(o);
        missing.extend(m);
    }
    bar.finish();
    let mut md = format!(
        "Stability report ({} families), {stamp}; made by `coupler report --stability`. Each run ends stable (reached its end, \
         every check passed), warned (reached its end, but a solver warned that a check failed), stopped (the diagnostic of the solver or coupler that stopped it), refused (the case check \
         rejects the setting; nothing ran) or failed silently (claimed success with NaN or absurd output: must never happen).\n\n",
        if opts.full { "full" } else { "CI-sized" }
    );
    if !opts.families.is_empty() {
        let _ = writeln!(
            md,
            "Only the families chosen with `--family`: {}.\n",
            opts.families.join(", ")
        );
    }
    md.push_str(&stability::markdown(&outcomes, &chosen, out).map_err(io)?);
    for line in &skipped {
        let _ = writeln!(md, "\n{line}");
    }
    if !missing.is_empty() {
        let _ = writeln!(
            md,
            "\n**Missing (the report was interrupted before they finished):** {}.",
            missing.join("; ")
        );
    }
    std::fs::write(out.join("stability.md"), md)
        .map_err(|e| CouplerError::Io(format!("cannot write stability.md: {e}")))?;
    Ok(missing)
}
