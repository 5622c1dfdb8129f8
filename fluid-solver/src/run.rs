//! A standalone run of a fluid-only case: steps to `case.end_time`, writes VTU frames with a
//! PVD series (and free-surface VTP frames when `surface_mesh = true`) every `output_interval`
//! and a probe CSV every `probe_interval` (with an inflow or outflow also `NAME_balance.csv`,
//! the particle balance of [`crate::boundaries::open_boundary`]); reports progress at a steady interval
//! ([`crate::output::progress`]) and returns the run's summary.

use crate::boundaries::open_boundary::BalanceFile;
use crate::gpu::driver::GpuStartError;
use crate::output::background::BackgroundWriter;
use crate::output::frame_files::FrameFiles;
pub use crate::output::progress::RunSummary;
use crate::output::progress::{peak_memory_bytes, Progress};
use crate::sensors::probes::{ProbeFile, ProbeSet};
use crate::sensors::view::ParticleView;
use crate::solver::FluidSolver;
use crate::stability::Instability;
use schemas::case::{Case, FluidConfig};
use schemas::participant::DiscardProgress;
use std::fmt;
use std::path::{Path, PathBuf};

/// Why a standalone run did not finish.
#[derive(Debug)]
pub enum RunError {
    /// The case is not a fluid-only case with exactly one `[fluid.NAME]` section.
    NotFluidOnly { file: PathBuf, message: String },
    /// An output could not be written.
    Output { path: PathBuf, error: std::io::Error },
    /// A frame could not be written (the message names its file).
    Frames(String),
    /// A probe cannot be placed where the case puts it.
    Probe { file: PathBuf, message: String },
    /// The run became unstable; the frames written so far are kept.
    Unstable(Instability),
    /// `backend = "gpu"` and no GPU, or a case the GPU path does not run (bad usage).
    Gpu { file: PathBuf, error: GpuStartError },
    /// The ranks of a run on MPI could not trade their particles.
    Ranks { message: String },
}

impl fmt::Display for RunError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            RunError::NotFluidOnly { file, message } => write!(f, "{}: {message}", file.display()),
            RunError::Output { path, error } => write!(f, "cannot write {}: {error}", path.display()),
            RunError::Probe { file, message } => write!(f, "{}: {message}", file.display()),
            RunError::Unstable(i) => write!(f, "{i}"),
            RunError::Gpu { file, error } => write!(f, "{}: {error}", file.display()),
            RunError::Ranks { message } => write!(f, "{message}"),
            RunError::Frames(message) => write!(f, "{message}"),
        }
    }
}

impl std::error::Error for RunError {}

/// The single fluid section of a fluid-only case.
pub fn fluid_only(case: &Case) -> Result<(&str, &FluidConfig), RunError> {
    let err = |message: String| RunError::NotFluidOnly {
        file: case.path.clone(),
        message,
    };
    if !case.structure.is_empty() || case.coupling.is_some() {
        return Err(err(
            "the fluid solver runs alone only on a fluid-only case (one [fluid.NAME] section, no [structure.*], no [coupling]); run coupled cases with `coupler run`".into(),
        ));
    }
    let mut it = case.fluid.iter();
    match (it.next(), it.next()) {
        (Some((name, cfg)), None) => Ok((name.as_str(), cfg)),
        _ => Err(err(format!(
            "a fluid-only case needs exactly one [fluid.NAME] section, found {}",
            case.fluid.len()
        ))),
    }
}

