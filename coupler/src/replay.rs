//! `coupler replay`: drive one solver with its partners' recorded messages and compare what it
//! answers with what it answered in the recorded run.
//!
//! The solver sees exactly the recorded inputs (open loop), so any difference is the solver's
//! own: a changed parameter, another implementation swapped in, a regression.

use crate::error::CouplerError;
use crate::launch::executable_for;
use crate::run::{new_run_id, output_folder, participant_args};
use crate::signals;
use crate::stack::{variant, Launch, Stack};
use schemas::case::{Case, Kind};
use schemas::message::{Fields, FromParticipant, Role, ToParticipant};
use schemas::recording::{Message, Recording};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::time::Duration;

/// What `coupler replay` was asked to do.
pub struct ReplayOptions {
    pub recording: PathBuf,
    pub participant: String,
    pub exe: Option<PathBuf>,
    /// Replay against this case instead of the recorded one (e.g. with a changed parameter).
    pub case: Option<PathBuf>,
    /// Largest relative difference per field that still counts as the same answer.
    pub tolerance: f64,
    pub out: Option<PathBuf>,
}

/// Largest differences of one output field over the replay.
#[derive(Debug, Clone, Default)]
pub struct FieldDifference {
    pub largest_absolute: f64,
    pub largest_relative: f64,
    /// First window where the relative difference exceeded the tolerance.
    pub first_departure: Option<u64>,
}

/// The comparison of a replay.
#[derive(Debug, Default)]
pub struct ReplayReport {
    pub messages: usize,
    pub fields: BTreeMap<String, FieldDifference>,
    /// First window where the solver departed from the recording, and the field.
    pub departure: Option<(u64, String)>,
}

/// Replays `opts.participant` against its recording; `Err(Departed)` when it departs.
pub fn replay(opts: &ReplayOptions) -> Result<ReplayReport, CouplerError> {
    let recording = Recording::read(&opts.recording).map_err(|e| CouplerError::Usage(e.to_string()))?;
    let name = &opts.participant;
    if !recording.header.participants.contains(name) {
        return Err(CouplerError::Usage(format!(
            "{}: no participant `{name}` in this recording; it has: {}",
            opts.recording.display(),
            recording.header.participants.join(", ")
        )));
    }
    if recording.truncated {
        eprintln!("note: the recording ends inside a frame (the run died); replaying what is complete");
    }
    let out = opts
        .out
        .clone()
        .unwrap_or_else(|| PathBuf::from("out").join(format!("replay-{name}")));
    let case = replay_case(&recording, opts.case.as_deref(), &out)?;
    let out = output_folder(&case, Some(&out))?;
    if case.hash != recording.header.case_hash {
        eprintln!(
            "note: replaying against a case that differs from the recorded one ({})",
            case.path.display()
        );
    }
    let kind = case.kind_of(name).ok_or_else(|| {
        CouplerError::Usage(format!(
            "the case {} has no participant `{name}`",
            case.path.display()
        ))
    })?;
    let exe = match &opts.exe {
        Some(p) => BTreeMap::from([(name.clone(), p.clone())]),
        None => BTreeMap::new(),
    };
    let exe = executable_for(&case, name, kind, &exe)?;
    let mine: Vec<&Message> = recording
        .frames
        .iter()
        .filter(|f| &f.participant == name)
        .map(|f| &f.message)
        .collect();
    signals::install();
    let run_id = new_run_id();
    let case_path = std::fs::canonicalize(&case.path).unwrap_or_else(|_| case.path.clone());
    let launch = Launch {
        name: name.clone(),
        role: if kind == Kind::Fluid {
            Role::Fluid
        } else {
            Role::Structure
        },
        exe,
        args: participant_args(&case_path, name, &run_id, &out),
    };
    let timeout = Duration::from_secs_f64(case.coupling.as_ref().map(|c| c.timeout).unwrap_or(120.0));
    let (mut stack, initial) = Stack::launch(vec![launch], &run_id, case.hash, &out, None, timeout)?;
    let initial = initial.into_iter().next().unwrap_or_default();
    let result = drive(&mut stack, &mine, initial, opts.tolerance);
    match result {
        Ok(report) => {
            stack.finish()?;
            print_report(&report, opts.tolerance);
            match &report.departure {
                Some((window, field)) => Err(CouplerError::Participant {
                    name: name.clone(),
                    window: Some(*window),
                    message: format!(
                        "departs from the recording in `{field}` (relative difference above {:.1e})",
                        opts.tolerance
                    ),
                }),
                None => Ok(report),
            }
        }
        Err(e) => {
            stack.abort();
            Err(e)
        }
    }
}

