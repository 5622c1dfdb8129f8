//! The slabs of one case in one process, stepped together: each slab's step in parallel, then
//! the fluid that crossed a cut handed to its new owner and the halos sent again
//! ([`super::subdomain`]). The checks that need the whole fluid (its energy) are made here over
//! the slabs' own particles.

use super::rebalance;
use super::rebalance::Recut;
use super::slab_plan::SlabPlan;
use super::slab_probes::SlabProbes;
use super::subdomain::{SlabState, Subdomain, ToNeighbours};
use crate::boundaries::open_boundary::ParticleBalance;
use crate::particles::Particles;
use crate::sensors::probes::ProbeSet;
use crate::sensors::view::ParticleView;
use crate::solver::FluidSolver;
use crate::stability::{Instability, StabilityMonitor};
use rayon::prelude::*;
use schemas::case::fluid::FluidConfig;

/// A case's fluid in slabs along x.
pub struct DecomposedFluid {
    parts: Vec<Subdomain>,
    /// The whole domain's monitor: its energy reference.
    whole: StabilityMonitor,
    /// Fluid particles handed from one slab to another so far.
    handed_over: u64,
    /// Halo copies sent so far.
    copied: u64,
    /// The case's probes: how the slabs' rows make the whole's, and each slab's set.
    probes: SlabProbes,
    probe_sets: Vec<ProbeSet>,
    /// Fluid particles at the start (after the gates are lifted).
    fluid_at_start: u64,
    /// Where the slabs are cut now, and what cutting them again needs.
    cuts: Vec<f64>,
    recut: Recut,
    /// How many times the slabs were cut again.
    recuts: u64,
}

impl DecomposedFluid {
    /// The fluid of `cfg` (a validated section) in `parts` slabs balanced by fluid particles, with
    /// the case's probes; an error naming what the slabs do not support yet, a probe that cannot
    /// be placed, or a slab thinner than the halo.
    pub fn new(cfg: &FluidConfig, parts: usize) -> Result<DecomposedFluid, String> {
        if let Some(what) = cfg.unsupported_in_slabs() {
            return Err(format!(
                "the fluid in slabs supports E-MPS on CPU threads with walls, blocks, gates, solids, bodies, damping zones, inflow and outflow; not yet {what}"
            ));
        }
        let mut whole = FluidSolver::new(cfg);
        let plan = SlabPlan::new(&mut whole, &cfg.probe, parts).map_err(|e| e.to_string())?;
        let parts: Vec<Subdomain> = (0..parts)
            .into_par_iter()
            .map(|r| {
                let mut solver = FluidSolver::new(cfg);
                solver.remove_gates();
                Subdomain::of(
                    solver,
                    &plan.everything,
                    plan.cuts[r],
                    plan.cuts[r + 1],
                    plan.recut.halo,
                )
            })
            .collect();
        Ok(DecomposedFluid {
            parts,
            whole: plan.whole,
            handed_over: 0,
            copied: 0,
            probes: plan.probes,
            probe_sets: plan.probe_sets,
            fluid_at_start: plan.fluid_at_start,
            cuts: plan.cuts,
            recut: plan.recut,
            recuts: 0,
        })
    }

    pub fn parts(&self) -> &[Subdomain] {
        &self.parts
    }

    /// Fluid particles handed from one slab to another so far (they crossed a cut).
    pub fn handed_over(&self) -> u64 {
        self.handed_over
    }

    /// Halo copies of fluid particles sent so far (every step, to each neighbour).
    pub fn copied(&self) -> u64 {
        self.copied
    }

    /// Fluid particles the slabs own.
    pub fn fluid_count(&self) -> u64 {
        self.parts.iter().map(Subdomain::owned_count).sum()
    }

    /// The open boundaries' particle balance: the first slab's inflow and the last slab's
    /// outflow (the others run neither).
    pub fn balance(&self) -> ParticleBalance {
        self.parts
            .iter()
            .map(|s| s.solver.open_boundaries().balance())
            .sum()
    }

    /// Fluid particles removed so far, through the open top and the outflow: what entered and
    /// was there at the start, less what the slabs own.
    pub fn removed(&self) -> u64 {
        self.fluid_at_start + self.balance().entered - self.fluid_count()
    }