/// Runs the case's fluid participant to `case.end_time`, writing into `out`; progress goes to
/// stderr as log lines, or as a bar when `terminal`. Messages about geometry moved onto the
/// lattice are printed first.
pub fn run_case(case: &Case, out: &Path, terminal: bool) -> Result<RunSummary, RunError> {
    let (name, cfg) = fluid_only(case)?;
    let io_err = |path: &Path| {
        let path = path.to_path_buf();
        move |error| RunError::Output { path, error }
    };
    std::fs::create_dir_all(out).map_err(io_err(out))?;
    let mut solver = FluidSolver::with_backend(cfg).map_err(|error| RunError::Gpu {
        file: case.path.clone(),
        error,
    })?;
    if let Some(d) = solver.device() {
        eprintln!("{name}: running on the GPU {}", d.dev.description());
    }
    for note in solver.layout_notes() {
        eprintln!("{name}: note: {note}");
    }
    for warning in solver.warnings() {
        eprintln!("warning: {name}: {warning}");
    }
    let mut probes = ProbeSet::new(&cfg.probe, &solver).map_err(|message| RunError::Probe {
        file: case.path.clone(),
        message,
    })?;
    let probe_path = out.join(format!("{name}_probes.csv"));
    let mut probe_file = ProbeFile::create(&probe_path, &probes.names()).map_err(io_err(&probe_path))?;
    let probe_interval = cfg.probe_interval.unwrap_or(cfg.output_interval);
    let end = case.info.end_time;
    let mut progress = Progress::new(name, end, cfg.progress_interval, terminal);

    let mut frames = 0usize;
    let mut frame_files = BackgroundWriter::new(FrameFiles::new(
        out.to_path_buf(),
        name,
        cfg.spacing,
        cfg.surface_mesh,
    ));
    // a frame's particles are copied (on the GPU path downloaded by `FluidSolver::frame_particles`,
    // the last frame into the host's own particles) and written on the frames' thread while the
    // solver steps on
    let mut write_frame = |solver: &mut FluidSolver| -> Result<(), RunError> {
        let time = solver.time();
        if time >= end {
            // the last frame: the host's copy is brought up to date for the summary anyway
            solver.sync_host();
        }
        let particles = solver.frame_particles().into_owned();
        let k = frames as u64;
        frame_files
            .start(&mut DiscardProgress, move |files, progress| {
                files.write(k, time, &particles, progress)
            })
            .map_err(RunError::Frames)?;
        frames += 1;
        Ok(())
    };
    let balance_path = out.join(format!("{name}_balance.csv"));
    let mut balance = match solver.open_boundaries().is_active() {
        true => Some(BalanceFile::create(&balance_path).map_err(io_err(&balance_path))?),
        false => None,
    };
    let mut sample =
        |solver: &FluidSolver, probes: &mut ProbeSet, file: &mut ProbeFile| -> Result<(), RunError> {
            let view = ParticleView::of(solver);
            if let Some(b) = &mut balance {
                let counts = solver.open_boundaries().balance();
                b.row(solver.time(), counts, view.all(), solver.particle_mass())
                    .map_err(io_err(&balance_path))?;
            }
            let values = probes.row_in(&view);
            file.row(solver.time(), &values, solver.removed())
                .map_err(io_err(&probe_path))
        };
    write_frame(&mut solver)?;
    solver.remove_gates();
    sample(&solver, &mut probes, &mut probe_file)?;
    let (mut next_frame, mut next_probe) = (1u64, 1u64);
    let at = |k: u64, interval: f64| (k as f64 * interval).min(end);
    while solver.time() < end {
        let row_at = at(next_probe, probe_interval);
        let target = at(next_frame, cfg.output_interval).min(row_at);
        while let Some(dt) = solver.next_step_towards(target) {
            solver.step(dt).map_err(|e| {
                progress.finish();
                RunError::Unstable(e)
            })?;
            probes.observe(&solver, row_at);
            let totals = solver.totals();
            progress.update(
                solver.time(),
                solver.steps(),
                totals.particle_steps,
                solver.particle_count(),
            );
            progress.note_escapes(solver.time(), solver.escaped());
        }
        solver.land_on(target);
        if solver.time() >= row_at {
            sample(&solver, &mut probes, &mut probe_file)?;
            next_probe += 1;
        }
        if solver.time() >= at(next_frame, cfg.output_interval) {
            write_frame(&mut solver)?;
            next_frame += 1;
        }
    }
    frame_files.wait(&mut DiscardProgress).map_err(RunError::Frames)?;
    progress.finish();
    solver.sync_host();
    Ok(RunSummary {
        time: solver.time(),
        steps: solver.steps(),
        particles: solver.particles().len(),
        fluid_particles: solver.particles().count(crate::Kind::Fluid),
        frames,
        wall_seconds: progress.elapsed(),
        particle_steps: solver.totals().particle_steps,
        peak_memory: peak_memory_bytes(),
        escaped: solver.escaped(),
        outflow_removed: solver.open_boundaries().balance().removed,
        host_copies: solver.host_copies(),
        device_seconds: solver.device_seconds(),
        advective_cuts: (solver.totals().advective_cuts, solver.totals().fastest_cut),
    })
}
