//! `coupler report --stability`: the case's families of stiff and extreme runs, each run once to
//! its end or until a detector stops it, and classified:
//! - refused: the case check, or a solver's own check of the case, rejects the setting (e.g. a
//!   time step beyond a solver's stated limit); nothing ran, the check's message is the diagnostic;
//! - stopped: the run ended with an error; the diagnostic is its message (what, where, when);
//! - stable: the run reached its end and every check passed: no warning from a solver, no NaN
//!   or absurd value in any CSV it wrote, every ledger window balanced, within the case's limits;
//! - warned: it reached its end with every output sound, but a solver warned that one of its
//!   checks failed (e.g. frame steps that kept missing equilibrium); the warning is the diagnostic;
//! - failed silently: the run claimed success but its output holds NaN or absurd values, or
//!   windows out of balance. This must never happen; the report says where.

use super::accuracy::last_error;
use super::case_copy::write_changed_case;
use super::measure::run_case;
use super::plot::{stability_map, Cell, Panel};
use super::progress::Bar;
use schemas::case::report::{apply_settings, Family};
use schemas::case::Case;
use std::fmt::Write as _;
use std::io::Write as _;
use std::path::Path;

/// A value no output of these solvers reaches in a sound run (forces of a bridge deck are 1e9 N).
pub const ABSURD: f64 = 1e15;

/// One classified run.
#[derive(Debug, Clone)]
pub struct Outcome {
    pub case: String,
    pub family: String,
    pub labels: Vec<String>,
    pub state: Cell,
    pub diagnostic: String,
    pub wall: f64,
}

/// The families of a case that run (all with `full`, else those not marked `full_only`), and
/// lines for the others.
pub fn families(case: &Case, full: bool) -> (Vec<&Family>, Vec<String>) {
    let Some(report) = &case.report else {
        return (Vec::new(), Vec::new());
    };
    let mut skipped: Vec<String> = report
        .stability
        .iter()
        .filter(|f| f.full_only && !full)
        .map(|f| format!("{}: {} runs with --full only", case.info.name, f.family))
        .collect();
    skipped.extend(
        report
            .left_out
            .iter()
            .map(|l| format!("{}: left out: {l}", case.info.name)),
    );
    (
        report.stability.iter().filter(|f| full || !f.full_only).collect(),
        skipped,
    )
}

/// Runs every run of `family`; each outcome is appended to `csv` as it ends.
pub fn run_family(
    case: &Case,
    family: &Family,
    out: &Path,
    csv: &mut std::fs::File,
    bar: &Bar,
) -> Result<(Vec<Outcome>, Vec<String>), String> {
    let mut outcomes = Vec::new();
    let mut missing = Vec::new();
    let slug = slug(&family.family);
    for (k, (labels, settings)) in family.runs().into_iter().enumerate() {
        let what = format!("{} / {} / {}", case.info.name, family.family, labels.join(", "));
        if schemas::signals::interrupted() {
            missing.push(what);
            continue;
        }
        bar.start(&what);
        let refused = apply_settings(&case.text, &settings).and_then(|text| {
            Case::parse(&case.path, text)
                .map(|_| ())
                .map_err(|e| format!("`{}`: {}", e.key, e.message))
        });
        let (state, diagnostic, wall) = match refused {
            Err(message) => (Cell::Refused, message, 0.0),
            Ok(()) => {
                let dir = out.join(&case.info.name).join(format!("{slug}-{k}"));
                let file = write_changed_case(case, &settings, &dir.join("case"))?;
                let run_out = dir.join("out");
                let m = run_case(&file, &run_out)?;
                if m.interrupted {
                    bar.done();
                    missing.push(what);
                    continue;
                }
                let (state, diagnostic) = if m.success() {
                    match beyond_limits(case, &run_out).or_else(|| scan_outputs(&run_out)) {
                        Some(problem) => (Cell::FailedSilently, problem),
                        None => match warnings(&m.stderr) {
                            w if w.is_empty() => (Cell::Stable, w),
                            w => (Cell::Warned, w),
                        },
                    }
                } else if refused_by_solver(&m.stderr) {
                    (Cell::Refused, last_error(&m.stderr))
                } else {
                    (Cell::Stopped, last_error(&m.stderr))
                };
                (state, diagnostic, m.wall)
            }
        };
        bar.done();
        let o = Outcome {
            case: case.info.name.clone(),
            family: family.family.clone(),
            labels,
            state,
            diagnostic,
            wall,
        };
        writeln!(
            csv,
            "\"{}\",\"{}\",\"{}\",{},{:.3},\"{}\"",
            o.case,
            o.family,
            o.labels.join(" / "),
            o.state.name(),
            o.wall,
            o.diagnostic.replace('"', "'")
        )
        .and_then(|_| csv.flush())
        .map_err(|e| format!("cannot write a stability row: {e}"))?;
        bar.note(&format!("{what}: {}", o.state.name()));
        outcomes.push(o);
    }
    Ok((outcomes, missing))
}