    /// After a step, as [`ProbeSet::observe`]: each slab's filtered probes keep their readings.
    pub fn observe_probes(&mut self, next_row: f64) {
        self.probe_sets
            .par_iter_mut()
            .zip(&self.parts)
            .for_each(|(set, s)| set.observe(&s.solver, next_row));
    }

    /// The probes' row at the present time, as the undivided fluid's ([`super::slab_probes`]).
    pub fn probe_row(&mut self) -> Vec<f64> {
        let rows: Vec<Vec<f64>> = self
            .probe_sets
            .par_iter_mut()
            .zip(&self.parts)
            .map(|(set, s)| set.row_in(&ParticleView::of(&s.solver)))
            .collect();
        self.probes.combine(&rows)
    }

    /// Moves every slab's bodies ([`FluidSolver::set_body_motion`]); a moving body drives the
    /// fluid (no energy check from then on).
    pub fn set_body_motion(&mut self, pose: &[f64], velocity: &[f64], lead: f64) -> Result<(), String> {
        if velocity.iter().any(|&v| v != 0.0) {
            self.whole.set_driven();
        }
        self.parts
            .iter_mut()
            .try_for_each(|s| s.solver.set_body_motion(pose, velocity, lead))
    }

    /// The bodies' loads of the last step (6 per body), summed over the slabs: each reports
    /// those from the fluid it owns and the walls' contact between its cuts.
    pub fn body_loads(&self) -> Vec<f64> {
        sum_over(self.parts.iter().map(|s| s.solver.body_loads()))
    }

    /// The bodies' reaction on the fluid and the walls in the last step, summed over the slabs.
    pub fn body_reactions(&self) -> Vec<f64> {
        sum_over(self.parts.iter().map(|s| s.solver.body_reactions()))
    }

    /// Every slab's state ([`DecomposedFluid::restore`] goes back to it), as an implicit
    /// coupling window keeps its start.
    pub fn save(&self) -> Vec<SlabState> {
        self.parts.iter().map(Subdomain::save).collect()
    }

    /// Goes back to the states `saved` by [`DecomposedFluid::save`] (the counts of what moved
    /// between the slabs keep counting).
    pub fn restore(&mut self, saved: &[SlabState]) {
        self.parts
            .iter_mut()
            .zip(saved)
            .for_each(|(s, state)| s.restore(state));
    }

    /// Sets every slab's clock to `t_end` when the steps have reached it up to rounding
    /// ([`FluidSolver::land_on`]), as a run does at each output time.
    pub fn land_on(&mut self, t_end: f64) {
        self.parts.iter_mut().for_each(|s| s.solver.land_on(t_end));
    }

    /// The simulated time (every slab's).
    pub fn time(&self) -> f64 {
        self.parts[0].solver.time()
    }

    /// One step of `dt` on every slab, then the exchange: stops with the first slab's diagnostic,
    /// or the whole fluid's energy check (as [`StabilityMonitor::check`]'s, over the slabs' own
    /// fluid). Every [`rebalance::CHECK_EVERY`] steps the slabs are cut again if the water has
    /// moved too far from an even split ([`super::rebalance`]).
    pub fn step(&mut self, dt: f64) -> Result<(), Instability> {
        self.parts
            .par_iter_mut()
            .map(|s| s.solver.step(dt).map(|_| ()))
            .collect::<Result<Vec<()>, Instability>>()?;
        self.hand_over();
        self.send_halos();
        self.check_energy(dt)?;
        if self.parts[0]
            .solver
            .steps()
            .is_multiple_of(rebalance::CHECK_EVERY)
        {
            self.rebalance();
        }
        Ok(())
    }

    /// Each slab hands the owned fluid that left it to its neighbours; returns how many went.
    fn hand_over(&mut self) -> u64 {
        let leaving: Vec<ToNeighbours> = self.parts.par_iter_mut().map(|s| s.emigrants()).collect();
        let went = leaving.iter().flatten().map(|p| p.len() as u64).sum::<u64>();
        self.handed_over += went;
        let arriving = from_neighbours(leaving);
        self.parts
            .par_iter_mut()
            .zip(&arriving)
            .for_each(|(s, a)| s.take(a));
        went
    }

    /// Each slab sends copies of its fluid near its faces to its neighbours and sorts its
    /// particles for the next step.
    fn send_halos(&mut self) {
        let copies: Vec<ToNeighbours> = self.parts.par_iter().map(|s| s.halo_copies()).collect();
        self.copied += copies.iter().flatten().map(|p| p.len() as u64).sum::<u64>();
        let halos = from_neighbours(copies);
        self.parts
            .par_iter_mut()
            .zip(&halos)
            .for_each(|(s, h)| s.take_halo(h));
    }

