//! [`FluidParticipant`]: the fluid solver taking part in a coupled run through
//! [`schemas::participant::serve`].
//!
//! Inputs: `body_pose` (7 per body) and `body_velocity` (6 per body), read from the window's
//! samples ([`body_motion`]): in an implicit window for the END of each substep, so that each
//! step ends with the bodies at the pose the structure returned for that time and the fluid's
//! answer follows the structure's latest iterate; in an explicit window for its start. Outputs at every exchange time: `body_force` (6 per
//! body: force and moment about the body's centre of the fluid's pressure, collision and, when
//! on, viscous pair terms, and of the walls' contact; see [`FluidSolver::body_loads`]) and
//! `body_reaction` (what the body exerted on the water and the walls: the fluid's pair terms
//! summed from the fluid's side, for the action–reaction ledger). Save/restore keep a copy of
//! the particle arrays. `advance` steps from the window start to exactly its end, shortening
//! the last substep before each exchange time. The unresolved drag coupling (S2): `reaction`
//! (6 per point: point, force) is read at the start of each substep and
//! spread over the fluid (S2-24, [`crate::unresolved::spreading`]); `sampled_velocity` (3 per
//! point) and `sampled_lambda_min` are answered at every exchange time for that time's
//! `sample_point`s ([`crate::unresolved::sampling`]). With an output folder, VTU frames (and surface meshes) are written at the first
//! exchange time at or after each output time, and the probe CSV (`NAME_probes.csv`) at the
//! first exchange time at or after each probe time, once the window is accepted. Progress lines
//! go to the participant's log at the case's `progress_interval`, and `finish` writes the run's
//! summary there. Every step is reported to the coupler as it is done (`advance_reporting`), so a
//! window longer than `coupling.timeout` is not taken for a hang.

pub(crate) mod body_motion;
pub(crate) mod probe_rows;
mod resume;

use crate::gpu::GpuDevice;
use crate::output::background::BackgroundWriter;
use crate::output::frame_files::FrameFiles;
use crate::output::progress::{peak_memory_bytes, Progress, RunSummary};
use crate::sensors::probes::{ProbeFile, ProbeSet};
use crate::solver::FluidSolver;
use crate::state::FluidState;
use probe_rows::ProbeRows;
use schemas::case::fluid::FluidBackend;
use schemas::case::Case;
use schemas::f64s::F64s;
use schemas::message::{Fields, InterfaceDecl, Role, Waveform};
use schemas::participant::{DiscardProgress, Participant, ProgressSink};
use std::path::Path;

/// A window may start this far (relative to max(1, t)) from the time the fluid is at.
const TIME_MATCH: f64 = 1e-9;

/// VTU frames of a participant: where, how often, and the frame due next.
struct Frames {
    interval: f64,
    next: u64,
    /// A state due for a frame in the last window, written once the window is accepted.
    pending: Option<crate::particles::Particles>,
    pending_time: f64,
    /// The frames' files, written on a thread of their own while the solver steps on.
    files: BackgroundWriter<FrameFiles>,
}

/// One fluid participant of a case, with its checkpoint.
pub struct FluidParticipant {
    name: String,
    solver: FluidSolver,
    checkpoint: Option<FluidState>,
    frames: Option<Frames>,
    probes: Option<ProbeRows>,
    progress: Progress,
    /// Fluid momentum at t = 0, for the momentum budget written at the end.
    initial_momentum: [f64; 3],
    /// The samples answered at the end of the last window stepped (time, velocity, λ_min).
    end_samples: Option<(f64, F64s, F64s)>,
    /// Whether the window about to be stepped is an implicit iterate (a checkpoint was saved or
    /// restored for it): its body motion is read at each substep's end, else at its start (see
    /// [`body_motion`]). Set by every implicit window's message, cleared by `advance`.
    iterated: bool,
}

