//! `coupler run`: load the case, start the participants it needs, run the windows, stop cleanly.

use crate::checkpoint::{self, Manifest};
use crate::error::CouplerError;
use crate::estimate::{bytes_text, Estimate};
use crate::interface::Interface;
use crate::launch::{behind_launcher, describe, executable_for, launcher_for};
use crate::ledger::Ledger;
use crate::out_folder::OutputFolder;
use crate::progress::Progress;
use crate::scheme::{window_count, CheckpointPlan, Summary, Windows};
use crate::stability::Detector;
use crate::stack::{Launch, Stack};
use schemas::case::error::check::short;
use schemas::case::fluid::FluidBackend;
use schemas::case::{Case, Kind};
use schemas::message::{Role, PROTOCOL_VERSION};
use schemas::recording::{Recorder, RecordingHeader};
use schemas::signals;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::{Duration, Instant};

/// What `coupler run` was asked to do.
pub struct RunOptions {
    pub case: PathBuf,
    pub out: Option<PathBuf>,
    /// Executables that replace a participant's default solver.
    pub exe: BTreeMap<String, PathBuf>,
    /// Delete an earlier run's files in the output folder first (else such a folder is refused).
    pub overwrite: bool,
    /// Refuse a run estimated to write more bytes than this.
    pub max_output: u64,
    /// Continue the run in this output folder from its last complete checkpoint.
    pub resume: Option<PathBuf>,
    /// Run to this time [s] instead of the case's `end_time` (with `resume`: extend the run to it).
    pub end_time: Option<f64>,
}

/// The output folder a run writes to: `--out`, or `out/<case name>`.
pub fn default_output_folder(case: &Case, out: Option<&Path>) -> PathBuf {
    out.map(Path::to_path_buf)
        .unwrap_or_else(|| PathBuf::from("out").join(&case.info.name))
}

/// The output folder: `--out`, or `out/<case name>`.
pub fn output_folder(case: &Case, out: Option<&Path>) -> Result<PathBuf, CouplerError> {
    let dir = default_output_folder(case, out);
    std::fs::create_dir_all(&dir)
        .map_err(|e| CouplerError::Io(format!("cannot create the output folder {}: {e}", dir.display())))?;
    Ok(dir)
}

/// A run id unique on this machine: service names carry it, so concurrent runs never cross.
pub fn new_run_id() -> String {
    let nanos = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map(|d| d.as_nanos())
        .unwrap_or(0);
    format!("{:x}-{:x}", std::process::id(), nanos & 0xffff_ffff_ffff)
}

/// Arguments of `SOLVER participant …`.
pub fn participant_args(case: &Path, name: &str, run_id: &str, out: &Path) -> Vec<String> {
    vec![
        "participant".into(),
        "--case".into(),
        case.display().to_string(),
        "--name".into(),
        name.into(),
        "--run-id".into(),
        run_id.into(),
        "--coupler-pid".into(),
        std::process::id().to_string(),
        "--out".into(),
        out.join(name).display().to_string(),
    ]
}

