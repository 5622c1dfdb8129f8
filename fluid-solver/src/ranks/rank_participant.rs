//! A fluid participant of a coupled run on MPI ranks (`ranks = N` in its section; cargo feature
//! `mpi`). The coupler starts it through the section's launcher and sees one participant: rank 0
//! serves the coupler ([`schemas::participant::serve`], through [`Leader`]) and sends each
//! request on to the other ranks as an [`Order`]; every rank then does it on its own slab
//! ([`super::rank_slab`]) with the same steps, so the ranks step as the case in N slabs of one
//! process. The other ranks wait for orders asleep between probes ([`RankLink::next_order`]).
//!
//! What the coupler gets is the whole fluid's: the bodies' loads and reactions summed over the
//! ranks (each reports the share of the fluid it owns and of the walls between its cuts), at
//! t = 0 those of the undivided layout; the flow at the drag law's sample points from the rank
//! whose slab holds each point. Every rank spreads every point reaction over the particles it
//! holds (its owned particles' shares are the undivided fluid's when the member is narrow enough
//! for the halo: [`RankParticipant::widest_member`]). Frames are written as a standalone run on ranks writes
//! them ([`super::rank_frames`]; the first after the gates are lifted), probe rows by rank 0, both
//! once the window is accepted, as one process does. A checkpoint is one file per rank, rank r's
//! beside rank 0's (`NAME-W.bin`, `NAME.rR-W.bin`), and resumes on as many ranks.
//!
//! A failure every rank learns of (a step that went unstable on one rank, a file one rank
//! cannot write) reaches the coupler from rank 0 naming the rank; a failure of the ranks' own
//! link stops every rank at once (`MPI_Abort`), and the coupler names the participant whose
//! process ended. The participant's log gets no momentum budget and no warning of reactions
//! left unapplied from the ranks (each rank's account covers the particles it holds).

use super::mpi_link::RankLink;
use super::rank_frames::RankFrames;
use super::rank_run::{RankRunError, RankRunSummary};
use super::rank_slab::RankSlab;
use super::slab_plan::SlabPlan;
use super::slab_probes::SlabProbes;
use super::subdomain::SlabState;
use crate::output::progress::Progress;
use crate::participant::body_motion;
use crate::participant::probe_rows::{ProbeRows, SavedProbes};
use crate::particles::Particles;
use crate::run::RunError;
use crate::sensors::probes::ProbeFile;
use crate::sensors::view::ParticleView;
use crate::solver::FluidSolver;
use crate::state::RunState;
use schemas::case::Case;
use schemas::f64s::F64s;
use schemas::message::{Fields, InterfaceDecl, Role, Waveform};
use schemas::participant::{DiscardProgress, Participant, ProgressSink};
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};
use std::time::Instant;

/// A window may start this far (relative to max(1, t)) from the time the fluid is at.
const TIME_MATCH: f64 = 1e-9;

/// What rank 0 tells the other ranks to do: the coupler's request it got.
#[derive(bincode::Encode, bincode::Decode)]
enum Order {
    Save,
    Restore,
    Advance(Waveform),
    WriteCheckpoint(String),
    Finish,
    /// Rank 0 stopped serving (the run ended early): stop waiting.
    Stop,
}

/// One rank of a fluid participant on ranks: its slab and what it writes.
pub struct RankParticipant<'a> {
    name: String,
    me: RankSlab<'a>,
    /// The whole fluid's outputs now (the bodies' loads and reactions summed over the ranks).
    current: Fields,
    /// The samples answered at the end of the last window stepped (time, velocity, λ_min).
    end_samples: Option<(f64, F64s, F64s)>,
    saved: Option<WindowStart>,
    frames: Option<RankFrames>,
    /// The state due for a frame in the last window (time, this rank's piece), written once the
    /// window is accepted.
    pending_frame: Option<(f64, Particles)>,
    frame_interval: f64,
    probes: Option<ProbeRows>,
    /// How the ranks' probe rows make the whole fluid's.
    combine: SlabProbes,
    /// Rank 0's progress lines.
    progress: Option<Progress>,
    /// The window about to be stepped is an implicit iterate: body motion is read at each
    /// substep's end (as [`crate::participant::FluidParticipant`] does).
    iterated: bool,
    fluid_at_start: u64,
    started: Instant,
    step_seconds: f64,
}

