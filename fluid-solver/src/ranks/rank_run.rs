//! A standalone run of a fluid-only case on MPI ranks (`mpirun -np N fluid-solver run CASE`,
//! cargo feature `mpi`): rank r steps slab r of the fluid ([`super::slabs`], cuts balanced by
//! fluid particles) and trades particles with its neighbours after each step
//! ([`super::mpi_link`]); the whole fluid's energy check is summed over the ranks. Every
//! `output_interval` each rank writes its piece of the frame, `NAME_FFFFF_rRRRR.vtu` (the fluid
//! it owns and the walls between its cuts, so every particle is in one piece), and rank 0 the
//! frame's index `NAME_FFFFF.pvtu` and the PVD series over the indexes, which ParaView opens as
//! one data set. The first frame is the layout after the gates are lifted. Every
//! `probe_interval` each rank reads the probes it owns ([`super::slab_probes`]) and rank 0 writes
//! the whole fluid's row to `NAME_probes.csv`, as a run in one process does.

use super::mpi_link::RankLink;
use super::rank_frames::RankFrames;
use super::rank_slab::RankSlab;
use super::slab_plan::{PlanError, SlabPlan};
use super::slab_probes::SlabProbes;
use crate::boundaries::open_boundary::BalanceFile;
use crate::output::progress::Progress;
use crate::run::{fluid_only, RunError};
use crate::sensors::probes::{ProbeFile, ProbeSet};
use crate::sensors::view::ParticleView;
use crate::solver::FluidSolver;
use schemas::case::Case;
use std::path::Path;
use std::time::Instant;

/// What a run on ranks did (the same on every rank).
#[derive(Debug, Clone)]
pub struct RankRunSummary {
    pub ranks: usize,
    pub time: f64,
    pub steps: u64,
    /// Fluid particles over all ranks at the end.
    pub fluid_particles: u64,
    pub frames: usize,
    /// Fluid particles handed from one rank to another, and halo copies sent, over the run.
    pub handed_over: u64,
    pub copied: u64,
    /// Bytes the ranks sent each other in the steps' exchanges (encoded particles).
    pub sent_bytes: u64,
    /// How many times the slabs were cut again as the water moved.
    pub recuts: u64,
    pub wall_seconds: f64,
    /// Wall time of the steps with their exchanges and checks (rank 0's; frames, probes and
    /// the set-up left out).
    pub step_seconds: f64,
    /// The least and the most a rank spent in its own steps, and in its exchanges, the halo's
    /// sort, reductions and waits ([`super::rank_slab::RankSlab::time_split`]).
    pub own_step_seconds: [f64; 2],
    pub exchange_seconds: [f64; 2],
}

impl std::fmt::Display for RankRunSummary {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "t = {:.4} s in {} steps on {} ranks, {} fluid particles, {} frames, {} particles handed over, {} halo copies, {} bytes sent between ranks, slabs cut again {} times, {:.1} s ({:.3} s in the steps; a rank's own steps {:.3}–{:.3} s, its exchanges and waits {:.3}–{:.3} s)",
            self.time,
            self.steps,
            self.ranks,
            self.fluid_particles,
            self.frames,
            self.handed_over,
            self.copied,
            self.sent_bytes,
            self.recuts,
            self.wall_seconds,
            self.step_seconds,
            self.own_step_seconds[0],
            self.own_step_seconds[1],
            self.exchange_seconds[0],
            self.exchange_seconds[1]
        )
    }
}

/// Why a run on ranks stopped early.
#[derive(Debug)]
pub enum RankRunError {
    /// The case cannot run on ranks: every rank finds the same (rank 0 reports it).
    Setup(RunError),
    /// This rank's own error, which the others may not know of.
    Here(RunError),
    /// Another rank's error, which that rank reports.
    Elsewhere { rank: usize },
}

impl std::fmt::Display for RankRunError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            RankRunError::Setup(e) | RankRunError::Here(e) => write!(f, "{e}"),
            RankRunError::Elsewhere { rank } => {
                write!(f, "rank {rank} stopped the run (its message says why)")
            }
        }
    }
}