impl FluidParticipant {
    /// Builds participant `name` of `case` at t = 0; with `out`, writes VTU frames there.
    pub fn from_case(case: &Case, name: &str, out: Option<&Path>) -> Result<Self, String> {
        let cfg = case.fluid.get(name).ok_or_else(|| {
            let names: Vec<&String> = case.fluid.keys().collect();
            format!(
                "{}: there is no [fluid.{name}] section; fluid participants: {names:?}",
                case.path.display()
            )
        })?;
        let mut solver = FluidSolver::new(cfg);
        for note in solver.layout_notes() {
            eprintln!("fluid `{name}`: note: {note}");
        }
        for warning in solver.warnings() {
            eprintln!("warning: fluid `{name}`: {warning}");
        }
        let frames = match out {
            Some(dir) => {
                std::fs::create_dir_all(dir).map_err(|e| format!("cannot create {}: {e}", dir.display()))?;
                let mut files = FrameFiles::new(dir.to_path_buf(), name, cfg.spacing, cfg.surface_mesh);
                files.write(0, 0.0, solver.particles(), &mut DiscardProgress)?;
                Some(Frames {
                    interval: cfg.output_interval,
                    next: 1,
                    pending: None,
                    pending_time: 0.0,
                    files: BackgroundWriter::new(files),
                })
            }
            None => None,
        };
        solver.remove_gates();
        if cfg.backend == FluidBackend::Gpu {
            let dev = GpuDevice::open().map_err(|e| format!("fluid `{name}`: {e}"))?;
            solver
                .to_device(cfg, dev)
                .map_err(|e| format!("fluid `{name}`: {e}"))?;
            eprintln!(
                "fluid `{name}`: on the GPU: {}",
                solver.device().map_or(String::new(), |d| d.dev.description())
            );
        }
        let probes = match out {
            Some(dir) if !cfg.probe.is_empty() => {
                let path = dir.join(format!("{name}_probes.csv"));
                let probes = ProbeSet::new(&cfg.probe, &solver)
                    .map_err(|e| format!("{}: fluid `{name}`: {e}", case.path.display()))?;
                let file = ProbeFile::create(&path, &probes.names())
                    .map_err(|e| format!("cannot write {}: {e}", path.display()))?;
                let interval = cfg.probe_interval.unwrap_or(cfg.output_interval);
                let mut rows = ProbeRows::new(path, Some(file), probes, interval);
                rows.sample(&solver);
                rows.commit()?;
                Some(rows)
            }
            _ => None,
        };
        Ok(Self {
            name: name.to_string(),
            initial_momentum: solver.fluid_momentum(),
            end_samples: None,
            iterated: false,
            solver,
            checkpoint: None,
            frames,
            probes,
            // the participant's stderr is its log file, never a terminal
            progress: Progress::new(
                &format!("fluid `{name}`"),
                case.info.end_time,
                cfg.progress_interval,
                false,
            ),
        })
    }

    /// The solver as it is now.
    pub fn solver(&self) -> &FluidSolver {
        &self.solver
    }

    /// The interface outputs of the current state.
    pub fn outputs(&self) -> Fields {
        Fields {
            body_force: F64s(self.solver.body_loads()),
            body_reaction: F64s(self.solver.body_reactions()),
            ..Fields::default()
        }
    }

    /// The interface outputs of the current state, with the flow at the sample points of `inputs`
    /// (and the shares of its reactions kept for the next step's spreading, used when the next
    /// window's reactions act at the same centroids: a fixed member).
    fn outputs_at(&self, inputs: Option<&Fields>) -> Fields {
        let mut out = self.outputs();
        if let Some(f) = inputs.filter(|f| !f.sample_point.is_empty()) {
            let (v, lambda) = self
                .solver
                .sample_points_for(&f.sample_point, &f.reaction, &f.reaction_width);
            out.sampled_velocity = F64s(v);
            out.sampled_lambda_min = F64s(lambda);
        }
        out
    }

    /// The outputs at a window start. The samples there are never read by the coupler's laws
    /// (they read the samples after the window start; the window-start values come from the
    /// last window's end), so when the last window stepped ended here with as many sample
    /// points, its samples are repeated instead of sampled again (they are this state's flow at
    /// the last window's points, which differ from this window's by the upstream update only).
    fn window_start_outputs(&self, inputs: Option<&Fields>) -> Fields {
        let points = inputs.map_or(0, |f| f.sample_point.len());
        match &self.end_samples {
            Some((t, v, lambda)) if *t == self.solver.time() && 3 * lambda.len() == points => Fields {
                sampled_velocity: v.clone(),
                sampled_lambda_min: lambda.clone(),
                ..self.outputs()
            },
            _ => self.outputs_at(inputs),
        }
    }

    /// Hands the point reactions of `f` to the solver (6 per reaction; their paired sample
    /// points, when given, 3 per reaction; their members' widths, when given, 1 per reaction).
    fn set_point_reactions(&mut self, f: &Fields) -> Result<(), String> {
        check_point_reactions(&self.name, f)?;
        self.solver
            .set_point_reactions(&f.reaction, &f.sample_point, &f.reaction_width);
        Ok(())
    }

    /// Says on stderr when point reactions found no fluid near their centroid or sample point
    /// in the window just stepped (they were not applied; see [`crate::unresolved::spreading`]).
    fn warn_unapplied(&self, before: [f64; 3]) {
        let now = self.solver.totals().unapplied_impulse;
        if now != before {
            let v = |f: [f64; 3]| format!("({:.3e}, {:.3e}, {:.3e})", f[0], f[1], f[2]);
            let window = v([now[0] - before[0], now[1] - before[1], now[2] - before[2]]);
            eprintln!(
                "warning: fluid `{}`: in the window ending at t = {:.6} s, point reactions with no fluid particle near \
                 their centroid or sample point were not applied: impulse {window} N s ({} N s since the start)",
                self.name,
                self.solver.time(),
                v(now)
            );
        }
    }