/// The in-memory checkpoint of an implicit window: the slab, the outputs, the energy check's
/// reference.
struct WindowStart {
    slab: SlabState,
    outputs: Fields,
    energy: (Option<f64>, f64, bool),
}

/// What one rank's checkpoint file holds.
#[derive(Serialize, Deserialize)]
struct SavedRank {
    name: String,
    rank: usize,
    ranks: usize,
    slab: SlabState,
    run: RunState,
    whole: (Option<f64>, f64, bool),
    current: (Vec<f64>, Vec<f64>),
    end_samples: Option<(f64, Vec<f64>, Vec<f64>)>,
    moved: (u64, u64),
    /// Where the slabs were cut, how many times they were cut again, and the step of the last
    /// count.
    cuts: Vec<f64>,
    recuts: (u64, u64),
    /// Frames written and rank 0's series of indexes.
    frames: Option<(u64, Vec<(f64, String)>)>,
    /// Probe rows written and this rank's filters' readings.
    probes: Option<SavedProbes>,
}

/// Rank r's checkpoint file: rank 0's own, `NAME.rR-W.bin` beside rank 0's `NAME-W.bin` for the
/// others (the window stays last, so the coupler keeps and prunes them with rank 0's).
pub fn rank_file(path: &Path, rank: usize) -> PathBuf {
    let name = path.file_name().and_then(|n| n.to_str()).unwrap_or_default();
    match (rank, name.rsplit_once('-')) {
        (0, _) => path.to_path_buf(),
        (r, Some((who, window))) => path.with_file_name(format!("{who}.r{r}-{window}")),
        (r, None) => path.with_file_name(format!("{name}.r{r}")),
    }
}

impl<'a> RankParticipant<'a> {
    /// This rank of participant `name` of `case` at t = 0 (every rank calls it), writing frames
    /// and probe rows into `out`.
    pub fn from_case(
        case: &Case,
        name: &str,
        out: Option<&Path>,
        link: &'a RankLink,
    ) -> Result<Self, String> {
        let built = Self::build(case, name, out, link, true);
        link.agree(built)
    }

    /// This rank of participant `name` of `case` continued from the checkpoint whose rank-0 file
    /// is `from` (every rank calls it; each reads its own file, written on as many ranks).
    pub fn resume(
        case: &Case,
        name: &str,
        out: Option<&Path>,
        from: &Path,
        link: &'a RankLink,
    ) -> Result<Self, String> {
        let resumed = Self::build(case, name, out, link, false).and_then(|mut p| {
            p.restore_from(&rank_file(from, link.rank()))?;
            Ok(p)
        });
        link.agree(resumed)
    }

