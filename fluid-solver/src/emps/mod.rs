//! E-MPS (Saitoh & Akitomo, seed 000, S1-3 … S1-16): the explicit MPS method with a stiff
//! equation of state.
//!
//! - [`kernel`]: the MPS weights (S1-5, S1-6) and lattice constants (S1-7, S1-8);
//! - [`operators`]: number density (S1-15), pressure gradient (S1-3), Laplacian (S1-4);
//! - [`pair_laws`]: the fluid–body pair forces of S1-3 and S1-4;
//! - [`artificial_viscosity`]: Monaghan's artificial viscosity, an option (not in the seed);
//! - [`step`]: one time step, S1-9 … S1-15, as a list of named stages.

pub mod artificial_viscosity;
pub mod kernel;
pub mod operators;
pub mod pair_laws;
pub mod step;
