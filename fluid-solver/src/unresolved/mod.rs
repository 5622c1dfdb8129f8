//! The fluid's side of the unresolved drag coupling (S2 §4, physics.md §6): the coupler's
//! drag law asks for the flow at sample points and hands back point reactions.
//!
//! - [`kernel`]: the smooth SPH kernel of these two operations (support 2.4 Δs, S2 Table 1).
//! - [`point_grid`]: a cell list of the particles near the query points.
//! - [`sampling`]: velocity (Shepard-normalised) and λ_min (moment matrix, S2-10) at a point.
//! - [`spreading`]: a point reaction spread over the fluid particles around it (S2-24).

pub mod kernel;
pub mod point_grid;
pub mod sampling;
pub mod spreading;
