//! The fluid cut into sub-domains (issue 39's domain decomposition, E-MPS first): slabs along x,
//! each stepped by its own [`crate::FluidSolver`] on the particles it owns and a halo of copies
//! of its neighbours' particles, thick enough that the owned particles' step is the whole
//! domain's ([`slabs::halo_width`]); after each step the particles that crossed a cut move to
//! their new owner and the halos are sent again.
//!
//! - [`slabs`]: where the cuts lie (balanced by fluid particles) and how thick a halo must be;
//! - [`slab_plan`]: what the slabs of a case start from (layout, cuts, halo, probes, energy);
//! - [`rebalance`]: the slabs cut again when the water has moved (counted by bins of x);
//! - [`slab_probes`]: the case's probes read by the slabs and combined into the whole's row;
//! - [`subdomain`]: one slab's solver, what it owns, what it sends and takes;
//! - [`decomposed`]: the slabs in one process, stepped together, with the whole domain's checks;
//! - [`launcher`]: what `mpirun` or `srun` tells the ranks it starts (with or without MPI built in);
//! - [`mpi_link`], [`rank_slab`] and [`rank_run`] (cargo feature `mpi`): one slab per MPI rank,
//!   the particles traded between ranks, one rank's slab stepped with its exchanges, and a
//!   standalone run on ranks writing its frames in pieces.
//!
//! The slabs trade particles through plain values (what each sends to its left and right
//! neighbour), so the same [`subdomain::Subdomain`] serves one process's threads and one MPI
//! rank each, in the same order: a run on N ranks steps as the case in N slabs of one process.

pub mod decomposed;
pub mod launcher;
#[cfg(feature = "mpi")]
pub mod mpi_link;
#[cfg(feature = "mpi")]
pub mod rank_frames;
#[cfg(feature = "mpi")]
pub mod rank_participant;
#[cfg(feature = "mpi")]
pub mod rank_run;
#[cfg(feature = "mpi")]
mod rank_slab;
pub mod rebalance;
pub mod slab_plan;
pub mod slab_probes;
pub mod slabs;
pub mod subdomain;
