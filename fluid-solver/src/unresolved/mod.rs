//! The fluid's side of the unresolved drag coupling (S2 §4, physics.md §6): the coupler's
//! drag law asks for the flow at sample points and hands back point reactions.
//!
//! - [`kernel`]: the smooth SPH kernel of these two operations (support 2.4 Δs, S2 Table 1).
//! - [`sampling`]: velocity (Shepard-normalised) and λ_min (moment matrix, S2-10) at a point.
//! - [`spreading`]: a point reaction spread over the fluid particles around it (S2-24).
//!
//! Both find the particles near a point in the step's own cell list
//! ([`crate::neighbour_search::CellGrid::for_each_near_point_trimmed`]) instead of a second grid
//! over the query points (which copied every particle near them each call). The list must be
//! sorted for the particles' present order (the solver re-sorts it when particles were added or
//! removed since the step's sort); positions may have moved since the sort: one pass per call
//! measures how far ([`crate::neighbour_search::CellGrid::drift`], 0 at the window end of an
//! E-MPS step), and each point visits only the cells that can hold a particle within the
//! kernel's support given that drift (rows trimmed to the sphere, empty rows skipped, rows
//! without water skipped for the spreading): the same particles in the same order as the 7³
//! block of 1.05 Δs cells around the point, so the sums are equal to the last bit (test
//! `the_trimmed_point_query_sees_what_the_full_block_sees_after_particles_drifted`).
//!
//! Cost, callgrind on the drag cost bench (`coupler/benches/drag_cost.rs`, t = 0.004 s, 1
//! thread, 10 080 sub-members, 3 270 wet), per call: sampling 71.7 M instructions (77.4 M
//! before a point with no water in its block of cells returned dry without reading the walls
//! around it, and before the point's cell was found without a libm floor; 82.5 M on the 7³
//! block), spreading 49.8 M (48.5 M: the same within the measurement's ±1 M); the ~0.25 M
//! particles within the support of the wet points cost ~100 instructions each and dominate.
//! With the law (2.45 M × 4) a window costs 131 M, 16.1 % of the fluid step's 813 M (17.5 %
//! before); the issue asks for 10 %. Results are equal to the last bit (the same particles in
//! the same order, the same arithmetic).
pub mod kernel;
pub mod sampling;
pub mod spreading;
