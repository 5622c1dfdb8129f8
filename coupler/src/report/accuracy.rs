//! The work–precision report of one case: every rung of its ladders run as `coupler run` with
//! the rung's settings, timed, measured against the case's reference; the rows, the observed
//! orders, the summary and the plot.

use super::case_copy::write_changed_case;
use super::error_measure;
use super::measure::timed;
use super::order;
use super::plot::{self, Series};
use super::progress::Bar;
use super::summary;
use super::table::{markdown, CsvRows, Row};
use super::work::work;
use schemas::case::reference::Against;
use schemas::case::report::describe;
use schemas::case::{Case, ReferenceConfig, ReportConfig};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// A run to do: which ladder and rung, its settings.
pub struct Job {
    pub ladder: usize,
    pub ladder_label: String,
    pub parameter: String,
    pub value: f64,
    pub settings: schemas::case::report::Settings,
}

/// The jobs of a case: its ladders' rungs (the full ladders with `full`).
pub fn jobs(report: &ReportConfig, full: bool) -> Vec<Job> {
    report
        .ladder
        .iter()
        .enumerate()
        .flat_map(|(i, l)| {
            l.rungs(full).unwrap_or_default().into_iter().map(move |r| Job {
                ladder: i,
                ladder_label: l.label.clone(),
                parameter: l.vary.first().cloned().unwrap_or_default(),
                value: r.parameter,
                settings: r.settings,
            })
        })
        .collect()
}

/// The case's reference and report sections, or why it cannot be reported.
pub fn sections(case: &Case) -> Result<(&ReferenceConfig, &ReportConfig), String> {
    match (&case.reference, &case.report) {
        (Some(r), Some(p)) => Ok((r, p)),
        _ => Err(format!(
            "{}: a report needs both a [reference] and a [report] section (see cases/oscillator/case.toml)",
            case.path.display()
        )),
    }
}

/// What one case's report came to.
pub struct CaseReport {
    pub markdown: String,
    /// Rungs that did not finish (interrupted).
    pub missing: Vec<String>,
}

/// Runs the case's ladders; rows go to `csv` as they finish. Stops early when interrupted.
pub fn run_case(
    case: &Case,
    out: &Path,
    full: bool,
    repeats: Option<u32>,
    csv: &mut CsvRows,
    bar: &Bar,
) -> Result<CaseReport, String> {
    let (reference, report) = sections(case)?;
    let name = &case.info.name;
    let dir = out.join(name);
    let repeats = repeats.unwrap_or(report.repeats);
    let mut rows: Vec<Row> = Vec::new();
    let mut missing = Vec::new();
    let mut notes: Vec<String> = Vec::new();
    let mut warnings = Warnings::default();
    // The finer (or resolved) run a `finer-run` (`resolved-run`) reference compares with.
    let finer: Option<PathBuf> = match reference.against {
        Against::FinerRun | Against::ResolvedRun => {
            let what = reference_run_name(reference);
            bar.start(&format!("{name}: {what} ({})", describe(&reference.set)));
            let source = match reference.against {
                Against::ResolvedRun => reference
                    .resolved_case(case)
                    .map_err(|e| format!("{}: `{}`: {}", case.path.display(), e.key, e.message))?,
                _ => case.clone(),
            };
            let case_file = write_changed_case(&source, &reference.set, &dir.join("finer").join("case"))?;
            let run_out = dir.join("finer").join("out");
            let m = super::measure::run_case(&case_file, &run_out)?;
            bar.done();
            if m.interrupted {
                missing.push(what.into());
                None
            } else if m.success() {
                notes.push(format!(
                    "Reference: {what} ({}) took {:.2} s wall, {:.0} MB.",
                    describe(&reference.set),
                    m.wall,
                    m.peak_rss as f64 / 1e6
                ));
                Some(run_out)
            } else {
                notes.push(format!("{what} failed: {}", last_error(&m.stderr)));
                None
            }
        }
        _ => None,
    };
    let all = jobs(report, full);
    for (k, job) in all.iter().enumerate() {
        let what = format!("{} = {}", job.parameter, job.value);
        if schemas::signals::interrupted()
            || (reference_run(reference) && finer.is_none() && !missing.is_empty())
        {
            missing.push(format!("{}: {what}", job.ladder_label));
            continue;
        }
        bar.start(&format!("{name}: {}, {what}", job.ladder_label));
        let run_dir = dir.join(format!("ladder{}-rung{k}", job.ladder));
        let case_file = write_changed_case(case, &job.settings, &run_dir.join("case"))?;
        let run_out = run_dir.join("out");
        let t = timed(&case_file, &run_out, repeats)?;
        bar.done();
        if t.last.interrupted {
            missing.push(format!("{}: {what}", job.ladder_label));
            continue;
        }
        let changed = Case::load(&case_file).map_err(|e| e.to_string())?;
        let (error, status) = if t.last.success() {
            match error_measure::error(case, reference, &run_out, finer.as_deref()) {
                Ok(e) => (e, "ok".to_string()),
                Err(m) => (f64::NAN, format!("no error: {m}")),
            }
        } else {
            (f64::NAN, format!("run failed: {}", last_error(&t.last.stderr)))
        };
        let warned = super::stability::warnings(&t.last.stderr);
        if !warned.is_empty() {
            warnings.add(&warned, format!("{}, {what}", job.ladder_label));
        }
        let w = work(&changed, &run_out);
        let row = Row {
            case: name.clone(),
            ladder: job.ladder_label.clone(),
            parameter: job.parameter.clone(),
            value: job.value,
            error,
            wall: t.wall,
            cpu: t.cpu,
            runs: t.runs,
            spread: t.spread,
            steps: w.steps,
            particle_steps: w.particle_steps,
            peak_mb: t.peak_rss as f64 / 1e6,
            sweeps: w.sweeps,
            status,
        };
        csv.push(&row)?;
        bar.note(&format!(
            "{name}: {}, {what}: error {:.3e}, {:.3} s",
            row.ladder, row.error, row.wall
        ));
        rows.push(row);
    }
    notes.extend(warnings.notes());
    let markdown = case_markdown(case, reference, report, &rows, &missing, &notes, out)?;
    Ok(CaseReport { markdown, missing })
}