    /// Cuts the slabs again where the fluid's counts say, when the fullest slab holds more than
    /// [`rebalance::LIMIT`] times the mean and the new cuts fit ([`super::rebalance`]).
    fn rebalance(&mut self) {
        let bins = &self.recut.bins;
        let counts = self
            .parts
            .iter()
            .map(|s| bins.histogram(s.solver.particles(), |i| s.owned(i)))
            .reduce(|a, b| a.iter().zip(&b).map(|(x, y)| x + y).collect())
            .unwrap_or_default();
        let Some(cuts) = self.recut.new_cuts(&counts, &self.cuts) else {
            return;
        };
        let fixed = &self.recut.fixed;
        self.parts
            .par_iter_mut()
            .enumerate()
            .for_each(|(r, s)| s.recut(cuts[r], cuts[r + 1], fixed));
        // a cut may have moved past a whole slab: hand over until every slab owns its own
        while self.hand_over() > 0 {}
        self.send_halos();
        let windows: Vec<rebalance::Windows> = self.probe_sets.iter().map(|p| p.windows().to_vec()).collect();
        (self.probes, self.probe_sets) = self.recut.probes_after(&self.probes, &windows, &cuts);
        self.cuts = cuts;
        self.recuts += 1;
    }

    /// How many times the slabs were cut again as the water moved.
    pub fn recuts(&self) -> u64 {
        self.recuts
    }

    /// Where the slabs are cut now (slab r owns `cuts[r] ≤ x < cuts[r + 1]`).
    pub fn cuts(&self) -> &[f64] {
        &self.cuts
    }

    /// The whole fluid's mechanical energy against the whole domain's reference.
    fn check_energy(&self, dt: f64) -> Result<(), Instability> {
        let energy = || self.parts.iter().map(|s| s.owned_energy(&self.whole)).sum();
        check_whole_energy(
            &self.whole,
            energy,
            &self.parts[0].solver,
            self.parts.len(),
            "slabs",
            dt,
        )
    }

    /// Every slab's own fluid, slab after slab.
    pub fn fluid(&self) -> Particles {
        let mut all = Particles::default();
        for s in &self.parts {
            all.append(&s.owned_fluid());
        }
        all
    }
}

/// The whole fluid's energy check (as [`StabilityMonitor::check`]'s) when its parts each hold
/// some of it: `energy()`, the fluid's energy summed over its `parts` `what` ("slabs",
/// "ranks"), against `whole`'s limit (taken only when there is one), reported at `s`'s step.
pub(super) fn check_whole_energy(
    whole: &StabilityMonitor,
    energy: impl FnOnce() -> f64,
    s: &FluidSolver,
    parts: usize,
    what: &str,
    dt: f64,
) -> Result<(), Instability> {
    let Some(limit) = whole.energy_limit() else {
        return Ok(());
    };
    let e = energy();
    if e.is_finite() && e <= limit {
        return Ok(());
    }
    Err(Instability {
        step: s.steps(),
        time: s.time(),
        particle: None,
        quantity: "mechanical energy",
        message: format!(
            "the fluid's energy per unit particle mass, summed over {parts} {what}, grew to {e:.6e}, past the allowed {limit:.6e}, with no source (step of {dt} s)"
        ),
    })
}

/// The element-wise sum of equally long vectors.
fn sum_over(parts: impl Iterator<Item = Vec<f64>>) -> Vec<f64> {
    parts
        .reduce(|a, b| a.iter().zip(&b).map(|(x, y)| x + y).collect())
        .unwrap_or_default()
}

/// What each slab receives from its neighbours: slab r gets what r − 1 sent right and what
/// r + 1 sent left (its own left and right inputs).
fn from_neighbours(sent: Vec<ToNeighbours>) -> Vec<ToNeighbours> {
    let n = sent.len();
    (0..n)
        .map(|r| {
            let from_left = match r {
                0 => Particles::default(),
                _ => sent[r - 1][1].clone(),
            };
            let from_right = match r + 1 < n {
                true => sent[r + 1][0].clone(),
                false => Particles::default(),
            };
            [from_left, from_right]
        })
        .collect()
}
