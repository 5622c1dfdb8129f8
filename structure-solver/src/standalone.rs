//! Standalone mode (`structure-solver run CASE [--out DIR]`): a structure-only case under its
//! prescribed loads, from t = 0 to `case.end_time`. Writes the declared CSV histories every
//! `history.interval` (and at the end), the frame's VTU series at the same times (at the start
//! and end without a history section), and `releases.csv` when there are supports; prints every
//! washout release when it happens and a lost energy balance (`frame/energy_check.rs`) at the
//! history interval where it happened, and at the end what the user should know about the frame
//! steps' accuracy.

use crate::frame::Frame;
use crate::load_schedule::LoadSchedule;
use crate::output::{output_times, Output};
use crate::structure::Structure;
use schemas::case::Case;
use std::path::{Path, PathBuf};

/// What a finished run reports.
#[derive(Debug, Clone, PartialEq)]
pub struct RunSummary {
    pub out_dir: PathBuf,
    pub end_time: f64,
    pub substeps: u64,
    /// Released bodies and their release times.
    pub releases: Vec<(String, f64)>,
    /// What the user should know about the run's accuracy (see [`Frame::accuracy_warning`] and
    /// [`Frame::energy_warning`]; the energy warning is also printed when it is set).
    pub warnings: Vec<String>,
}

/// Runs the structure-only case at `case_path`; output goes to `out` (default `out/<case name>`).
pub fn run(case_path: &Path, out: Option<&Path>) -> Result<RunSummary, String> {
    let case = Case::load(case_path).map_err(|e| e.to_string())?;
    if !case.fluid.is_empty() || case.structure.len() != 1 {
        let names: Vec<String> = case.participants().into_iter().map(|(n, _)| n).collect();
        return Err(format!(
            "{}: standalone mode runs a case with exactly one [structure.NAME] section and no fluid; \
             this case has participants {names:?} — run it with `coupler run`",
            case_path.display()
        ));
    }
    let Some((name, cfg)) = case.structure.iter().next() else {
        return Err(format!(
            "{}: the case has no [structure.NAME] section",
            case_path.display()
        ));
    };
    let key = format!("structure.{name}");
    let at_key = |e: schemas::case::FieldError| schemas::case::CaseError::at(&case.path, e).to_string();
    let mut structure = Structure::from_config(cfg, &key).map_err(at_key)?;
    let schedule = LoadSchedule::from_config(cfg, &key, &case.dir(), &structure).map_err(at_key)?;
    let out_dir = out.map_or_else(|| Path::new("out").join(&case.info.name), Path::to_path_buf);
    structure.record_hinge_events();
    if cfg.history.is_some() {
        structure.record_energy();
    }
    let mut output = Output::create(&out_dir, cfg, &structure)?;

    let end_time = case.info.end_time;
    let stops = cfg
        .history
        .as_ref()
        .map_or_else(|| vec![end_time], |h| output_times(h.interval, end_time));
    output.record(&structure)?;
    let loads = |t: f64| Ok(schedule.at(t));
    let mut reported = 0;
    let energy_warning = |s: &Structure| s.frame().and_then(Frame::energy_warning).map(str::to_string);
    for &t in &stops {
        let warned = energy_warning(&structure).is_some();
        let result = structure.advance(t, &loads);
        if let (false, Some(w)) = (warned, energy_warning(&structure)) {
            eprintln!("warning: {key}.frame: {w}");
        }
        let releases = structure.releases();
        for (body, at) in releases.iter().skip(reported) {
            println!("{name}: body `{body}` released at t = {at} s");
        }
        reported = releases.len();
        if let Err(e) = result {
            output.finish(&structure)?;
            return Err(format!("{}: {e}", case_path.display()));
        }
        output.record(&structure)?;
    }
    output.finish(&structure)?;
    let releases = structure
        .releases()
        .into_iter()
        .map(|(b, t)| (b.to_string(), t))
        .collect();
    let warnings = structure
        .frame()
        .map(|f| [f.accuracy_warning(), f.energy_warning().map(str::to_string)])
        .into_iter()
        .flatten()
        .flatten()
        .map(|w| format!("{key}.frame: {w}"))
        .collect();
    Ok(RunSummary {
        out_dir,
        end_time,
        substeps: structure.substeps(),
        releases,
        warnings,
    })
}