/// Whether a solver refused the case file before anything ran (its message names a case key).
fn refused_by_solver(stderr: &str) -> bool {
    stderr.contains("before the first window")
        && stderr
            .lines()
            .any(|l| l.starts_with("error:") && l.contains(".toml: `"))
}

/// The warnings a finished run printed: a check that failed without stopping the run.
pub fn warnings(stderr: &str) -> String {
    stderr
        .lines()
        .filter(|l| l.to_lowercase().contains("warning"))
        .map(str::trim)
        .collect::<Vec<_>>()
        .join(" ")
}

/// The first NaN, infinite or absurd number in any CSV under `dir`, or a ledger window out of
/// balance: where and what. None when every output is sound.
pub fn scan_outputs(dir: &Path) -> Option<String> {
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        let Ok(entries) = std::fs::read_dir(&d) else {
            continue;
        };
        let mut entries: Vec<_> = entries.flatten().map(|e| e.path()).collect();
        entries.sort();
        for path in entries {
            if path.is_dir() {
                stack.push(path);
                continue;
            }
            if path.extension().is_none_or(|e| e != "csv") {
                continue;
            }
            let text = std::fs::read_to_string(&path).unwrap_or_default();
            let mut lines = text.lines();
            let header: Vec<&str> = lines.next().unwrap_or_default().split(',').collect();
            for (n, line) in lines.enumerate() {
                for (c, field) in line.split(',').enumerate() {
                    let name = header.get(c).copied().unwrap_or("?");
                    let bad = match field.trim().parse::<f64>() {
                        Ok(v) => !v.is_finite() || v.abs() > ABSURD,
                        Err(_) => {
                            let f = field.trim().to_lowercase();
                            f.contains("nan") || f.contains("inf") || (name == "status" && f != "ok")
                        }
                    };
                    if bad {
                        return Some(format!(
                            "{} row {}, column `{name}`: {}",
                            path.strip_prefix(dir).unwrap_or(&path).display(),
                            n + 1,
                            field.trim()
                        ));
                    }
                }
            }
        }
    }
    None
}

/// The first value beyond one of the case's `[[report.limit]]` bounds: where, what and why.
pub fn beyond_limits(case: &Case, out: &Path) -> Option<String> {
    let report = case.report.as_ref()?;
    for limit in &report.limit {
        let path = match case.coupling {
            Some(_) => out.join(&limit.participant).join(&limit.file),
            None => out.join(&limit.file),
        };
        let Ok(text) = std::fs::read_to_string(&path) else {
            return Some(format!("{} is missing", path.display()));
        };
        let mut lines = text.lines();
        let header: Vec<&str> = lines.next().unwrap_or_default().split(',').collect();
        let Some(col) = header.iter().position(|h| *h == limit.column) else {
            return Some(format!("{} has no column `{}`", path.display(), limit.column));
        };
        for (n, line) in lines.enumerate() {
            let v: f64 = line
                .split(',')
                .nth(col)
                .and_then(|f| f.trim().parse().ok())
                .unwrap_or(f64::NAN);
            if v.is_nan() || v.abs() > limit.max_abs {
                return Some(format!(
                    "{}/{} row {}, `{}` = {v:.3e} beyond ±{} ({})",
                    limit.participant,
                    limit.file,
                    n + 1,
                    limit.column,
                    limit.max_abs,
                    limit.reason
                ));
            }
        }
    }
    None
}