    fn build(
        case: &Case,
        name: &str,
        out: Option<&Path>,
        link: &'a RankLink,
        first_frame: bool,
    ) -> Result<Self, String> {
        let cfg = case.fluid.get(name).ok_or_else(|| {
            let names: Vec<&String> = case.fluid.keys().collect();
            format!(
                "{}: there is no [fluid.{name}] section; fluid participants: {names:?}",
                case.path.display()
            )
        })?;
        let (rank, ranks) = (link.rank(), link.size());
        if let Some(f) = cfg.unsupported_on_ranks() {
            return Err(format!(
                "{}: fluid `{name}` on {ranks} MPI ranks: not yet {f}",
                case.path.display()
            ));
        }
        let mut solver = FluidSolver::new(cfg);
        if rank == 0 {
            for note in solver.layout_notes() {
                eprintln!("fluid `{name}`: note: {note}");
            }
            for warning in solver.warnings() {
                eprintln!("warning: fluid `{name}`: {warning}");
            }
        }
        let plan = SlabPlan::new(&mut solver, &cfg.probe, ranks).map_err(|e| {
            format!(
                "{}: fluid `{name}` on {ranks} MPI ranks: {e}",
                case.path.display()
            )
        })?;
        // what one process answers at t = 0: the undivided layout's loads, gates lifted
        let current = Fields {
            body_force: F64s(solver.body_loads()),
            body_reaction: F64s(solver.body_reactions()),
            ..Fields::default()
        };
        let SlabPlan {
            everything,
            cuts,
            probes: combine,
            mut probe_sets,
            whole,
            fluid_at_start,
            recut,
        } = plan;
        // the whole layout's solver, its gates lifted by the plan, steps this rank's slab (as
        // the standalone rank run's does)
        let me = RankSlab::new(solver, &everything, link, whole, cuts, recut);
        drop(everything);
        let set = probe_sets.swap_remove(rank);
        let mut p = RankParticipant {
            name: name.to_string(),
            me,
            current,
            end_samples: None,
            saved: None,
            frames: None,
            pending_frame: None,
            frame_interval: cfg.output_interval,
            probes: None,
            combine,
            progress: (rank == 0).then(|| {
                Progress::new(
                    &format!("fluid `{name}`"),
                    case.info.end_time,
                    cfg.progress_interval,
                    false,
                )
            }),
            iterated: false,
            fluid_at_start,
            started: Instant::now(),
            step_seconds: 0.0,
        };
        let Some(dir) = out else {
            return Ok(p);
        };
        std::fs::create_dir_all(dir).map_err(|e| format!("cannot create {}: {e}", dir.display()))?;
        p.frames = Some(RankFrames::new(dir, name));
        if !cfg.probe.is_empty() {
            let path = dir.join(format!("{name}_probes.csv"));
            let file = match (rank, first_frame) {
                (0, true) => Some(ProbeFile::create(&path, &set.names())),
                (0, false) => Some(ProbeFile::append(&path)),
                _ => None,
            }
            .transpose()
            .map_err(|e| format!("cannot write {}: {e}", path.display()))?;
            let interval = cfg.probe_interval.unwrap_or(cfg.output_interval);
            p.probes = Some(ProbeRows::new(path, file, set, interval));
        }
        if first_frame {
            // a collective step: every rank builds the same, so none is missing here
            let t = p.time();
            let piece = p.me.piece();
            if let Some(f) = &mut p.frames {
                f.write(link, t, &piece)?;
            }
            if p.probes.is_some() {
                p.sample_probes();
                p.commit()?;
            }
        }
        Ok(p)
    }

    fn time(&self) -> f64 {
        self.me.slab.solver.time()
    }

    fn rank(&self) -> usize {
        self.me.link.rank()
    }

    /// The whole fluid's probe row now, kept until the window is accepted (every rank).
    fn sample_probes(&mut self) {
        let link = self.me.link;
        let (balance, counts) = self.me.balance();
        let removed = self.fluid_at_start + balance.entered - counts[1];
        let t = self.time();
        let Some(probes) = &mut self.probes else {
            return;
        };
        let rows = link.all_rows(&probes.probes.row_in(&ParticleView::of(&self.me.slab.solver)));
        probes.keep(t, self.combine.combine(&rows), removed);
    }

    /// Writes the frame and probe rows kept back from the accepted window (every rank).
    fn commit(&mut self) -> Result<(), String> {
        let link = self.me.link;
        let rows = self.probes.as_mut().map_or(Ok(()), ProbeRows::commit);
        link.agree(rows)?;
        if let (Some(frames), Some((t, piece))) = (&mut self.frames, self.pending_frame.take()) {
            frames.write(link, t, &piece)?;
        }
        Ok(())
    }

    /// The bodies' loads and reactions of the last step, summed over the ranks (every rank).
    fn summed_outputs(&self) -> Fields {
        let (link, s) = (self.me.link, &self.me.slab.solver);
        Fields {
            body_force: F64s(link.sum_each(&s.body_loads())),
            body_reaction: F64s(link.sum_each(&s.body_reactions())),
            ..Fields::default()
        }
    }

    /// One step of `dt` with the exchanges; a failure on any rank is one on every rank, rank 0's
    /// naming the rank. A failure of the ranks' own link stops every rank.
    fn step(&mut self, dt: f64) -> Result<(), String> {
        let stepping = Instant::now();
        let stepped = self.me.step(dt);
        self.step_seconds += stepping.elapsed().as_secs_f64();
        match stepped {
            Ok(()) => Ok(()),
            Err(RankRunError::Here(RunError::Ranks { message })) => {
                eprintln!(
                    "error: fluid `{}`: rank {}: {message}; stopping every rank",
                    self.name,
                    self.rank()
                );
                self.me.link.abort(1)
            }
            Err(e) => {
                let mine = match &e {
                    RankRunError::Elsewhere { .. } => String::new(),
                    e => e.to_string(),
                };
                Err(format!(
                    "fluid `{}` on {} ranks: {}",
                    self.name,
                    self.me.link.size(),
                    self.me.link.failures_at_root(&mine)
                ))
            }
        }
    }