/// Runs a case to its end time (`opts.end_time` when given).
pub fn run(opts: &RunOptions) -> Result<(), CouplerError> {
    let case = Case::load_to(&opts.case, opts.end_time)?;
    if let (Some(t), None) = (opts.end_time, &case.coupling) {
        return Err(CouplerError::Usage(format!(
            "--end-time {}: {} has no [coupling]; its one solver runs alone and goes to the case's end_time \
             (edit case.end_time instead)",
            short(t),
            opts.case.display()
        )));
    }
    for name in opts.exe.keys() {
        if case.kind_of(name).is_none() {
            return Err(CouplerError::Usage(format!(
                "--exe {name}=…: the case {} has no participant `{name}`",
                opts.case.display()
            )));
        }
    }
    let participants = case.participants();
    let executables = participants
        .iter()
        .map(|(name, kind)| executable_for(&case, name, *kind, &opts.exe).map(|exe| (name.clone(), exe)))
        .collect::<Result<BTreeMap<_, _>, _>>()?;
    let launchers = participants
        .iter()
        .map(|(name, _)| launcher_for(&case, name).map(|l| (name.clone(), l)))
        .collect::<Result<BTreeMap<_, _>, _>>()?;
    let out = match &opts.resume {
        Some(dir) => dir.clone(),
        None => default_output_folder(&case, opts.out.as_deref()),
    };
    crate::out_folder::check_place(&out)?;
    let estimate = Estimate::of(&case);
    estimate.check(&out, opts.max_output)?;
    crate::say!("estimate: {}", estimate.describe());
    // A fluid solver that runs alone writes to this terminal and warns itself; coupled solvers
    // write to their logs, so the coupler prints their warnings here, once; the frames' and the
    // drag's it prints always.
    let warnings = match case.coupling {
        Some(_) => case.warnings(),
        None => case.frame_and_drag_warnings(),
    };
    for warning in warnings {
        crate::say!("warning: {warning}");
    }
    let folder = match &opts.resume {
        Some(_) => OutputFolder::hold(&out)?,
        None => OutputFolder::take(&out, opts.overwrite)?,
    };
    let out = folder.dir.clone();
    let resumed = match &opts.resume {
        Some(_) => Some(resume_point(&case, &out, opts.end_time.is_some())?),
        None => None,
    };
    signals::install();
    let Some(coupling) = &case.coupling else {
        let (name, kind) = &participants[0];
        return standalone(&case, name, *kind, &executables[name], &launchers[name], &out);
    };
    let case_path = std::fs::canonicalize(&case.path).unwrap_or_else(|_| case.path.clone());
    let run_id = new_run_id();
    let order = coupling.serial_order(&case);
    let launches = order
        .iter()
        .map(|name| Launch {
            name: name.clone(),
            role: match case.kind_of(name) {
                Some(Kind::Fluid) => Role::Fluid,
                _ => Role::Structure,
            },
            exe: executables[name].clone(),
            args: participant_args(&case_path, name, &run_id, &out),
            launcher: launchers[name].clone(),
        })
        .collect::<Vec<_>>();
    let mut launches = launches;
    if let Some(t) = opts.end_time {
        // f64's Display reads back to the same number
        for l in &mut launches {
            l.args.extend(["--end-time".to_string(), t.to_string()]);
        }
    }
    if let Some(m) = &resumed {
        for l in &mut launches {
            let file = checkpoint::participant_file(&out, &l.name, m)?;
            l.args
                .extend(["--resume".to_string(), file.display().to_string()]);
        }
        checkpoint::cut_back(&out, m)?;
        crate::say!(
            "resuming from the checkpoint of window {} (t = {} s) in {}, to end at t = {} s",
            m.window,
            m.time,
            out.join(schemas::checkpoint::FOLDER).display(),
            case.info.end_time
        );
    }
    let recording = out.join("recording.rec");
    let header = RecordingHeader {
        protocol: PROTOCOL_VERSION,
        case_hash: case.hash,
        case_path: case_path.display().to_string(),
        case_text: case.text.clone(),
        run_id: run_id.clone(),
        participants: order.clone(),
    };
    let recorder = match &resumed {
        Some(_) => Recorder::append(&recording),
        None => Recorder::create(&recording, &header),
    }
    .map_err(|e| CouplerError::Io(format!("cannot write {}: {e}", recording.display())))?;
    let started = Instant::now();
    let timeout = Duration::from_secs_f64(coupling.timeout);
    let (mut stack, initial) = Stack::launch(
        launches,
        &run_id,
        case.hash,
        &out,
        Some(recorder),
        timeout,
        resumed.as_ref().map(|m| m.wall),
    )?;
    let result = (|| {
        let decls: Vec<_> = stack.sessions.iter().map(|s| s.interface.clone()).collect();
        let mut interface = Interface::bind(&case, &order, &decls)?;
        for (p, session) in stack.sessions.iter().enumerate() {
            if let Some(g) = &session.geometry {
                interface.geometry(p, g, &initial[p])?;
            }
        }
        let mut initial = initial;
        for (p, fields) in initial.iter_mut().enumerate() {
            interface.complete_outputs(p, fields);
        }
        for (p, fields) in initial.iter().enumerate() {
            interface
                .check_outputs(p, fields)
                .map_err(|message| CouplerError::Participant {
                    name: order[p].clone(),
                    window: None,
                    message: format!("initial outputs: {message}"),
                })?;
        }
        let ledger_path = out.join("ledger.csv");
        let gpu = case.fluid.values().any(|f| f.backend == FluidBackend::Gpu);
        let tolerance = coupling.balance_tolerance(gpu);
        let ledger = match &resumed {
            Some(_) => Ledger::append(&ledger_path, tolerance)?,
            None => Ledger::create(&ledger_path, &order, tolerance)?,
        };
        let windows = Windows {
            stack: &mut stack,
            interface: &mut interface,
            config: coupling,
            ledger,
            progress: Progress::new(),
            detector: Detector::create(
                &out.join("interface_energy.csv"),
                &order,
                coupling.created_energy_limit,
                resumed.is_some(),
            )?,
            reference: Default::default(),
            checkpoints: coupling.checkpoint_windows().map(|every| CheckpointPlan {
                every,
                out: out.clone(),
                inputs: case.input_hashes(),
            }),
        };
        match &resumed {
            Some(m) => windows.resume(case.info.end_time, &m.coupler),
            None => windows.run(case.info.end_time, initial),
        }
    })();
    match result {
        Ok(summary) => {
            stack.finish(Some((summary.windows, case.info.end_time)))?;
            report(&summary, started.elapsed().as_secs_f64(), &out);
            Ok(())
        }
        Err(e) => {
            stack.abort(&e);
            Err(e)
        }
    }
}

