//! `fluid-solver`: a 3D particle fluid with particle walls for tsunami–structure scenes.
//!
//! Methods (one per folder, picked by the case's `method`): [`emps`], the explicit MPS of Saitoh &
//! Akitomo (seed 000, S1-3 … S1-16), and [`isph`], the incompressible SPH of Ohinata et al.
//! (seed 003, S2-3 … S2-13). [`method`] is the seam the solver steps them through.
//!
//! Shared services:
//! - [`particles`]: structure-of-arrays storage; [`kind`]: fluid / wall / dummy / body / gate / inflow.
//! - [`layout`]: the initial lattice of a case; [`neighbour_search`]: cell lists with counting sort
//!   and point queries; [`moments`]: the moment matrix and λ_min (S2-10 … S2-13).
//! - [`bodies`] + [`body_wall_contact`]: rigid bodies of particles (kinematics in, loads out through
//!   the method's [`pair_law`]s); [`collision`]: the collision stage both methods share.
//! - [`solver`]: the clock, advance-to, checkpoints of [`state::FluidState`]; [`stage_timer`]: time per stage.
//! - [`open_boundary`]: inflow and outflow boundaries (particles added and removed during a run).
//! - [`unresolved`]: sample points and point reactions of the unresolved drag coupling (S2).
//! - [`gpu`]: the E-MPS step on a GPU (wgpu, WGSL), chosen by `backend = "gpu"`.
//! - [`stability`]: the instability detector; [`probes`] (with [`probe_signal`]: a probe's roughness
//!   across time steps), [`vtu`], [`surface_mesh`] + [`vtp`]: outputs; [`run`]: a standalone run;
//!   [`participant`]: the coupled-run side (`fluid-solver participant …`).

pub mod bodies;
pub mod body_wall_contact;
pub mod collision;
pub mod emps;
pub mod escape;
pub mod gpu;
pub mod isph;
pub mod kind;
pub mod lattice;
pub mod layout;
pub mod method;
pub mod moments;
pub mod neighbour_search;
pub mod open_boundary;
pub mod pair_law;
pub mod participant;
pub mod particles;
pub mod physics;
pub mod probe_signal;
pub mod probes;
pub mod progress;
pub mod run;
pub mod solver;
pub mod stability;
pub mod stage_timer;
pub mod state;
pub mod surface_mesh;
pub mod unresolved;
pub mod vector_field;
pub mod vtk_appended;
pub mod vtp;
pub mod vtu;
pub mod wall_sensor;

pub use kind::Kind;
pub use solver::FluidSolver;
pub use stability::Instability;
pub use state::FluidState;
