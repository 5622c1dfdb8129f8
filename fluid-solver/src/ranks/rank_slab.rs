//! One MPI rank's slab of the fluid ([`super::subdomain::Subdomain`]) and its link: a step with
//! the exchanges that follow it and the whole fluid's energy check, the rank's piece of a frame,
//! and the open boundaries' balance summed over the ranks, as a standalone run on ranks
//! ([`super::rank_run`]) steps.

use super::decomposed::check_whole_energy;
use super::mpi_link::RankLink;
use super::rank_run::RankRunError;
use super::rebalance;
use super::rebalance::Recut;
use super::slab_probes::SlabProbes;
use super::subdomain::{Subdomain, ToNeighbours};
use crate::boundaries::open_boundary::ParticleBalance;
use crate::particles::kind::FLUID;
use crate::run::RunError;
use crate::sensors::probes::ProbeSet;
use crate::stability::StabilityMonitor;

/// Message tags of a step's two exchanges.
const HAND_OVER: i32 = 1;
const HALO: i32 = 2;

/// This rank's slab, its link and the whole fluid's energy reference.
pub(super) struct RankSlab<'a> {
    pub(super) slab: Subdomain,
    pub(super) link: &'a RankLink,
    pub(super) whole: StabilityMonitor,
    pub(super) handed_over: u64,
    pub(super) copied: u64,
    /// Where the slabs are cut now, and what cutting them again needs.
    pub(super) cuts: Vec<f64>,
    pub(super) recut: Recut,
    /// How many times the slabs were cut again, and the step of the last count.
    pub(super) recuts: u64,
    pub(super) counted_at: u64,
    /// Wall seconds of this rank's own steps (its solver's, without the exchanges, reductions
    /// and waits that follow them).
    pub(super) own_step_seconds: f64,
}

fn link_error(message: String) -> RankRunError {
    RankRunError::Here(RunError::Ranks { message })
}

