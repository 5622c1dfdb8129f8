//! ISPH (Ohinata, Omura, Asai & Isobe, seed 003, S2-3 … S2-13): incompressible SPH by a
//! projection method with a pressure Poisson equation every step.
//!
//! - [`kernel`]: the Wendland C2 kernel, support 2.4 Δs;
//! - [`neighbour_list`]: the pairs within the support, built once per step;
//! - [`operators`]: density (S2-7), divergence and gradient (S2-8), Laplacian (S2-9);
//! - [`free_surface`]: Marrone's λ_min thresholds and geometric scan (S2-10 … S2-13);
//! - [`walls`]: particle walls with Adami's pressure extrapolation;
//! - [`ppe`]: the pressure Poisson equation (S2-5) and its solvers;
//! - [`exact_projection`]: the PPE built from the symmetric gradient (`"conservative"`);
//! - [`ppe_two_level`]: its CG with a two-level (aggregation) preconditioner;
//! - [`pair_gradients`]: the pairs' kernel gradients the exact projection's operator reads;
//! - [`pair_laws`]: the fluid–body pair forces;
//! - [`body_completion`]: the bodies' pressure law of the exact projection;
//! - [`kernel_correction`]: the symmetric forms' pairs corrected by the moment matrices;
//! - [`surface_walls`]: the walls complete surface water the PPE does not hold (symmetric forms);
//! - [`shifting`]: particle shifting (Lind et al. 2012), a case option;
//! - [`step`]: one time step, S2-3 … S2-5, as a list of named stages.

pub mod body_completion;
pub mod exact_projection;
pub mod free_surface;
pub mod kernel;
pub mod kernel_correction;
pub mod neighbour_list;
pub mod operators;
pub mod pair_gradients;
pub mod pair_laws;
pub mod ppe;
pub mod ppe_two_level;
pub mod shifting;
pub mod step;
pub mod step_length;
pub mod surface_walls;
pub mod walls;
