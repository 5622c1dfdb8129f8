//! What the slabs of a case start from, the same for the slabs of one process
//! ([`super::decomposed`]) and for MPI ranks ([`super::rank_run`]): the whole layout with its
//! gates lifted, where it is cut, the halo, the case's probes over the slabs, the whole fluid's
//! energy reference and its fluid particles at the start.

use super::rebalance::{Recut, XBins};
use super::slab_probes::SlabProbes;
use super::slabs::{cuts, halo_width, open_boundaries_fit};
use crate::particles::kind::{Kind, FLUID};
use crate::particles::Particles;
use crate::sensors::probes::ProbeSet;
use crate::solver::FluidSolver;
use crate::stability::StabilityMonitor;
use schemas::case::fluid::ProbeConfig;

/// The start of a case's slabs.
pub struct SlabPlan {
    /// Every particle of the layout, gates lifted (each slab keeps its part).
    pub everything: Particles,
    /// Slab r owns `cuts[r] ≤ x < cuts[r + 1]`.
    pub cuts: Vec<f64>,
    /// How the slabs' probe rows make the whole's, and each slab's probes.
    pub probes: SlabProbes,
    pub probe_sets: Vec<ProbeSet>,
    /// The whole fluid's monitor, started on `everything`: its energy reference.
    pub whole: StabilityMonitor,
    pub fluid_at_start: u64,
    /// What the slabs are cut again from as the water moves ([`super::rebalance`]).
    pub recut: Recut,
}

/// Why a case's slabs cannot start.
#[derive(Debug)]
pub enum PlanError {
    /// A probe cannot be placed where the case puts it.
    Probe(String),
    /// The fluid cannot be cut into the slabs asked for, or an open boundary lies too near a cut.
    Slabs(String),
}

impl std::fmt::Display for PlanError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            PlanError::Probe(m) | PlanError::Slabs(m) => write!(f, "{m}"),
        }
    }
}

impl SlabPlan {
    /// The start of `parts` slabs of `whole` (a solver of the case as built; its gates are
    /// lifted here), balanced by fluid particles, with the case's `probes`.
    pub fn new(whole: &mut FluidSolver, probes: &[ProbeConfig], parts: usize) -> Result<SlabPlan, PlanError> {
        let probes = ProbeSet::new(probes, whole).map_err(PlanError::Probe)?;
        whole.remove_gates();
        let halo = halo_width(whole.kernel(), whole.physics().viscous());
        let cuts = cuts(whole.particles(), parts, halo).map_err(PlanError::Slabs)?;
        let open = whole.open_boundaries();
        open_boundaries_fit(open.inflow_plane(), open.outflow_plane(), &cuts, halo)
            .map_err(PlanError::Slabs)?;
        let (slab_probes, probe_sets) = SlabProbes::new(&probes, &cuts);
        let everything = whole.particles().clone();
        let fixed_kinds = [Kind::Wall.code(), Kind::Dummy.code()];
        let fixed: Vec<u32> = (0..everything.len() as u32)
            .filter(|&i| fixed_kinds.contains(&everything.kind[i as usize]))
            .collect();
        let tank = whole.tank();
        let recut = Recut {
            bins: XBins::new(tank.min[0], tank.max[0], whole.kernel().spacing),
            fixed: everything.subset(&fixed),
            probes,
            planes: (open.inflow_plane(), open.outflow_plane()),
            halo,
        };
        let mut monitor = whole.monitor.clone();
        monitor.start(&everything);
        let fluid_at_start = everything.kind.iter().filter(|&&k| k == FLUID).count() as u64;
        Ok(SlabPlan {
            everything,
            cuts,
            probes: slab_probes,
            probe_sets,
            whole: monitor,
            fluid_at_start,
            recut,
        })
    }
}
