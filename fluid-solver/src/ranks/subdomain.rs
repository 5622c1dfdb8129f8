//! One slab of the fluid: a solver stepping the fluid particles the slab owns (lo ≤ x < hi), a
//! halo of copies of its neighbours' fluid within the halo's width of its faces, and the walls
//! over both (walls do not move: each slab keeps those it needs from the start).

use crate::particles::kind::FLUID;
use crate::particles::Particles;
use crate::solver::FluidSolver;
use crate::stability::StabilityMonitor;

/// What a slab sends to its left (lower x) and right neighbours.
pub type ToNeighbours = [Particles; 2];

/// One slab's solver and what it owns.
pub struct Subdomain {
    pub solver: FluidSolver,
    /// The slab owns the fluid at `lo ≤ x < hi`.
    pub lo: f64,
    pub hi: f64,
    /// Halo thickness ([`super::slabs::halo_width`]).
    halo: f64,
    /// Whether the slab owns the fluid particle of each id (indexed by id).
    owns: Vec<bool>,
}

impl Subdomain {
    /// The slab `lo ≤ x < hi` of `whole` (the whole domain's particles, gates removed), stepped
    /// by `solver` (built for the same case): its fluid, the fluid of the halo `halo` thick
    /// around it, and the walls over both. The solver's energy check is off: it holds only
    /// part of the fluid (the whole domain's check is [`super::decomposed`]'s).
    pub fn of(mut solver: FluidSolver, whole: &Particles, lo: f64, hi: f64, halo: f64) -> Subdomain {
        let ids = whole.id.iter().map(|&i| i as usize + 1).max().unwrap_or(0);
        let mut owns = vec![false; ids];
        let near: Vec<u32> = (0..whole.len() as u32)
            .filter(|&i| {
                let x = whole.x[i as usize];
                lo - halo <= x && x < hi + halo
            })
            .collect();
        for &i in &near {
            let i = i as usize;
            owns[whole.id[i] as usize] = whole.kind[i] == FLUID && lo <= whole.x[i] && whole.x[i] < hi;
        }
        solver.monitor.set_driven();
        let mut slab = Subdomain {
            solver,
            lo,
            hi,
            halo,
            owns,
        };
        slab.solver.state.particles = whole.subset(&near);
        slab.settle();
        slab
    }

    /// Whether local particle `i` is fluid this slab owns.
    pub fn owned(&self, i: usize) -> bool {
        let p = self.solver.particles();
        p.kind[i] == FLUID && self.owns[p.id[i] as usize]
    }

    /// The mechanical energy of the fluid this slab owns, by `whole`'s measure.
    pub fn owned_energy(&self, whole: &StabilityMonitor) -> f64 {
        whole.mechanical_energy_where(self.solver.particles(), |i| self.owned(i))
    }

    /// The fluid this slab owns.
    pub fn owned_fluid(&self) -> Particles {
        let n = self.solver.particles().len() as u32;
        let mine: Vec<u32> = (0..n).filter(|&i| self.owned(i as usize)).collect();
        self.solver.particles().subset(&mine)
    }

    /// After a step: drops the halo's copies and hands over the owned fluid that left the slab
    /// (to the left neighbour below `lo`, to the right one from `hi` on).
    pub fn emigrants(&mut self) -> ToNeighbours {
        let p = self.solver.particles();
        let (mut keep, mut left, mut right) = (Vec::new(), Vec::new(), Vec::new());
        for i in 0..p.len() {
            if p.kind[i] != FLUID {
                keep.push(i as u32);
            } else if self.owns[p.id[i] as usize] {
                match p.x[i] {
                    x if x < self.lo => left.push(i as u32),
                    x if x >= self.hi => right.push(i as u32),
                    _ => keep.push(i as u32),
                }
            }
        }
        let out = [p.subset(&left), p.subset(&right)];
        for q in &out {
            for &id in &q.id {
                self.owns[id as usize] = false;
            }
        }
        self.solver.state.particles = p.subset(&keep);
        out
    }

    /// Takes over fluid its neighbours handed over ([`Subdomain::emigrants`]).
    pub fn take(&mut self, arrivals: &ToNeighbours) {
        for q in arrivals {
            for &id in &q.id {
                self.owns[id as usize] = true;
            }
            self.solver.state.particles.append(q);
        }
    }

    /// Copies of the owned fluid within the halo's width of each face, for the neighbour there.
    pub fn halo_copies(&self) -> ToNeighbours {
        let p = self.solver.particles();
        let n = p.len() as u32;
        let near = |edge: f64| {
            let list: Vec<u32> = (0..n)
                .filter(|&i| self.owned(i as usize) && (p.x[i as usize] - edge).abs() < self.halo)
                .collect();
            p.subset(&list)
        };
        [near(self.lo), near(self.hi)]
    }

    /// Takes the neighbours' halo copies ([`Subdomain::halo_copies`]) and sorts the particles
    /// into the solver's cell list: the slab is ready for its next step.
    pub fn take_halo(&mut self, copies: &ToNeighbours) {
        for q in copies {
            self.solver.state.particles.append(q);
        }
        self.settle();
    }

    /// Sorts the particles into the solver's cell list after they were replaced.
    fn settle(&mut self) {
        let st = &mut self.solver.state;
        st.grid.sort(&mut st.particles, &mut Vec::new());
        self.solver.moved();
    }
}