/// The solvers' warnings of a case's rungs, each text once with the rungs that gave it (a
/// warning about the case itself, such as a member wider than the reaction's radius, repeats
/// on every rung).
#[derive(Default)]
struct Warnings(Vec<(String, Vec<String>)>);

impl Warnings {
    fn add(&mut self, text: &str, rung: String) {
        match self.0.iter_mut().find(|(t, _)| t == text) {
            Some((_, rungs)) => rungs.push(rung),
            None => self.0.push((text.to_string(), vec![rung])),
        }
    }

    /// One note per distinct warning: `Warning at RUNG: TEXT` or `Warning at N rungs (A; B; …): TEXT`.
    fn notes(self) -> impl Iterator<Item = String> {
        self.0.into_iter().map(|(text, rungs)| match rungs.as_slice() {
            [one] => format!("Warning at {one}: {text}"),
            _ => format!("Warning at {} rungs ({}): {text}", rungs.len(), rungs.join("; ")),
        })
    }
}

/// Whether the reference is a run of its own (finer or resolved) done before the ladders.
pub fn reference_run(r: &ReferenceConfig) -> bool {
    matches!(r.against, Against::FinerRun | Against::ResolvedRun)
}

/// The reference run in words.
fn reference_run_name(r: &ReferenceConfig) -> &'static str {
    match r.against {
        Against::ResolvedRun => "the resolved reference run",
        _ => "the finer reference run",
    }
}

/// The run's `error:` lines joined (a solver's own message, then the coupler's), or its last line.
pub fn last_error(stderr: &str) -> String {
    let lines: Vec<&str> = stderr.lines().map(str::trim).filter(|l| !l.is_empty()).collect();
    let errors: Vec<&str> = lines
        .iter()
        .filter_map(|l| l.strip_prefix("error:").map(str::trim))
        .collect();
    match (errors.is_empty(), lines.last()) {
        (false, _) => errors.join(" ← "),
        (true, Some(l)) => l.to_string(),
        (true, None) => "no message".into(),
    }
}

