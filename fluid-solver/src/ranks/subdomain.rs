//! One slab of the fluid: a solver stepping the fluid particles the slab owns (lo ≤ x < hi), a
//! halo of copies of its neighbours' fluid within the halo's width of its faces, and the walls
//! over both (walls do not move: each slab keeps those it needs from the start), and every body
//! particle (a slab reports the loads from the fluid it owns: [`LoadShare`]). The first slab
//! runs the inflow and the last the outflow, each farther than a halo from the slab's cut
//! ([`super::slabs::open_boundaries_fit`]): no other slab holds a strip particle or fluid behind
//! the outflow plane, so the first slab's entries and the last slab's removals are the fluid's.

use crate::bodies::rigid_bodies::LoadShare;
use crate::particles::kind::{Kind, FLUID};
use crate::particles::Particles;
use crate::solver::FluidSolver;
use crate::stability::StabilityMonitor;
use crate::state::FluidState;

/// What a slab sends to its left (lower x) and right neighbours.
pub type ToNeighbours = [Particles; 2];

/// A slab's state, as a checkpoint keeps it: its solver's, which fluid it owns and where its
/// cuts lie.
#[derive(Debug, Clone, serde::Serialize, serde::Deserialize)]
pub struct SlabState {
    pub solver: FluidState,
    pub owns: Vec<bool>,
    pub lo: f64,
    pub hi: f64,
}

/// One slab's solver and what it owns.
pub struct Subdomain {
    pub solver: FluidSolver,
    /// The slab owns the fluid at `lo ≤ x < hi`.
    pub lo: f64,
    pub hi: f64,
    /// Halo thickness ([`super::slabs::halo_width`]).
    halo: f64,
    /// Whether the slab owns the fluid particle of each id (indexed by id; an id past its end,
    /// fluid that entered through the inflow since, was never this slab's).
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
        // every body particle: a body moves, and each slab places all of it by the pose
        let body = Kind::Body.code();
        let near: Vec<u32> = (0..whole.len() as u32)
            .filter(|&i| {
                let x = whole.x[i as usize];
                (lo - halo <= x && x < hi + halo) || whole.kind[i as usize] == body
            })
            .collect();
        let (first, last) = (lo == f64::NEG_INFINITY, hi == f64::INFINITY);
        for &i in &near {
            let i = i as usize;
            let (kind, x) = (whole.kind[i], whole.x[i]);
            // the inflow strip's particles are the first slab's fluid once they cross the plane
            owns[whole.id[i] as usize] =
                (kind == FLUID && lo <= x && x < hi) || (kind == Kind::Inflow.code() && first);
        }
        solver.monitor.set_driven();
        solver.state.open_boundaries.keep_only(first, last);
        if !solver.bodies.names().is_empty() {
            // the slab reports the bodies' loads from the fluid it owns ([`Subdomain::settle`])
            solver.bodies.set_share(Some(LoadShare {
                owned: Vec::new(),
                lo,
                hi,
            }));
        }
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

    /// The slab's state now ([`Subdomain::restore`] goes back to it).
    pub fn save(&self) -> SlabState {
        SlabState {
            solver: self.solver.save_state(),
            owns: self.owns.clone(),
            lo: self.lo,
            hi: self.hi,
        }
    }

    /// Goes back to the state `saved` (of this slab).
    pub fn restore(&mut self, saved: &SlabState) {
        self.solver.restore_state(&saved.solver);
        self.owns.clone_from(&saved.owns);
        (self.lo, self.hi) = (saved.lo, saved.hi);
        if let Some(share) = self.solver.bodies.share_mut() {
            share.owned.clone_from(&self.owns);
            (share.lo, share.hi) = (saved.lo, saved.hi);
        }
    }

