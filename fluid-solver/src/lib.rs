//! `fluid-solver`: a 3D particle fluid with particle walls for tsunami–structure scenes.
//!
//! Methods (one per folder, picked by the case's `method`): [`emps`], the explicit MPS of Saitoh &
//! Akitomo (seed 000, S1-3 … S1-16), and [`isph`], the incompressible SPH of Ohinata et al.
//! (seed 003, S2-3 … S2-13). [`method`] is the seam the solver steps them through; [`gpu`] is the
//! E-MPS step on a GPU (wgpu, WGSL), chosen by `backend = "gpu"`.
//!
//! Shared services, one folder per concept:
//! - [`particles`]: storage, kinds, the lattice and the initial layout of a case;
//! - [`neighbours`]: cell lists and the passes over neighbours both methods share (moment matrix,
//!   collision);
//! - [`bodies`]: rigid bodies of particles (kinematics in, loads out through the method's pair
//!   laws) and their contact with the walls;
//! - [`boundaries`]: inflow and outflow boundaries, and splash leaving through an open top;
//! - [`unresolved`]: sample points and point reactions of the unresolved drag coupling (S2);
//! - [`sensors`]: probes and wall-pressure sensors; [`output`]: VTU / VTP frames, progress;
//! - [`ranks`]: the fluid cut into slabs with halos, stepped together (the decomposition the MPI
//!   ranks will use).
//!
//! The spine, at the root: [`solver`], the clock, advance-to, checkpoints of
//! [`state::FluidState`]; [`physics`]: the fluid's parameters; [`stability`]: the instability
//! detector; [`stage_timer`]: time per stage; [`run`]: a standalone run; [`participant`]: the
//! coupled-run side (`fluid-solver participant …`).

pub mod bodies;
pub mod boundaries;
pub mod emps;
pub mod gpu;
pub mod isph;
pub mod method;
pub mod neighbours;
pub mod output;
pub mod participant;
pub mod particles;
pub mod physics;
pub mod ranks;
pub mod run;
pub mod sensors;
pub mod solver;
pub mod stability;
pub mod stage_timer;
pub mod state;
pub mod unresolved;

pub use particles::kind::Kind;
pub use solver::FluidSolver;
pub use stability::Instability;
pub use state::FluidState;

// The modules' paths from before they were grouped into folders, which tests and benches use.
pub use boundaries::{escape, open_boundary};
pub use neighbours::{collision, neighbour_search, vector_field};
pub use output::{surface_mesh, vtp, vtu};
pub use particles::layout;
pub use sensors::{probe_signal, probes, wall_sensor};
