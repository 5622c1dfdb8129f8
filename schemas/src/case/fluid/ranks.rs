//! `ranks` and `launcher`: a fluid participant run on several MPI ranks (fluid-solver's
//! `ranks` module, built with its `mpi` feature), each stepping one slab of the fluid along x.
//! The coupler starts such a participant through the launcher and sees one participant: rank 0
//! talks to it, the others follow rank 0.

use super::{FluidBackend, FluidConfig, FluidMethodName};
use crate::case::FieldError;

/// The launcher when a case names none: OpenMPI's and MPICH's `mpirun`.
pub const DEFAULT_LAUNCHER: &str = "mpirun -np {ranks}";

/// Where a launcher template takes the number of ranks.
pub const RANKS_PLACEHOLDER: &str = "{ranks}";

impl FluidConfig {
    /// How many MPI ranks run this participant (1 unless `ranks` says more).
    pub fn rank_count(&self) -> usize {
        self.ranks.unwrap_or(1)
    }

    /// The launcher's program and arguments for [`FluidConfig::rank_count`] ranks, the
    /// solver's own command to follow them (`mpirun -np 2`, `srun -n 2`).
    pub fn launcher_words(&self) -> Vec<String> {
        let ranks = self.rank_count().to_string();
        self.launcher
            .as_deref()
            .unwrap_or(DEFAULT_LAUNCHER)
            .split_whitespace()
            .map(|w| w.replace(RANKS_PLACEHOLDER, &ranks))
            .collect()
    }

    /// The first feature of this section the fluid in slabs (one process or MPI ranks) does not
    /// run yet, by its case-file name.
    pub fn unsupported_in_slabs(&self) -> Option<&'static str> {
        [
            (self.method != FluidMethodName::Emps, "method = \"isph\""),
            (self.backend != FluidBackend::Cpu, "backend = \"gpu\""),
            (self.wave_maker.is_some(), "[wave_maker]"),
        ]
        .into_iter()
        .find_map(|(on, what)| on.then_some(what))
    }

    /// The first feature of this section the fluid on MPI ranks does not run yet: those of
    /// [`FluidConfig::unsupported_in_slabs`], and free-surface meshes (the ranks write frames in
    /// pieces).
    pub fn unsupported_on_ranks(&self) -> Option<&'static str> {
        self.unsupported_in_slabs()
            .or(self.surface_mesh.then_some("surface_mesh = true"))
    }

    /// Checks `ranks` and `launcher`: at least one rank, a launcher that says where the number
    /// goes, and with more than one rank only what the ranks run. `key` is the section's
    /// dotted path.
    pub(super) fn validate_ranks(&self, key: &str) -> Result<(), FieldError> {
        if self.ranks == Some(0) {
            return Err(FieldError::new(
                format!("{key}.ranks"),
                "must be at least 1, got 0",
            ));
        }
        if let Some(launcher) = &self.launcher {
            if launcher.split_whitespace().next().is_none() || !launcher.contains(RANKS_PLACEHOLDER) {
                return Err(FieldError::new(
                    format!("{key}.launcher"),
                    format!(
                        "must be a command that holds {RANKS_PLACEHOLDER} where the number of ranks goes (e.g. \"srun -n {RANKS_PLACEHOLDER}\"; default \"{DEFAULT_LAUNCHER}\"), got {launcher:?}"
                    ),
                ));
            }
        }
        if self.rank_count() == 1 {
            return Ok(());
        }
        match self.unsupported_on_ranks() {
            Some(f) => Err(FieldError::new(
                format!("{key}.ranks"),
                format!(
                    "the fluid on {} MPI ranks runs E-MPS on CPU threads with walls, blocks, gates, solids, terrains, bodies, the drag coupling, damping zones, probes, inflow and outflow; not yet {f}: set ranks = 1 (or leave it out) for this case",
                    self.rank_count()
                ),
            )),
            None => Ok(()),
        }
    }
}