    /// Moves the slab's cuts to `lo ≤ x < hi` ([`super::rebalance`]): it keeps its own fluid,
    /// its bodies and inflow strip and the walls it holds within a halo of its new faces (with
    /// the pressures of their last step), takes the walls of `fixed` (the whole domain's, as
    /// built) that its new reach adds, and drops its halo copies. A wall it takes lies more than
    /// the halo less the cut's move from the fluid it owns, beyond what the next step reads
    /// before computing it again. The fluid it owns outside its new cuts leaves at the next
    /// [`Subdomain::emigrants`]; its halo comes with the next [`Subdomain::take_halo`].
    pub fn recut(&mut self, lo: f64, hi: f64, fixed: &Particles) {
        (self.lo, self.hi) = (lo, hi);
        if let Some(share) = self.solver.bodies.share_mut() {
            (share.lo, share.hi) = (lo, hi);
        }
        let (body, inflow) = (Kind::Body.code(), Kind::Inflow.code());
        let reach = |x: f64| lo - self.halo <= x && x < hi + self.halo;
        let p = self.solver.particles();
        let keep: Vec<u32> = (0..p.len() as u32)
            .filter(|&i| {
                let (kind, id, x) = (p.kind[i as usize], p.id[i as usize], p.x[i as usize]);
                match kind {
                    FLUID => self.owns_id(id),
                    k if k == body || k == inflow => true,
                    _ => reach(x),
                }
            })
            .collect();
        let mut kept = p.subset(&keep);
        let mut held = vec![false; fixed.id.iter().map(|&i| i as usize + 1).max().unwrap_or(0)];
        for &id in &kept.id {
            if let Some(h) = held.get_mut(id as usize) {
                *h = true;
            }
        }
        let added: Vec<u32> = (0..fixed.len() as u32)
            .filter(|&i| reach(fixed.x[i as usize]) && !held[fixed.id[i as usize] as usize])
            .collect();
        kept.append(&fixed.subset(&added));
        self.solver.state.particles = kept;
    }

    /// Whether local particle `i` is fluid this slab owns.
    pub fn owned(&self, i: usize) -> bool {
        let p = self.solver.particles();
        p.kind[i] == FLUID && self.owns_id(p.id[i])
    }

    /// Whether the slab owns the fluid particle `id` (an id it never saw: no).
    fn owns_id(&self, id: u32) -> bool {
        self.owns.get(id as usize).copied().unwrap_or(false)
    }

    /// Fluid particles this slab owns.
    pub fn owned_count(&self) -> u64 {
        let n = self.solver.particles().len();
        (0..n).filter(|&i| self.owned(i)).count() as u64
    }

    /// Marks the fluid particle `id` as this slab's or not.
    fn set_owned(&mut self, id: u32, owned: bool) {
        let id = id as usize;
        if id >= self.owns.len() {
            self.owns.resize(id + 1, false);
        }
        self.owns[id] = owned;
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

    /// After a step: takes the fluid that entered through the inflow in it (ids no slab had
    /// yet), drops the halo's copies and hands over the owned fluid that left the slab (to the
    /// left neighbour below `lo`, to the right one from `hi` on).
    pub fn emigrants(&mut self) -> ToNeighbours {
        let known = self.owns.len() as u32;
        let entered: Vec<u32> = {
            let p = self.solver.particles();
            (0..p.len())
                .filter(|&i| p.kind[i] == FLUID && p.id[i] >= known)
                .map(|i| p.id[i])
                .collect()
        };
        for id in entered {
            self.set_owned(id, true);
        }
        let p = self.solver.particles();
        let (mut keep, mut left, mut right) = (Vec::new(), Vec::new(), Vec::new());
        for i in 0..p.len() {
            if p.kind[i] != FLUID {
                keep.push(i as u32);
            } else if self.owns_id(p.id[i]) {
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
                self.owns[id as usize] = false; // owned, so known
            }
        }
        self.solver.state.particles = p.subset(&keep);
        out
    }

    /// Takes over fluid its neighbours handed over ([`Subdomain::emigrants`]).
    pub fn take(&mut self, arrivals: &ToNeighbours) {
        for q in arrivals {
            for &id in &q.id {
                self.set_owned(id, true);
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
            for &id in &q.id {
                if id as usize >= self.owns.len() {
                    self.set_owned(id, false);
                }
            }
            self.solver.state.particles.append(q);
        }
        self.settle();
    }

    /// Sorts the particles into the solver's cell list after they were replaced, and tells the
    /// bodies which fluid the slab owns now.
    fn settle(&mut self) {
        let st = &mut self.solver.state;
        st.grid.sort(&mut st.particles, &mut Vec::new());
        if let Some(share) = self.solver.bodies.share_mut() {
            share.owned.clone_from(&self.owns);
        }
        self.solver.moved();
    }
}