    /// The widest member whose reactions the ranks spread as one process does: a slab that owns
    /// a particle within a reaction's reach (`a + R` of its centroid or its sample point, a
    /// member width upstream; `a = (D − Δs)/2`, `R` the drag kernel's support) must hold every
    /// particle within that reach of both, so `2 D + 2 R − Δs` must fit in the halo.
    fn widest_member(&self) -> f64 {
        let ds = self.me.slab.solver.kernel().spacing;
        let support = schemas::case::drag::KERNEL_SUPPORT_IN_SPACINGS * ds;
        0.5 * (self.me.recut.halo - 2.0 * support + ds)
    }

    /// Hands the point reactions of `f` to this rank's slab (every rank spreads every reaction
    /// over the particles it holds; the halo copies' shares are dropped with them, the owned
    /// particles' are the undivided fluid's), after the checks one process makes and that of
    /// the members' width against the halo ([`RankParticipant::widest_member`]).
    fn set_point_reactions(&mut self, f: &Fields) -> Result<(), String> {
        crate::participant::check_point_reactions(&self.name, f)?;
        let widest = self.widest_member();
        if let Some(w) = f.reaction_width.iter().find(|&&w| w > widest) {
            return Err(format!(
                "fluid `{}` on {} MPI ranks: a member {w} m wide spreads its reactions farther than the ranks' halo of {:.4} m covers (at most {widest:.4} m wide here); set the fluid's ranks = 1 for this case",
                self.name,
                self.me.link.size(),
                self.me.recut.halo
            ));
        }
        self.me
            .slab
            .solver
            .set_point_reactions(&f.reaction, &f.sample_point, &f.reaction_width);
        Ok(())
    }

    /// The whole fluid's outputs now with the flow at the sample points of `inputs`: each
    /// point is sampled by the rank whose slab holds it (its halo holds the point's support),
    /// the others answer 0, and the sum goes to the coupler (every rank).
    fn outputs_at(&self, inputs: Option<&Fields>) -> Fields {
        let mut out = self.current.clone();
        if let Some(f) = inputs.filter(|f| !f.sample_point.is_empty()) {
            let s = &self.me.slab;
            let (mut v, mut lambda) =
                s.solver
                    .sample_points_for(&f.sample_point, &f.reaction, &f.reaction_width);
            for (k, x) in f.sample_point.chunks_exact(3).enumerate() {
                if !(s.lo <= x[0] && x[0] < s.hi) {
                    v[3 * k..3 * k + 3].fill(0.0);
                    lambda[k] = 0.0;
                }
            }
            out.sampled_velocity = F64s(self.me.link.sum_each(&v));
            out.sampled_lambda_min = F64s(self.me.link.sum_each(&lambda));
        }
        out
    }

    /// The outputs at a window start, as [`crate::participant::FluidParticipant`] gives them:
    /// the last window's end samples when it ended here with as many points, else sampled now.
    fn window_start_outputs(&self, inputs: Option<&Fields>) -> Fields {
        let points = inputs.map_or(0, |f| f.sample_point.len());
        match &self.end_samples {
            Some((t, v, lambda)) if *t == self.time() && 3 * lambda.len() == points => Fields {
                sampled_velocity: v.clone(),
                sampled_lambda_min: lambda.clone(),
                ..self.current.clone()
            },
            _ => self.outputs_at(inputs),
        }
    }

    /// At a window's start, before anything of it is stepped or kept: the slabs cut again when
    /// the water has moved ([`RankSlab::rebalance`]; every rank). A failure of the ranks' own
    /// link stops every rank.
    fn rebalance_if_due(&mut self) {
        if !self.me.recount_due() {
            return;
        }
        let set = self.probes.as_mut().map(|p| &mut p.probes);
        if let Err(e) = self.me.rebalance(&mut self.combine, set) {
            eprintln!(
                "error: fluid `{}`: rank {}: {e}; stopping every rank",
                self.name,
                self.rank()
            );
            self.me.link.abort(1)
        }
    }