/// The error measure in words, for table headers and plot axes.
pub fn error_name(r: &ReferenceConfig) -> String {
    let how = match r.measure {
        schemas::case::reference::Measure::Max => "largest",
        schemas::case::reference::Measure::Rms => "RMS",
        schemas::case::reference::Measure::Integral => "time-integral",
    };
    let what = match (&r.column, r.solution) {
        (_, Some(schemas::case::reference::Solution::TwoMassOscillator)) => "displacement error".to_string(),
        (Some(c), _) => format!("`{c}` error"),
        _ => "error".into(),
    };
    format!("{}{how} {what}", if r.relative { "relative " } else { "" })
}

/// The Markdown section of one case, and its plot.
fn case_markdown(
    case: &Case,
    reference: &ReferenceConfig,
    report: &ReportConfig,
    rows: &[Row],
    missing: &[String],
    notes: &[String],
    out: &Path,
) -> Result<String, String> {
    let name = &case.info.name;
    let against = match reference.against {
        Against::Exact => "exact solution",
        Against::Experiment => "experiment",
        Against::FinerRun => "finer run of the same case",
        Against::ResolvedRun => "resolved run of the same scene",
    };
    let mut s = format!(
        "### {name}\n\nError: {} against the {against} ({}).\n\n",
        error_name(reference),
        reference.source
    );
    let refs: Vec<&Row> = rows.iter().collect();
    s.push_str(&markdown(&refs));
    s.push_str("\n| ladder | expected order | observed order between rungs |\n|---|---|---|\n");
    let mut series = Vec::new();
    let mut growing = Vec::new();
    for l in &report.ladder {
        let of: Vec<&Row> = rows.iter().filter(|r| r.ladder == l.label).collect();
        let orders = order::observed(&of);
        if order::grows_with_refinement(&orders) {
            growing.push(format!("{} ({})", l.label, order::describe(&orders)));
        }
        let _ = writeln!(
            s,
            "| {} | {} | {} |",
            l.label,
            l.order.map_or("–".into(), |o| format!("{o}")),
            order::describe(&orders)
        );
        series.push(Series {
            name: l.label.clone(),
            points: of
                .iter()
                .map(|r| (r.wall, r.error, format!("{}", r.value)))
                .collect(),
        });
    }
    let png = out.join(format!("{name}-work-precision.png"));
    plot::work_precision(
        &png,
        &format!("{name}: error against wall time"),
        &error_name(reference),
        &series,
    )?;
    let _ = write!(
        s,
        "\n{}\n\n![work–precision of {name}]({name}-work-precision.png)\n",
        summary::paragraph(&refs, report.target_error, &error_name(reference))
    );
    if !growing.is_empty() {
        let _ =
            writeln!(
            s,
            "\n**The error grows as the parameter is refined** in {}: these rungs do not converge towards \
             the reference, so something the refinement does not reduce dominates the measure{}.",
            growing.join("; "),
            if report.note.is_some() { " (the note below says what)" } else { "" }
        );
    }
    if let Some(note) = &report.note {
        let _ = writeln!(s, "\n{note}");
    }
    for n in notes {
        let _ = writeln!(s, "\n{n}");
    }
    for l in &report.left_out {
        let _ = writeln!(s, "\nLeft out: {l}");
    }
    if !missing.is_empty() {
        let _ = writeln!(
            s,
            "\n**Missing (the report was interrupted before they finished):** {}.",
            missing.join("; ")
        );
    }
    Ok(s)
}

#[cfg(test)]
mod tests {
    use super::Warnings;

    /// The prism's --full report gave the wide-member warning once per rung (12 notes of one
    /// text); a warning of one rung keeps its single form.
    #[test]
    fn a_warning_repeated_by_every_rung_is_written_once() {
        let mut w = Warnings::default();
        w.add("warning: wide", "explicit, window = 0.0008".into());
        w.add("warning: energy", "implicit, window = 0.004".into());
        w.add("warning: wide", "explicit, window = 0.004".into());
        let notes: Vec<String> = w.notes().collect();
        assert_eq!(
            notes,
            [
                "Warning at 2 rungs (explicit, window = 0.0008; explicit, window = 0.004): warning: wide",
                "Warning at implicit, window = 0.004: warning: energy",
            ]
        );
    }
}