    /// With the drag coupling on: the fluid's momentum budget since t = 0 on stderr (the log),
    /// `change = gravity + walls + drag reactions` to round-off when no particle entered or left.
    fn report_momentum(&self) {
        let totals = self.solver.totals();
        if totals.reaction_impulse == [0.0; 3] && totals.unapplied_impulse == [0.0; 3] {
            return;
        }
        let p = self.solver.particles();
        let mass = p.count(crate::Kind::Fluid) as f64 * self.solver.particle_mass();
        let g = self.solver.physics().gravity;
        let t = self.solver.time();
        let now = self.solver.fluid_momentum();
        let v = |f: [f64; 3]| format!("{:.12e} {:.12e} {:.12e}", f[0], f[1], f[2]);
        eprintln!(
            "fluid `{}`: momentum budget [N s] at t = {t}: change {} | gravity {} | walls {} | drag reactions {} | not applied {}",
            self.name,
            v(std::array::from_fn(|c| now[c] - self.initial_momentum[c])),
            v(g.map(|gc| mass * gc * t)),
            v(totals.wall_impulse),
            v(totals.reaction_impulse),
            v(totals.unapplied_impulse)
        );
    }

    /// Writes the probe rows kept back from the last window (that window was accepted) and
    /// starts writing its frame on the frames' thread, telling `progress` of the bytes written
    /// while it waits for the frame before.
    fn commit(&mut self, progress: &mut dyn ProgressSink) -> Result<(), String> {
        if let Some(p) = &mut self.probes {
            p.commit()?;
        }
        if let Some(f) = &mut self.frames {
            if let Some(p) = f.pending.take() {
                let (k, time) = (f.next, f.pending_time);
                f.files.start(progress, move |files, progress| {
                    files.write(k, time, &p, progress)
                })?;
                f.next += 1;
            }
        }
        Ok(())
    }

    /// Waits until every frame committed so far is written.
    fn flush_frames(&mut self, progress: &mut dyn ProgressSink) -> Result<(), String> {
        match &mut self.frames {
            Some(f) => f.files.wait(progress).map(|_| ()),
            None => Ok(()),
        }
    }
}

/// Checks the point reactions of `f` for fluid `name`: 6 values per reaction, 3 per paired
/// sample point, and one finite width ≥ 0 per reaction (or none).
pub(crate) fn check_point_reactions(name: &str, f: &Fields) -> Result<(), String> {
    if !f.reaction.len().is_multiple_of(6) || !f.sample_point.len().is_multiple_of(3) {
        return Err(format!(
            "fluid `{name}`: reaction needs 6 values per point and sample_point 3, got {} and {}",
            f.reaction.len(),
            f.sample_point.len()
        ));
    }
    if !f.reaction_width.is_empty() && 6 * f.reaction_width.len() != f.reaction.len() {
        return Err(format!(
            "fluid `{name}`: reaction_width needs 1 value per reaction (or none), got {} for {} reactions",
            f.reaction_width.len(),
            f.reaction.len() / 6
        ));
    }
    if let Some(w) = f.reaction_width.iter().find(|w| !(w.is_finite() && **w >= 0.0)) {
        return Err(format!(
            "fluid `{name}`: reaction_width must be finite and ≥ 0 m, got {w}"
        ));
    }
    Ok(())
}

impl Participant for FluidParticipant {
    fn role(&self) -> Role {
        Role::Fluid
    }

    fn time(&self) -> f64 {
        self.solver.time()
    }

    fn interface(&self) -> InterfaceDecl {
        InterfaceDecl {
            bodies: self.solver.body_names().to_vec(),
            ..InterfaceDecl::default()
        }
    }

    fn initial_outputs(&mut self) -> Fields {
        self.outputs()
    }

    fn save_checkpoint(&mut self) {
        self.iterated = true;
        self.solver.sync_host();
        self.checkpoint = Some(self.solver.save_state());
        if let Some(p) = &mut self.probes {
            p.save_filters();
        }
    }

    fn restore_checkpoint(&mut self) -> Result<(), String> {
        self.iterated = true;
        if let Some(f) = &mut self.frames {
            f.pending = None;
        }
        if let Some(p) = &mut self.probes {
            p.restore_filters();
        }
        let saved = self.checkpoint.as_ref().ok_or_else(|| {
            format!(
                "fluid `{}`: asked to restore a checkpoint, but none was saved",
                self.name
            )
        })?;
        self.solver.restore_state(saved);
        Ok(())
    }

