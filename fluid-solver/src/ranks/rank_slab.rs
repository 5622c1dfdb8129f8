//! One MPI rank's slab of the fluid ([`super::subdomain::Subdomain`]) and its link: a step with
//! the exchanges that follow it and the whole fluid's energy check, the rank's piece of a frame,
//! and the open boundaries' balance summed over the ranks, as a standalone run on ranks
//! ([`super::rank_run`]) steps.

use super::decomposed::check_whole_energy;
use super::mpi_link::RankLink;
use super::rank_run::RankRunError;
use super::subdomain::{Subdomain, ToNeighbours};
use crate::boundaries::open_boundary::ParticleBalance;
use crate::particles::kind::FLUID;
use crate::run::RunError;
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
}

impl RankSlab<'_> {
    /// One step of `dt`, the exchanges, and the whole fluid's energy check. Every rank leaves
    /// together: when one rank's step fails, the others learn it from the same reduction.
    pub(super) fn step(&mut self, dt: f64) -> Result<(), RankRunError> {
        let stepped = self.slab.solver.step(dt).map(|_| ());
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
        let link_error = |message: String| RankRunError::Here(RunError::Ranks { message });
        let leaving = self.slab.emigrants();
        self.handed_over += count(&leaving);
        let arriving = self.link.exchange(&leaving, HAND_OVER).map_err(link_error)?;
        self.slab.take(&arriving);
        let copies = self.slab.halo_copies();
        self.copied += count(&copies);
        let halo = self.link.exchange(&copies, HALO).map_err(link_error)?;
        self.slab.take_halo(&halo);
        self.check_energy(dt)
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