/// The checkpoint in `out` to resume from, checked against the case: its inputs and its
/// participants. The end time (`--end-time` when `end_time_given`) must be after the last complete
/// checkpoint; when it is that checkpoint's time, a checkpoint the run took at its end (it
/// finished, or was stopped while finishing), the run continues from the checkpoint before it.
fn resume_point(case: &Case, out: &Path, end_time_given: bool) -> Result<Manifest, CouplerError> {
    if case.coupling.is_none() {
        return Err(CouplerError::Usage(format!(
            "--resume: {} has no [coupling]; only coupled runs take checkpoints",
            case.path.display()
        )));
    }
    let m = checkpoint::latest(out)?;
    let now = case.input_hashes();
    if m.inputs != now {
        let changed: Vec<&str> = m
            .inputs
            .iter()
            .filter(|was| !now.contains(was))
            .map(|(what, _)| what.as_str())
            .chain(
                now.iter()
                    .filter(|n| !m.inputs.iter().any(|w| w.0 == n.0))
                    .map(|(what, _)| what.as_str()),
            )
            .collect();
        return Err(CouplerError::Usage(format!(
            "--resume {}: {} changed since the run was started ({}), so its outputs would not continue the same run; \
             resume with the case and files it was started with (comments and layout of the case file may change)",
            out.display(),
            changed.join(", "),
            case.path.display()
        )));
    }
    let names: Vec<String> = case
        .coupling
        .as_ref()
        .map(|c| c.serial_order(case))
        .unwrap_or_default();
    if m.participants != names {
        return Err(CouplerError::Usage(format!(
            "--resume {}: the checkpoint is of participants {:?}, the case has {:?}",
            out.display(),
            m.participants,
            names
        )));
    }
    let window = case.coupling.as_ref().map_or(1.0, |c| c.window);
    let windows = window_count(case.info.end_time, window);
    if windows == m.coupler.next_window && case.info.end_time == m.time {
        return match checkpoint::latest_before(out, m.window) {
            Some(earlier) => {
                crate::say!(
                    "note: the last checkpoint (t = {} s) is at the end time: the run is continued from the one \
                     before it, and ends as it did (give --end-time a later time to extend it)",
                    short(m.time)
                );
                Ok(earlier)
            }
            None => Err(CouplerError::Usage(format!(
                "--resume {}: its only checkpoint is at its end time {} s, so there is nothing to resume; give \
                 --end-time a later time to extend the run, or run it again with --overwrite",
                out.display(),
                short(m.time)
            ))),
        };
    }
    if windows <= m.coupler.next_window {
        let end = short(case.info.end_time);
        let before = if case.info.end_time < m.time {
            "before it"
        } else {
            "within round-off of it"
        };
        let asked = if end_time_given {
            format!("--end-time {end} s")
        } else {
            format!("the case's end_time {end} s")
        };
        // a run extended and stopped before its new end
        let hint = if !end_time_given && m.end_time > m.time {
            let was = short(m.end_time);
            format!(" (the run was going to t = {was} s: --end-time {was})")
        } else {
            String::new()
        };
        return Err(CouplerError::Usage(format!(
            "--resume {}: its last checkpoint is at t = {} s (window {}) and {asked} is {before}; a resumed run \
             continues from that checkpoint, so give --end-time a time after {} s{hint}",
            out.display(),
            short(m.time),
            m.window,
            short(m.time)
        )));
    }
    Ok(m)
}