/// The case to replay against: `--case`, else the recorded file if unchanged, else the
/// recorded text written into the output folder.
fn replay_case(recording: &Recording, case: Option<&Path>, out: &Path) -> Result<Case, CouplerError> {
    if let Some(p) = case {
        return Ok(Case::load(p)?);
    }
    let recorded = PathBuf::from(&recording.header.case_path);
    if let Ok(c) = Case::load(&recorded) {
        if c.hash == recording.header.case_hash {
            return Ok(c);
        }
    }
    std::fs::create_dir_all(out)
        .map_err(|e| CouplerError::Io(format!("cannot create {}: {e}", out.display())))?;
    let copy = out.join("case.toml");
    std::fs::write(&copy, &recording.header.case_text)
        .map_err(|e| CouplerError::Io(format!("cannot write {}: {e}", copy.display())))?;
    eprintln!(
        "note: {} changed since the recording; replaying the recorded text from {} (relative paths in it are \
         taken from there)",
        recorded.display(),
        copy.display()
    );
    Ok(Case::load(&copy)?)
}

fn drive(
    stack: &mut Stack,
    messages: &[&Message],
    initial: Fields,
    tolerance: f64,
) -> Result<ReplayReport, CouplerError> {
    let mut report = ReplayReport::default();
    let mut sent_window = None;
    for m in messages {
        match m {
            Message::From(FromParticipant::Initial { outputs, .. }) => {
                compare(
                    &mut report,
                    0,
                    std::slice::from_ref(outputs),
                    std::slice::from_ref(&initial),
                    tolerance,
                );
            }
            Message::To(msg @ ToParticipant::Advance { header, .. }) => {
                if signals::interrupted() {
                    return Err(CouplerError::Interrupted {
                        window: Some(header.window),
                    });
                }
                sent_window = Some(header.window);
                stack.send(0, msg.clone(), sent_window)?;
            }
            Message::From(recorded @ (FromParticipant::Advanced { .. } | FromParticipant::Failed { .. })) => {
                let window = sent_window.unwrap_or(0);
                let actual = match stack.recv(0, sent_window) {
                    Ok(a) => a,
                    Err(e) if matches!(recorded, FromParticipant::Failed { .. }) => {
                        eprintln!("the solver failed where the recorded one failed too: {e}");
                        report.messages += 1;
                        return Ok(report);
                    }
                    Err(e) => return Err(e),
                };
                report.messages += 1;
                match (recorded, &actual) {
                    (
                        FromParticipant::Advanced { outputs: r, .. },
                        FromParticipant::Advanced { outputs: a, .. },
                    ) => compare(&mut report, window, &r.samples, &a.samples, tolerance),
                    _ => {
                        report.departure.get_or_insert((
                            window,
                            format!(
                                "answer kind: recorded {}, now {}",
                                variant(recorded),
                                variant(&actual)
                            ),
                        ));
                    }
                }
            }
            _ => {}
        }
    }
    Ok(report)
}

/// Largest absolute and relative (to the recorded array's largest magnitude) differences per field.
fn compare(report: &mut ReplayReport, window: u64, recorded: &[Fields], actual: &[Fields], tolerance: f64) {
    for (r, a) in recorded.iter().zip(actual) {
        for ((name, rv), (_, av)) in r.arrays().into_iter().zip(a.arrays()) {
            if rv.is_empty() && av.is_empty() {
                continue;
            }
            let entry = report.fields.entry(name.to_string()).or_default();
            let (abs, rel) = if rv.len() != av.len() {
                (f64::INFINITY, f64::INFINITY)
            } else {
                let abs = rv
                    .iter()
                    .zip(av.iter())
                    .map(|(x, y)| (x - y).abs())
                    .fold(0.0, f64::max);
                let scale = rv.iter().map(|x| x.abs()).fold(0.0, f64::max);
                (abs, if scale > 0.0 { abs / scale } else { abs })
            };
            let abs = if abs.is_nan() { f64::INFINITY } else { abs };
            let rel = if rel.is_nan() { f64::INFINITY } else { rel };
            entry.largest_absolute = entry.largest_absolute.max(abs);
            entry.largest_relative = entry.largest_relative.max(rel);
            if rel > tolerance && entry.first_departure.is_none() {
                entry.first_departure = Some(window);
                if report.departure.as_ref().is_none_or(|(w, _)| window < *w) {
                    report.departure = Some((window, name.to_string()));
                }
            }
        }
    }
}

fn print_report(report: &ReplayReport, tolerance: f64) {
    println!(
        "replayed {} answers; tolerance {tolerance:.1e} (relative to the recorded field's largest value)",
        report.messages
    );
    println!(
        "{:<22} {:>16} {:>16} {:>16}",
        "field", "largest abs", "largest rel", "first window over"
    );
    for (name, d) in &report.fields {
        let first = d
            .first_departure
            .map(|w| w.to_string())
            .unwrap_or_else(|| "-".into());
        println!(
            "{name:<22} {:>16.3e} {:>16.3e} {first:>16}",
            d.largest_absolute, d.largest_relative
        );
    }
    match &report.departure {
        Some((w, field)) => println!("DEPARTS in window {w} ({field})"),
        None => println!("PASS: every answer matches the recording"),
    }
}
