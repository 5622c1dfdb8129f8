//! `coupler replay`: drive one solver with its partners' recorded messages and compare what it
//! answers with what it answered in the recorded run.
//!
//! The solver sees exactly the recorded inputs (open loop), so any difference is the solver's
//! own: a changed parameter, another implementation swapped in, a regression.

use crate::error::CouplerError;
use crate::launch::{executable_for, launcher_for};
use crate::run::{new_run_id, output_folder, participant_args};
use crate::stack::{variant, Launch, Stack};
use schemas::case::{Case, Kind};
use schemas::message::{
    Fields, FromParticipant, Role, ToParticipant, OLDEST_REPLAYABLE_PROTOCOL, PROTOCOL_VERSION,
};
use schemas::recording::{Message, Recording, RecordingEnd, RunEnd};
use schemas::signals;
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
    /// Answers of the solver compared with recorded ones.
    pub messages: usize,
    /// Answers of this participant in the recording's complete frames.
    pub recorded: usize,
    pub fields: BTreeMap<String, FieldDifference>,
    /// First window where the solver departed from the recording, and the field.
    pub departure: Option<(u64, String)>,
}

/// Replays `opts.participant` against its recording. Fails (never passes) when the solver departs,
/// when fewer answers were compared than the recording holds (none included), when the recording
/// is damaged, and when it is cut: it has no end record, so the run's last answers may be missing
/// (the coupler was killed while writing it, or the file was truncated). A recording of a run that
/// the coupler stopped on a failure ends with a record of who and why: it replays what it holds
/// and passes when every answer matches, saying where and why the run died. Every failure is a
/// [`CouplerError`] with exit code 1, like a departure.
pub fn replay(opts: &ReplayOptions) -> Result<ReplayReport, CouplerError> {
    let recording = Recording::read(&opts.recording).map_err(|e| CouplerError::Usage(e.to_string()))?;
    if !(OLDEST_REPLAYABLE_PROTOCOL..=PROTOCOL_VERSION).contains(&recording.header.protocol) {
        return Err(CouplerError::Usage(format!(
            "{}: recorded with message protocol version {}, this coupler speaks version {PROTOCOL_VERSION} and \
             replays recordings of versions {OLDEST_REPLAYABLE_PROTOCOL} to {PROTOCOL_VERSION}: its messages do \
             not read back with this build. Replay it with the build that recorded it, or record the case \
             again with this one",
            opts.recording.display(),
            recording.header.protocol
        )));
    }
    let name = &opts.participant;
    if !recording.header.participants.contains(name) {
        return Err(CouplerError::Usage(format!(
            "{}: no participant `{name}` in this recording; it has: {}",
            opts.recording.display(),
            recording.header.participants.join(", ")
        )));
    }
    if recording.version == 1 {
        crate::say!(
            "note: a version-1 recording: its frames carry no checksums, so damage to it cannot be told from a \
             departure of the solver"
        );
    }
    let run_end = recording.run_end();
    if recording.version < 3 && run_end != RunEnd::Corrupt {
        crate::say!(
            "note: a version-{} recording has no end record: it counts as whole when every participant's \
             last message is `Finished`, or when it says why the run died",
            recording.version
        );
    }
    match run_end {
        RunEnd::Finished { .. } | RunEnd::Died { .. } => {}
        RunEnd::Cut => crate::say!(
            "error: {}: the recording was cut (it has no end record); replaying its {} complete frames, but \
             the replay cannot pass",
            opts.recording.display(),
            recording.frames.len()
        ),
        RunEnd::Corrupt => crate::say!(
            "error: {}: {}; replaying the frames before it, but the replay cannot pass",
            opts.recording.display(),
            recording.end
        ),
    }
    let mine: Vec<&Message> = recording
        .frames
        .iter()
        .filter(|f| &f.participant == name)
        .map(|f| &f.message)
        .collect();
    let recorded = mine.iter().filter(|m| is_answer(m)).count();
    if recorded == 0 {
        let why = match run_end {
            RunEnd::Cut => format!("{run_end}; {}", cut_detail(&recording)),
            RunEnd::Corrupt => recording.end.to_string(),
            _ => run_end.to_string(),
        };
        return Err(CouplerError::Replay(format!(
            "{}: the recording holds no answer of `{name}` to compare ({} complete frames; {why}); nothing \
             was replayed",
            opts.recording.display(),
            recording.frames.len(),
        )));
    }
    let ending = ending(&run_end, name, &mine);
    let out = opts
        .out
        .clone()
        .unwrap_or_else(|| PathBuf::from("out").join(format!("replay-{name}")));
    let case = replay_case(&recording, opts.case.as_deref(), &out)?;
    let out = output_folder(&case, Some(&out))?;
    if case.hash != recording.header.case_hash {
        crate::say!(
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
    let launcher = launcher_for(&case, name)?;
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
        launcher,
    };
    let timeout = Duration::from_secs_f64(case.coupling.as_ref().map(|c| c.timeout).unwrap_or(120.0));
    let (mut stack, initial) = Stack::launch(vec![launch], &run_id, case.hash, &out, None, timeout, None)?;
    let initial = initial.into_iter().next().unwrap_or_default();
    let result = drive(&mut stack, &mine, initial, opts.tolerance);
    let mut report = match result {
        Ok(report) => report,
        Err(e) => {
            stack.abort(&e);
            return Err(e);
        }
    };
    stack.finish(None)?;
    report.recorded = recorded;
    print_report(&report, opts.tolerance, ending.as_deref());
    if let Some((window, field)) = &report.departure {
        return Err(CouplerError::Participant {
            name: name.clone(),
            window: Some(*window),
            message: format!(
                "departs from the recording in `{field}` (relative difference above {:.1e})",
                opts.tolerance
            ),
        });
    }
    if report.messages < recorded {
        return Err(CouplerError::Replay(format!(
            "compared only {} of the {recorded} answers of `{name}` in the recording",
            report.messages
        )));
    }
    match run_end {
        RunEnd::Corrupt => {
            return Err(CouplerError::Replay(format!(
                "{}: {}; the {} answers before it match",
                opts.recording.display(),
                recording.end,
                report.messages
            )))
        }
        RunEnd::Cut => {
            return Err(CouplerError::Replay(format!(
                "{}: {run_end}; {}; read {} complete frames holding {recorded} answers of `{name}`: the {} \
                 compared match, but the run's last answers may be missing, so a cut recording cannot pass",
                opts.recording.display(),
                cut_detail(&recording),
                recording.frames.len(),
                report.messages
            )))
        }
        RunEnd::Finished { .. } | RunEnd::Died { .. } => {}
    }
    crate::show!(
        "PASS: all {} recorded answers of `{name}` match the recording",
        report.messages
    );
    Ok(report)
}

/// Where a recording without an end record stops: inside a frame (as the reader says it), or at
/// a frame boundary.
fn cut_detail(recording: &Recording) -> String {
    match &recording.end {
        RecordingEnd::Whole => format!(
            "the file ends after frame {}, at a frame boundary",
            recording.frames.len()
        ),
        inside => inside.to_string(),
    }
}

/// Whether a recorded message is a participant's answer to an `Advance`.
fn is_answer(m: &Message) -> bool {
    matches!(
        m,
        Message::From(FromParticipant::Advanced { .. } | FromParticipant::Failed { .. })
    )
}

/// Where and why the recording of a run that did not finish ends, as seen by participant `name`;
/// `None` for a run that finished, and for a damaged recording (reported as damage).
fn ending(run_end: &RunEnd, name: &str, mine: &[&Message]) -> Option<String> {
    let stopped = match run_end {
        // The damage, not the run, ends what can be read; it is reported as such.
        RunEnd::Corrupt | RunEnd::Finished { .. } => return None,
        RunEnd::Died { window, reason, .. } => Some((*window, reason.clone())),
        RunEnd::Cut => None,
    };
    let last_window = mine.iter().rev().find_map(|m| match m {
        Message::To(ToParticipant::Advance { header, .. }) => Some(header.window),
        _ => None,
    });
    let unanswered = matches!(mine.last(), Some(Message::To(ToParticipant::Advance { .. })));
    let request = if unanswered {
        format!(", with `{name}`'s request in that window unanswered")
    } else {
        String::new()
    };
    Some(match (stopped, last_window) {
        (Some((Some(w), reason)), _) => format!("the run died in window {w}{request}: {reason}"),
        (Some((None, reason)), _) => format!("the run died: {reason}"),
        (None, Some(w)) => {
            format!("it was cut in window {w}{request}, without a record of why the run stopped")
        }
        (None, None) => "it was cut before the first window".to_string(),
    })
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
    crate::say!(
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
    for (i, m) in messages.iter().enumerate() {
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
                if !messages.get(i + 1).is_some_and(|next| is_answer(next)) {
                    // The recorded run died before this request was answered: nothing to compare.
                    break;
                }
                sent_window = Some(header.window);
                stack.send(0, msg.clone(), sent_window)?;
            }
            Message::From(recorded @ (FromParticipant::Advanced { .. } | FromParticipant::Failed { .. })) => {
                let window = sent_window.unwrap_or(0);
                let actual = match stack.recv(0, sent_window) {
                    Ok(a) => a,
                    Err(e) if matches!(recorded, FromParticipant::Failed { .. }) => {
                        crate::say!("the solver failed where the recorded one failed too: {e}");
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

fn print_report(report: &ReplayReport, tolerance: f64, ending: Option<&str>) {
    crate::show!(
        "compared {} of the recording's {} answers; tolerance {tolerance:.1e} (relative to the recorded field's \
         largest value)",
        report.messages, report.recorded
    );
    crate::show!(
        "{:<22} {:>16} {:>16} {:>16}",
        "field",
        "largest abs",
        "largest rel",
        "first window over"
    );
    for (name, d) in &report.fields {
        let first = d
            .first_departure
            .map(|w| w.to_string())
            .unwrap_or_else(|| "-".into());
        crate::show!(
            "{name:<22} {:>16.3e} {:>16.3e} {first:>16}",
            d.largest_absolute,
            d.largest_relative
        );
    }
    if let Some(ending) = ending {
        crate::show!("the recording ends early: {ending}");
    }
    match &report.departure {
        Some((w, field)) => crate::show!("DEPARTS in window {w} ({field})"),
        None if report.messages < report.recorded => crate::show!(
            "FAIL: only {} of the {} recorded answers were compared",
            report.messages,
            report.recorded
        ),
        None => {}
    }
}