    /// Advances over the window as [`crate::participant::FluidParticipant`] does (every rank).
    fn advance(&mut self, inputs: &Waveform, progress: &mut dyn ProgressSink) -> Result<Vec<Fields>, String> {
        let now = self.time();
        let start = inputs.start();
        if (start - now).abs() > TIME_MATCH * now.abs().max(1.0) {
            return Err(format!(
                "fluid `{}`: the window starts at t = {start} s but the fluid is at t = {now} s",
                self.name
            ));
        }
        self.commit()?;
        let bodies = self.me.slab.solver.body_names().len();
        let reactions = inputs.samples.iter().any(|s| !s.reaction.is_empty());
        let motion_at_end = std::mem::take(&mut self.iterated);
        if !motion_at_end {
            // an explicit window's start (an implicit one is cut again before it is saved)
            self.rebalance_if_due();
        }
        let mut outputs = vec![self.window_start_outputs(inputs.samples.first())];
        for (j, &t) in inputs.times.iter().enumerate().skip(1) {
            while let Some(dt) = self.me.slab.solver.next_step_towards(t) {
                if bodies > 0 {
                    let (read_at, lead) = match motion_at_end {
                        true => (self.time() + dt, dt),
                        false => (self.time(), 0.0),
                    };
                    let (pose, velocity) = body_motion::at(inputs, read_at)?;
                    if !pose.is_empty() || !velocity.is_empty() {
                        if velocity.iter().any(|&v| v != 0.0) {
                            self.me.whole.set_driven();
                        }
                        self.me.slab.solver.set_body_motion(&pose, &velocity, lead)?;
                    }
                }
                if bodies > 0 || reactions {
                    self.set_point_reactions(&inputs.at(self.time())?)?;
                }
                self.step(dt)?;
                progress.step_done(self.time());
                if let Some(p) = &mut self.probes {
                    let next = p.next_row();
                    p.probes.observe(&self.me.slab.solver, next);
                }
                let s = &self.me.slab.solver;
                if let Some(lines) = &mut self.progress {
                    let steps = s.steps();
                    lines.update(
                        s.time(),
                        steps,
                        steps * self.fluid_at_start,
                        self.fluid_at_start as usize,
                    );
                }
            }
            self.me.slab.solver.land_on(t);
            self.current = self.summed_outputs();
            outputs.push(self.outputs_at(inputs.samples.get(j)));
            if self.probes.as_ref().is_some_and(|p| p.due(t)) {
                self.sample_probes();
            }
            let due = self.frames.as_ref().map_or(f64::INFINITY, |f| {
                f.next() as f64 * self.frame_interval - 1e-9 * self.frame_interval
            });
            if self.pending_frame.is_none() && t >= due {
                self.pending_frame = Some((t, self.me.piece()));
            }
        }
        self.end_samples = outputs
            .last()
            .filter(|o| !o.sampled_lambda_min.is_empty())
            .map(|o| {
                (
                    self.time(),
                    o.sampled_velocity.clone(),
                    o.sampled_lambda_min.clone(),
                )
            });
        Ok(outputs)
    }

    fn save(&mut self) {
        self.rebalance_if_due();
        self.iterated = true;
        self.saved = Some(WindowStart {
            slab: self.me.slab.save(),
            outputs: self.current.clone(),
            energy: self.me.whole.energy_reference(),
        });
        if let Some(p) = &mut self.probes {
            p.save_filters();
        }
    }

    fn restore(&mut self) -> Result<(), String> {
        self.iterated = true;
        self.pending_frame = None;
        if let Some(p) = &mut self.probes {
            p.restore_filters();
        }
        let saved = self.saved.as_ref().ok_or_else(|| {
            format!(
                "fluid `{}`: asked to restore a checkpoint, but none was saved",
                self.name
            )
        })?;
        self.me.slab.restore(&saved.slab);
        self.current = saved.outputs.clone();
        self.me.whole.set_energy_reference(saved.energy);
        Ok(())
    }

