//! The fluid's side of the unresolved drag coupling (S2 §4, physics.md §6): the coupler's
//! drag law asks for the flow at sample points and hands back point reactions.
//!
//! - [`kernel`]: the smooth SPH kernel of these two operations (support 2.4 Δs, S2 Table 1).
//! - [`sampling`]: velocity (Shepard-normalised) and λ_min (moment matrix, S2-10) at a point.
//! - [`spreading`]: a point reaction spread over the fluid particles around it (S2-24).
//!
//! Both find the particles near a point in the step's own cell list
//! ([`crate::neighbour_search::CellGrid::for_each_near_point`]) instead of a second grid over
//! the query points (which copied every particle near them each call). Measured on the drag
//! cost bench (`coupler/benches/drag_cost.rs`, callgrind, 10 080 sub-members, 3 271 wet):
//! sampling 82.5 M instructions against 77.6 M with the second grid, spreading 55.1 M against
//! 49.3 M — the shared list reads 343 cells per point where the second grid read 125 half-size
//! ones — while the bench's wall time per window fell from 17.5 % to 14.1 % of a fluid step (one
//! run each on a shared machine): no copy of the particles. Trimming the 7³ block to the cells within reach (217) cost more
//! per row of cells than it saved. That list must be sorted for the particles' present
//! order (the solver re-sorts it when particles were added or removed since the step's sort);
//! positions may have moved since the sort by less than the cells' slack: the 7 × 7 × 7 cells of
//! 1.05 Δs around a point reach 3.15 Δs, 0.75 Δs beyond the support, while a stable step moves a
//! particle by a fraction of Δs (Courant number well below 1).

pub mod kernel;
pub mod sampling;
pub mod spreading;