impl<'a> RankSlab<'a> {
    /// Rank `link.rank()`'s slab of `everything` (the whole layout, gates lifted) cut at `cuts`,
    /// stepped by `solver`, with the whole fluid's monitor `whole` and what cutting again needs.
    pub(super) fn new(
        solver: crate::solver::FluidSolver,
        everything: &crate::particles::Particles,
        link: &'a RankLink,
        whole: StabilityMonitor,
        cuts: Vec<f64>,
        recut: Recut,
    ) -> RankSlab<'a> {
        let r = link.rank();
        RankSlab {
            slab: Subdomain::of(solver, everything, cuts[r], cuts[r + 1], recut.halo),
            link,
            whole,
            handed_over: 0,
            copied: 0,
            cuts,
            recut,
            recuts: 0,
            counted_at: 0,
            own_step_seconds: 0.0,
        }
    }

    /// One step of `dt`, the exchanges, and the whole fluid's energy check. Every rank leaves
    /// together: when one rank's step fails, the others learn it from the same reduction.
    pub(super) fn step(&mut self, dt: f64) -> Result<(), RankRunError> {
        let started = std::time::Instant::now();
        let stepped = self.slab.solver.step(dt).map(|_| ());
        self.own_step_seconds += started.elapsed().as_secs_f64();
        let failed_rank = self
            .link
            .max(stepped.as_ref().err().map_or(-1.0, |_| self.link.rank() as f64));
        if let Err(e) = stepped {
            return Err(RankRunError::Here(RunError::Unstable(e)));
        }
        if failed_rank >= 0.0 {
            return Err(RankRunError::Elsewhere {
                rank: failed_rank as usize,
            });
        }
        self.hand_over()?;
        self.send_halos()?;
        self.check_energy(dt)
    }

    /// Hands the owned fluid that left this slab to its neighbours and takes theirs; returns how
    /// many particles this rank sent.
    fn hand_over(&mut self) -> Result<u64, RankRunError> {
        let leaving = self.slab.emigrants();
        let went = count(&leaving);
        self.handed_over += went;
        let arriving = self.link.exchange(&leaving, HAND_OVER).map_err(link_error)?;
        self.slab.take(&arriving);
        Ok(went)
    }

    /// Sends copies of this slab's fluid near its faces to its neighbours, takes theirs, and
    /// sorts the particles for the next step.
    fn send_halos(&mut self) -> Result<(), RankRunError> {
        let copies = self.slab.halo_copies();
        self.copied += count(&copies);
        let halo = self.link.exchange(&copies, HALO).map_err(link_error)?;
        self.slab.take_halo(&halo);
        Ok(())
    }

    /// Over the ranks (every rank calls it): the least and the most time a rank spent in its own
    /// steps, and in the rest of `step_seconds` (this rank's steps with their exchanges, the
    /// halo's sort, reductions and waits).
    pub(super) fn time_split(&self, step_seconds: f64) -> [[f64; 2]; 2] {
        let rows = self
            .link
            .all_rows(&[self.own_step_seconds, step_seconds - self.own_step_seconds]);
        [0, 1].map(|k| {
            let column = rows.iter().map(|r| r[k]);
            [
                schemas::validation::smallest(column.clone(), f64::INFINITY),
                schemas::validation::largest(column, 0.0),
            ]
        })
    }

    /// Whether [`rebalance::CHECK_EVERY`] steps have passed since the slabs' fluid was last
    /// counted.
    pub(super) fn recount_due(&self) -> bool {
        self.slab.solver.steps() >= self.counted_at + rebalance::CHECK_EVERY
    }

    /// Counts the fluid over the ranks and, when the fullest slab holds more than
    /// [`rebalance::LIMIT`] times the mean and new cuts fit, cuts the slabs again: each rank
    /// takes its new reach's walls, hands over fluid until every rank owns what lies between its
    /// cuts, and sends its halo; `rules` and this rank's probe `set` follow the new cuts (with the
    /// filters' readings of the rank that read each probe). Every rank calls it; returns whether
    /// the slabs were cut again.
    pub(super) fn rebalance(
        &mut self,
        rules: &mut SlabProbes,
        set: Option<&mut ProbeSet>,
    ) -> Result<bool, RankRunError> {
        self.counted_at = self.slab.solver.steps();
        let (link, rank) = (self.link, self.link.rank());
        let bins = &self.recut.bins;
        let counts = link.sum_each(&bins.histogram(self.slab.solver.particles(), |i| self.slab.owned(i)));
        let Some(cuts) = self.recut.new_cuts(&counts, &self.cuts) else {
            return Ok(false);
        };
        self.slab.recut(cuts[rank], cuts[rank + 1], &self.recut.fixed);
        // a cut may have moved past a whole slab: hand over until every rank owns its own
        while link.sum(self.hand_over()?) > 0 {}
        self.send_halos()?;
        if let Some(set) = set {
            let config = bincode::config::standard();
            let mine = bincode::serde::encode_to_vec(set.windows(), config)
                .map_err(|e| link_error(format!("rank {rank}: cannot encode the probes' readings: {e}")))?;
            let windows = link
                .all_bytes(&mine)
                .iter()
                .map(|bytes| bincode::serde::decode_from_slice(bytes, config).map(|(w, _)| w))
                .collect::<Result<Vec<rebalance::Windows>, _>>()
                .map_err(|e| {
                    link_error(format!(
                        "rank {rank}: the probes' readings from a rank are damaged: {e}"
                    ))
                })?;
            let (new_rules, mut sets) = self.recut.probes_after(rules, &windows, &cuts);
            (*rules, *set) = (new_rules, sets.swap_remove(rank));
        } else {
            *rules = SlabProbes::new(&self.recut.probes, &cuts).0;
        }
        self.cuts = cuts;
        self.recuts += 1;
        Ok(true)
    }

    /// The whole fluid's energy check, summed over the ranks' own fluid; every rank finds the
    /// same, rank 0 reports it.
    fn check_energy(&self, dt: f64) -> Result<(), RankRunError> {
        let (slab, link) = (&self.slab, self.link);
        let energy = || link.sum(slab.owned_energy(&self.whole));
        check_whole_energy(&self.whole, energy, &slab.solver, link.size(), "ranks", dt).map_err(
            |e| match link.rank() {
                0 => RankRunError::Here(RunError::Unstable(e)),
                _ => RankRunError::Elsewhere { rank: 0 },
            },
        )
    }

    /// This rank's piece of a frame: the fluid it owns and the walls between its cuts.
    pub(super) fn piece(&self) -> crate::particles::Particles {
        let n = self.slab.solver.particles().len() as u32;
        let mine: Vec<u32> = (0..n).filter(|&i| self.in_piece(i as usize)).collect();
        self.slab.solver.particles().subset(&mine)
    }

    /// Whether local particle `i` is in [`RankSlab::piece`]: the owned fluid, and the others
    /// between the cuts (walls, the inflow strip of the first slab).
    fn in_piece(&self, i: usize) -> bool {
        let p = self.slab.solver.particles();
        match p.kind[i] {
            FLUID => self.slab.owned(i),
            _ => self.slab.lo <= p.x[i] && p.x[i] < self.slab.hi,
        }
    }

    /// The whole fluid's open-boundary balance and its particle counts `[inflow strip, fluid,
    /// all]`, summed over the ranks (each runs only the boundaries in its slab).
    pub(super) fn balance(&self) -> (ParticleBalance, [u64; 3]) {
        let link = self.link;
        let b = self.slab.solver.open_boundaries().balance();
        let balance = ParticleBalance {
            inserted: link.sum(b.inserted),
            entered: link.sum(b.entered),
            removed: link.sum(b.removed),
            withdrawn: link.sum(b.withdrawn),
        };
        let strip = self.slab.solver.particles().count(crate::Kind::Inflow) as u64;
        let counts = [
            link.sum(strip),
            link.sum(self.slab.owned_count()),
            link.sum(
                (0..self.slab.solver.particles().len())
                    .filter(|&i| self.in_piece(i))
                    .count() as u64,
            ),
        ];
        (balance, counts)
    }
}

pub(super) fn count(sent: &ToNeighbours) -> u64 {
    sent.iter().map(|p| p.len() as u64).sum()
}