    /// Writes what the accepted window kept back, then this rank's state to its file beside
    /// `path` (every rank); returns the bytes the ranks wrote.
    fn write_checkpoint(&mut self, path: &Path, progress: &mut dyn ProgressSink) -> Result<u64, String> {
        self.commit()?;
        let (link, rank) = (self.me.link, self.rank());
        let saved = SavedRank {
            name: self.name.clone(),
            rank,
            ranks: link.size(),
            slab: self.me.slab.save(),
            run: self.me.slab.solver.run_state(),
            whole: self.me.whole.energy_reference(),
            current: (
                self.current.body_force.0.clone(),
                self.current.body_reaction.0.clone(),
            ),
            end_samples: self
                .end_samples
                .as_ref()
                .map(|(t, v, l)| (*t, v.0.clone(), l.0.clone())),
            moved: (self.me.handed_over, self.me.copied),
            cuts: self.me.cuts.clone(),
            recuts: (self.me.recuts, self.me.counted_at),
            frames: self.frames.as_ref().map(|f| (f.next(), f.series().to_vec())),
            probes: self.probes.as_ref().map(ProbeRows::saved),
        };
        let file = rank_file(path, rank);
        let written = schemas::checkpoint::write(&file, &saved, progress).map_err(|e| {
            format!(
                "fluid `{}`: cannot write the checkpoint {}: {e}",
                self.name,
                file.display()
            )
        });
        let bytes = link.agree(written)?;
        Ok(link.sum(bytes))
    }

    /// Takes this rank's state from its checkpoint file `file`.
    fn restore_from(&mut self, file: &Path) -> Result<(), String> {
        let saved: SavedRank = schemas::checkpoint::read(file)?;
        let (rank, ranks) = (self.rank(), self.me.link.size());
        if saved.name != self.name || saved.rank != rank || saved.ranks != ranks {
            return Err(format!(
                "{} is the checkpoint of rank {} of {} of fluid `{}`, not of rank {rank} of {ranks} of `{}`: resume on as many ranks as wrote it",
                file.display(),
                saved.rank,
                saved.ranks,
                saved.name,
                self.name
            ));
        }
        self.me.slab.restore(&saved.slab);
        self.me.slab.solver.restore_run_state(saved.run);
        self.me.whole.set_energy_reference(saved.whole);
        self.current = Fields {
            body_force: F64s(saved.current.0),
            body_reaction: F64s(saved.current.1),
            ..Fields::default()
        };
        (self.me.handed_over, self.me.copied) = saved.moved;
        self.end_samples = saved.end_samples.map(|(t, v, l)| (t, F64s(v), F64s(l)));
        (self.me.recuts, self.me.counted_at) = saved.recuts;
        // the probes over the slabs as they were cut then
        let (combine, mut sets) = SlabProbes::new(&self.me.recut.probes, &saved.cuts);
        self.combine = combine;
        if let Some(probes) = &mut self.probes {
            probes.probes = sets.swap_remove(rank);
        }
        self.me.cuts = saved.cuts;
        if let (Some(frames), Some((next, series))) = (&mut self.frames, saved.frames) {
            frames.continue_after(self.me.link, next, series)?;
        }
        if let (Some(probes), Some(saved)) = (&mut self.probes, saved.probes) {
            probes.continue_from(saved);
        }
        if rank == 0 {
            eprintln!(
                "fluid `{}`: resumed on {ranks} ranks from {} at t = {} s (step {})",
                self.name,
                file.display(),
                self.time(),
                self.me.slab.solver.steps()
            );
        }
        Ok(())
    }

    /// The run's summary (every rank), written to the log by rank 0.
    fn finish(&mut self) -> Result<(), String> {
        self.commit()?;
        if let Some(lines) = &mut self.progress {
            lines.finish();
        }
        let link = self.me.link;
        let [own_step_seconds, exchange_seconds] = self.me.time_split(self.step_seconds);
        let summary = RankRunSummary {
            ranks: link.size(),
            time: self.time(),
            steps: self.me.slab.solver.steps(),
            fluid_particles: link.sum(self.me.slab.owned_count()),
            frames: self.frames.as_ref().map_or(0, |f| f.next() as usize),
            handed_over: link.sum(self.me.handed_over),
            copied: link.sum(self.me.copied),
            sent_bytes: link.sum(link.sent_bytes()),
            recuts: self.me.recuts,
            wall_seconds: self.started.elapsed().as_secs_f64(),
            step_seconds: self.step_seconds,
            own_step_seconds,
            exchange_seconds,
        };
        if self.rank() == 0 {
            eprintln!("fluid `{}`: done: {summary}", self.name);
        }
        Ok(())
    }
}

