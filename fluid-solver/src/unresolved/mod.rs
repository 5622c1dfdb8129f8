//! The fluid's side of the unresolved drag coupling (S2 §4, physics.md §6): the coupler's
//! drag law asks for the flow at sample points and hands back point reactions.
//!
//! - [`kernel`]: the smooth SPH kernel of these two operations (support 2.4 Δs, S2 Table 1).
//! - [`sampling`]: velocity (Shepard-normalised) and λ_min (moment matrix, S2-10) at a point.
//! - [`spreading`]: a point reaction spread over the fluid particles around it (S2-24).
//!
//! Both find the particles near a point in the step's own cell list
//! ([`crate::neighbour_search::CellGrid::for_each_near_point`]); building a second grid over the
//! query points cost as much as the queries. That list must be sorted for the particles' present
//! order (the solver re-sorts it when particles were added or removed since the step's sort);
//! positions may have moved since the sort by less than the cells' slack: the 7 × 7 × 7 cells of
//! 1.05 Δs around a point reach 3.15 Δs, 0.75 Δs beyond the support, while a stable step moves a
//! particle by a fraction of Δs (Courant number well below 1).

pub mod kernel;
pub mod sampling;
pub mod spreading;