/// Runs the fluid-only `case` to its end on the ranks of `link`, writing into `out` (every rank
/// sees the same folder). Progress lines come from rank 0.
pub fn run_on_ranks(case: &Case, out: &Path, link: &RankLink) -> Result<RankRunSummary, RankRunError> {
    let started = Instant::now();
    let here = RankRunError::Here;
    let (name, cfg) = fluid_only(case).map_err(RankRunError::Setup)?;
    let refuse = |what: &str| {
        RankRunError::Setup(RunError::NotFluidOnly {
            file: case.path.clone(),
            message: format!("a run on MPI ranks supports E-MPS on CPU threads with walls, blocks, gates, solids, damping zones, inflow and outflow; not yet {what}"),
        })
    };
    if let Some(what) = cfg.unsupported_on_ranks() {
        return Err(refuse(what));
    }
    if !cfg.body.is_empty() {
        // the slabs of one process carry bodies; on ranks they wait for the coupler's `ranks`
        return Err(refuse("[[fluid.NAME.body]]"));
    }
    let io_err = |path: &Path| {
        let path = path.to_path_buf();
        move |error| here(RunError::Output { path, error })
    };
    std::fs::create_dir_all(out).map_err(io_err(out))?;
    let (rank, ranks) = (link.rank(), link.size());
    let mut solver = FluidSolver::new(cfg);
    let plan = SlabPlan::new(&mut solver, &cfg.probe, ranks).map_err(|e| {
        let file = case.path.clone();
        RankRunError::Setup(match e {
            PlanError::Probe(message) => RunError::Probe { file, message },
            PlanError::Slabs(message) => RunError::NotFluidOnly { file, message },
        })
    })?;
    let open = solver.open_boundaries().is_active();
    let SlabPlan {
        everything,
        cuts,
        probes: mut slab_probes,
        mut probe_sets,
        whole,
        fluid_at_start,
        recut,
    } = plan;
    let mut probes = probe_sets.swap_remove(rank);
    let mut me = RankSlab::new(solver, &everything, link, whole, cuts, recut);
    drop(everything);

    let mut frames = RankFrames::new(out, name);
    // a frame that cannot be written stops every rank: each learns it from the frame's write
    let mut write_frame = |me: &RankSlab| {
        frames
            .write(link, me.slab.solver.time(), &me.piece())
            .map_err(|message| match rank {
                0 => here(RunError::Ranks { message }),
                _ => RankRunError::Elsewhere { rank: 0 },
            })
    };
    // the probe CSV: each rank reads its own probes, rank 0 writes the whole fluid's row
    let probe_path = out.join(format!("{name}_probes.csv"));
    let mut probe_file = match rank {
        0 => Some(ProbeFile::create(&probe_path, &probes.names()).map_err(io_err(&probe_path))?),
        _ => None,
    };
    // with an inflow or an outflow, the balance CSV from rank 0 too
    let balance_path = out.join(format!("{name}_balance.csv"));
    let mut balance_file = match rank == 0 && open {
        true => Some(BalanceFile::create(&balance_path).map_err(io_err(&balance_path))?),
        false => None,
    };
    let mass = me.slab.solver.particle_mass();
    let mut sample =
        |me: &RankSlab, probes: &mut ProbeSet, slab_probes: &SlabProbes| -> Result<(), RankRunError> {
            let t = me.slab.solver.time();
            let rows = link.all_rows(&probes.row_in(&ParticleView::of(&me.slab.solver)));
            let (balance, counts) = me.balance();
            if let Some(file) = &mut balance_file {
                file.row_of_counts(t, balance, counts, mass)
                    .map_err(io_err(&balance_path))?;
            }
            // what was there and entered, less what the ranks own: the open top's and the outflow's
            let removed = fluid_at_start + balance.entered - counts[1];
            match &mut probe_file {
                Some(file) => file
                    .row(t, &slab_probes.combine(&rows), removed)
                    .map_err(io_err(&probe_path)),
                None => Ok(()),
            }
        };
    let probe_interval = cfg.probe_interval.unwrap_or(cfg.output_interval);
    let end = case.info.end_time;
    let mut progress = (rank == 0).then(|| Progress::new(name, end, cfg.progress_interval, false));
    write_frame(&me)?;
    sample(&me, &mut probes, &slab_probes)?;
    let (mut next_frame, mut next_probe) = (1u64, 1u64);
    let at = |k: u64, interval: f64| (k as f64 * interval).min(end);
    let mut step_seconds = 0.0;
    while me.slab.solver.time() < end {
        let row_at = at(next_probe, probe_interval);
        let target = at(next_frame, cfg.output_interval).min(row_at);
        while let Some(dt) = me.slab.solver.next_step_towards(target) {
            let stepping = Instant::now();
            me.step(dt).inspect_err(|_| {
                if let Some(p) = &mut progress {
                    p.finish();
                }
            })?;
            if me.recount_due() {
                me.rebalance(&mut slab_probes, Some(&mut probes))?;
            }
            step_seconds += stepping.elapsed().as_secs_f64();
            probes.observe(&me.slab.solver, row_at);
            if let Some(p) = &mut progress {
                let steps = me.slab.solver.steps();
                p.update(
                    me.slab.solver.time(),
                    steps,
                    steps * fluid_at_start,
                    fluid_at_start as usize,
                );
            }
        }
        me.slab.solver.land_on(target);
        if me.slab.solver.time() >= row_at {
            sample(&me, &mut probes, &slab_probes)?;
            next_probe += 1;
        }
        if me.slab.solver.time() >= at(next_frame, cfg.output_interval) {
            write_frame(&me)?;
            next_frame += 1;
        }
    }
    if let Some(p) = &mut progress {
        p.finish();
    }
    let owned = me.slab.owned_count();
    let [own_step_seconds, exchange_seconds] = me.time_split(step_seconds);
    Ok(RankRunSummary {
        ranks,
        time: me.slab.solver.time(),
        steps: me.slab.solver.steps(),
        fluid_particles: link.sum(owned),
        frames: frames.next() as usize,
        handed_over: link.sum(me.handed_over),
        copied: link.sum(me.copied),
        sent_bytes: link.sum(link.sent_bytes()),
        recuts: me.recuts,
        wall_seconds: started.elapsed().as_secs_f64(),
        step_seconds,
        own_step_seconds,
        exchange_seconds,
    })
}