    fn advance(&mut self, inputs: &Waveform) -> Result<Vec<Fields>, String> {
        self.advance_reporting(inputs, &mut DiscardProgress)
    }

    /// Advances over the window, telling `progress` of every step.
    fn advance_reporting(
        &mut self,
        inputs: &Waveform,
        progress: &mut dyn ProgressSink,
    ) -> Result<Vec<Fields>, String> {
        let now = self.solver.time();
        let start = inputs.start();
        if (start - now).abs() > TIME_MATCH * now.abs().max(1.0) {
            return Err(format!(
                "fluid `{}`: the window starts at t = {start} s but the fluid is at t = {now} s",
                self.name
            ));
        }
        self.commit(progress)?;
        let bodies = self.solver.body_names().len();
        let reactions = inputs.samples.iter().any(|s| !s.reaction.is_empty());
        let unapplied_before = self.solver.totals().unapplied_impulse;
        let motion_at_end = std::mem::take(&mut self.iterated);
        let mut outputs = vec![self.window_start_outputs(inputs.samples.first())];
        for (j, &t) in inputs.times.iter().enumerate().skip(1) {
            while let Some(dt) = self.solver.next_step_towards(t) {
                if bodies > 0 {
                    let (read_at, lead) = match motion_at_end {
                        true => (self.solver.time() + dt, dt),
                        false => (self.solver.time(), 0.0),
                    };
                    let (pose, velocity) = body_motion::at(inputs, read_at)?;
                    if !pose.is_empty() || !velocity.is_empty() {
                        self.solver.set_body_motion(&pose, &velocity, lead)?;
                    }
                }
                if bodies > 0 || reactions {
                    self.set_point_reactions(&inputs.at(self.solver.time())?)?;
                }
                self.solver
                    .step(dt)
                    .map_err(|e| format!("fluid `{}`: {e}", self.name))?;
                progress.step_done(self.solver.time());
                if let Some(p) = &mut self.probes {
                    let next = p.next_row();
                    p.probes.observe(&self.solver, next);
                }
                let s = &self.solver;
                self.progress
                    .update(s.time(), s.steps(), s.totals().particle_steps, s.particle_count());
                self.progress.note_escapes(s.time(), s.escaped());
            }
            self.solver.land_on(t);
            outputs.push(self.outputs_at(inputs.samples.get(j)));
            if let Some(p) = &mut self.probes {
                if p.due(t) {
                    p.sample(&self.solver);
                }
            }
            if let Some(f) = &mut self.frames {
                let due = f.next as f64 * f.interval - 1e-9 * f.interval;
                if f.pending.is_none() && t >= due {
                    f.pending = Some(self.solver.frame_particles().into_owned());
                    f.pending_time = t;
                }
            }
        }
        self.end_samples = outputs
            .last()
            .filter(|o| !o.sampled_lambda_min.is_empty())
            .map(|o| {
                (
                    self.solver.time(),
                    o.sampled_velocity.clone(),
                    o.sampled_lambda_min.clone(),
                )
            });
        self.warn_unapplied(unapplied_before);
        Ok(outputs)
    }

    fn write_checkpoint(&mut self, path: &Path, progress: &mut dyn ProgressSink) -> Result<u64, String> {
        self.checkpoint_to(path, progress)
    }

    fn finish(&mut self, progress: &mut dyn ProgressSink) -> Result<(), String> {
        self.solver.sync_host();
        if self.solver.open_boundaries().is_active() {
            let (b, p) = (self.solver.open_boundaries().balance(), self.solver.particles());
            eprintln!(
                "fluid `{}`: open boundaries at t = {} s: {} inserted, {} entered, {} removed, {} withdrawn; {} fluid, {} inflow, {} particles",
                self.name,
                self.solver.time(),
                b.inserted,
                b.entered,
                b.removed,
                b.withdrawn,
                p.count(crate::Kind::Fluid),
                p.count(crate::Kind::Inflow),
                p.len()
            );
        }
        self.report_momentum();
        self.commit(progress)?;
        self.flush_frames(progress)?;
        let s = &self.solver;
        let summary = RunSummary {
            time: s.time(),
            steps: s.steps(),
            particles: s.particles().len(),
            fluid_particles: s.particles().count(crate::Kind::Fluid),
            frames: self.frames.as_ref().map_or(0, |f| f.next as usize),
            wall_seconds: self.progress.elapsed(),
            particle_steps: s.totals().particle_steps,
            peak_memory: peak_memory_bytes(),
            escaped: s.escaped(),
            outflow_removed: s.open_boundaries().balance().removed,
            host_copies: s.host_copies(),
            device_seconds: s.device_seconds(),
            advective_cuts: (s.totals().advective_cuts, s.totals().fastest_cut),
        };
        eprintln!("fluid `{}`: done: {summary}", self.name);
        Ok(())
    }
}