/// Rank 0 of a fluid participant on ranks, as the coupler sees it: each request is sent on to
/// the other ranks as an [`Order`], then done here.
pub struct Leader<'a> {
    ranks: RankParticipant<'a>,
    /// `Finish` was sent on: the other ranks have stopped waiting for orders.
    finished: bool,
}

impl<'a> Leader<'a> {
    pub fn new(ranks: RankParticipant<'a>) -> Leader<'a> {
        Leader {
            ranks,
            finished: false,
        }
    }

    fn order(&self, order: &Order) {
        // an order holds plain values: encoding it cannot fail
        let bytes = bincode::encode_to_vec(order, bincode::config::standard()).unwrap_or_default();
        self.ranks.me.link.send_order(&bytes);
    }

    /// Tells the other ranks to stop waiting, when the run ended before `Finish`.
    pub fn stop_the_others(&self) {
        if !self.finished {
            self.order(&Order::Stop);
        }
    }
}

impl Participant for Leader<'_> {
    fn role(&self) -> Role {
        Role::Fluid
    }

    fn time(&self) -> f64 {
        self.ranks.time()
    }

    fn interface(&self) -> InterfaceDecl {
        InterfaceDecl {
            bodies: self.ranks.me.slab.solver.body_names().to_vec(),
            ..InterfaceDecl::default()
        }
    }

    fn initial_outputs(&mut self) -> Fields {
        self.ranks.current.clone()
    }

    fn save_checkpoint(&mut self) {
        self.order(&Order::Save);
        self.ranks.save();
    }

    fn restore_checkpoint(&mut self) -> Result<(), String> {
        self.order(&Order::Restore);
        self.ranks.restore()
    }

    fn advance(&mut self, inputs: &Waveform) -> Result<Vec<Fields>, String> {
        self.advance_reporting(inputs, &mut DiscardProgress)
    }

    fn advance_reporting(
        &mut self,
        inputs: &Waveform,
        progress: &mut dyn ProgressSink,
    ) -> Result<Vec<Fields>, String> {
        self.order(&Order::Advance(inputs.clone()));
        self.ranks.advance(inputs, progress)
    }

    fn write_checkpoint(&mut self, path: &Path, progress: &mut dyn ProgressSink) -> Result<u64, String> {
        self.order(&Order::WriteCheckpoint(path.display().to_string()));
        self.ranks.write_checkpoint(path, progress)
    }

    fn finish(&mut self, _progress: &mut dyn ProgressSink) -> Result<(), String> {
        self.order(&Order::Finish);
        self.finished = true;
        self.ranks.finish()
    }
}

/// A rank other than 0: does what rank 0 orders until `Finish` or `Stop`, or until a signal
/// comes while it waits. Failures of a request are rank 0's to report: they reached it
/// ([`RankLink::agree`]); this rank waits for the next order.
pub fn follow(mut ranks: RankParticipant<'_>) -> Result<(), String> {
    let link = ranks.me.link;
    loop {
        let Some(bytes) = link.next_order(schemas::signals::interrupted) else {
            return Err(format!(
                "rank {}: stopped by {} while waiting for rank 0",
                link.rank(),
                schemas::signals::received().unwrap_or("a signal")
            ));
        };
        let (order, _): (Order, usize) = bincode::decode_from_slice(&bytes, bincode::config::standard())
            .map_err(|e| format!("rank {}: rank 0's order is damaged: {e}", link.rank()))?;
        let _ = match order {
            Order::Save => {
                ranks.save();
                Ok(())
            }
            Order::Restore => ranks.restore(),
            Order::Advance(inputs) => ranks.advance(&inputs, &mut DiscardProgress).map(|_| ()),
            Order::WriteCheckpoint(path) => ranks
                .write_checkpoint(Path::new(&path), &mut DiscardProgress)
                .map(|_| ()),
            Order::Finish => return ranks.finish(),
            Order::Stop => return Ok(()),
        };
    }
}
