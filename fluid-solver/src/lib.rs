//! `fluid-solver`: a 3D explicit MPS (E-MPS) fluid with particle walls, after Saitoh & Akitomo
//! (seed 000, equations S1-3 … S1-16 in `physics.md`).
//!
//! - [`particles`]: structure-of-arrays storage; [`kind`]: fluid / wall / dummy / body / gate / inflow.
//! - [`layout`]: the initial lattice of a case; [`kernel`]: weights and lattice constants.
//! - [`neighbour_search`]: cell lists with counting sort; [`operators`]: the particle operators.
//! - [`bodies`]: rigid bodies of particles (kinematics in, loads out); [`emps_step`]: one time step; [`solver`]: the clock, save/restore, advance-to.
//! - [`open_boundary`]: inflow and outflow boundaries (particles added and removed during a run).
//! - [`unresolved`]: sample points and point reactions of the unresolved drag coupling (S2).
//! - [`stability`]: the instability detector; [`probes`], [`vtu`], [`surface_mesh`] + [`vtp`]: outputs; [`run`]: a standalone run;
//!   [`participant`]: the coupled-run side (`fluid-solver participant …`).

pub mod bodies;
pub mod body_wall_contact;
pub mod emps_step;
pub mod kernel;
pub mod kind;
pub mod layout;
pub mod neighbour_search;
pub mod open_boundary;
pub mod operators;
pub mod participant;
pub mod particles;
pub mod probes;
pub mod run;
pub mod solver;
pub mod stability;
pub mod surface_mesh;
pub mod unresolved;
pub mod vtk_appended;
pub mod vtp;
pub mod vtu;

pub use kind::Kind;
pub use solver::{FluidSolver, SavedState};
pub use stability::Instability;