fn report(s: &Summary, wall: f64, out: &Path) {
    let written = folder_size(out);
    crate::say!(
        "done: {} windows, {} solver sweeps (at most {} in a window), {wall:.2} s wall; action–reaction balance \
         worst {:.1e}{}",
        s.windows,
        s.iterations,
        s.max_iterations,
        s.worst_balance,
        if s.balance_violations > 0 { format!(", {} windows above tolerance", s.balance_violations) } else { String::new() }
    );
    crate::say!(
        "output: {}, {} (recording.rec, ledger.csv, interface_energy.csv, one log and folder per participant)",
        out.display(),
        bytes_text(written as f64)
    );
}

/// Bytes of every file under `dir`.
pub fn folder_size(dir: &Path) -> u64 {
    std::fs::read_dir(dir)
        .map(|entries| {
            entries
                .filter_map(Result::ok)
                .map(|e| match e.file_type() {
                    Ok(t) if t.is_dir() => folder_size(&e.path()),
                    _ => e.metadata().map(|m| m.len()).unwrap_or(0),
                })
                .sum()
        })
        .unwrap_or(0)
}

/// A case with one participant and no coupling: the solver runs alone (`SOLVER run CASE --out DIR`).
fn standalone(
    case: &Case,
    name: &str,
    kind: Kind,
    exe: &Path,
    launcher: &[String],
    out: &Path,
) -> Result<(), CouplerError> {
    let args = [
        "run".to_string(),
        case.path.display().to_string(),
        "--out".into(),
        out.display().to_string(),
    ];
    let (program, args) = behind_launcher(launcher, exe, &args);
    match launcher.is_empty() {
        true => crate::say!("{name}: {} solver alone ({})", kind.binary_name(), exe.display()),
        false => crate::say!(
            "{name}: {} solver alone on its ranks ({} {})",
            kind.binary_name(),
            launcher.join(" "),
            exe.display()
        ),
    }
    let status = Command::new(&program)
        .args(&args)
        .status()
        .map_err(|e| CouplerError::Participant {
            name: name.to_string(),
            window: None,
            message: format!("cannot start {}: {e}", exe.display()),
        })?;
    if status.success() {
        crate::say!(
            "output: {}, {}",
            out.display(),
            bytes_text(folder_size(out) as f64)
        );
        Ok(())
    } else if signals::interrupted() {
        Err(CouplerError::Interrupted { window: None })
    } else {
        Err(CouplerError::Participant {
            name: name.to_string(),
            window: None,
            message: format!("{} {}", kind.binary_name(), describe(status)),
        })
    }
}