/// The Markdown of the outcomes and the maps: one map per family with one axis over all cases
/// (rows: cases), one per case and family with two or more axes (rows: the first axis, columns:
/// the second, one panel per combination of the others).
pub fn markdown(outcomes: &[Outcome], families: &[(&Case, &Family)], out: &Path) -> Result<String, String> {
    let mut s =
        String::from("| case | family | run | state | diagnostic | wall [s] |\n|---|---|---|---|---|---|\n");
    for o in outcomes {
        let _ = writeln!(
            s,
            "| {} | {} | {} | {} | {} | {:.2} |",
            o.case,
            o.family,
            o.labels.join(" / "),
            o.state.name(),
            o.diagnostic.replace('|', "\\|"),
            o.wall
        );
    }
    let silent = outcomes
        .iter()
        .filter(|o| o.state == Cell::FailedSilently)
        .count();
    let _ = writeln!(
        s,
        "\n{} runs: {} stable, {} warned, {} stopped, {} refused by the case check, {silent} failed silently.",
        outcomes.len(),
        outcomes.iter().filter(|o| o.state == Cell::Stable).count(),
        outcomes.iter().filter(|o| o.state == Cell::Warned).count(),
        outcomes.iter().filter(|o| o.state == Cell::Stopped).count(),
        outcomes.iter().filter(|o| o.state == Cell::Refused).count(),
    );
    let state = |case: &str, family: &str, labels: &[String]| {
        outcomes
            .iter()
            .find(|o| o.case == case && o.family == family && o.labels == labels)
            .map_or(Cell::NotRun, |o| o.state)
    };
    let mut one_axis: Vec<&str> = Vec::new();
    for (case, family) in families {
        if family.axis.len() == 1 {
            if !one_axis.contains(&family.family.as_str()) {
                one_axis.push(&family.family);
            }
            continue;
        }
        let (a, b) = (&family.axis[0], &family.axis[1]);
        let rest: Vec<Vec<String>> = family.axis[2..].iter().fold(vec![Vec::new()], |acc, axis| {
            acc.into_iter()
                .flat_map(|p| {
                    axis.labels.iter().map(move |l| {
                        let mut p = p.clone();
                        p.push(l.clone());
                        p
                    })
                })
                .collect()
        });
        let panels: Vec<Panel> = rest
            .iter()
            .map(|extra| Panel {
                title: if extra.is_empty() {
                    family.family.clone()
                } else {
                    extra.join(", ")
                },
                rows_name: a.name.clone(),
                rows: a.labels.clone(),
                columns_name: b.name.clone(),
                columns: b.labels.clone(),
                cells: a
                    .labels
                    .iter()
                    .map(|ra| {
                        b.labels
                            .iter()
                            .map(|cb| {
                                let mut labels = vec![ra.clone(), cb.clone()];
                                labels.extend(extra.iter().cloned());
                                state(&case.info.name, &family.family, &labels)
                            })
                            .collect()
                    })
                    .collect(),
            })
            .collect();
        let file = format!("{}-{}-map.png", case.info.name, slug(&family.family));
        stability_map(
            &out.join(&file),
            &format!("{}: {}", case.info.name, family.family),
            &panels,
        )?;
        let _ = writeln!(s, "\n![{}: {}]({file})", case.info.name, family.family);
    }
    for name in one_axis {
        let members: Vec<&(&Case, &Family)> = families.iter().filter(|(_, f)| f.family == name).collect();
        let axis = &members[0].1.axis[0];
        let panel = Panel {
            title: name.to_string(),
            rows_name: "case".into(),
            rows: members.iter().map(|(c, _)| c.info.name.clone()).collect(),
            columns_name: axis.name.clone(),
            columns: axis.labels.clone(),
            cells: members
                .iter()
                .map(|(c, f)| {
                    axis.labels
                        .iter()
                        .map(|l| match f.axis[0].labels.contains(l) {
                            true => state(&c.info.name, name, std::slice::from_ref(l)),
                            false => Cell::NotRun,
                        })
                        .collect()
                })
                .collect(),
        };
        let file = format!("{}-map.png", slug(name));
        stability_map(&out.join(&file), name, &[panel])?;
        let _ = writeln!(s, "\n![{name}]({file})");
    }
    Ok(s)
}

fn slug(s: &str) -> String {
    s.chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() {
                c.to_ascii_lowercase()
            } else {
                '-'
            }
        })
        .collect()
}
