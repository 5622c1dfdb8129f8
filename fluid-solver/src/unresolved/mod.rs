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
//! thread, 10 080 sub-members, 3 270 wet), per call: sampling 99.9 M instructions with the
//! shares of the reactions found in the same search, spreading 7.6 M by reusing them (the
//! fluid participant samples at the window end with the window's reactions and spreads the
//! next step's at the same particle positions: [`crate::FluidSolver::sample_points_for`],
//! guarded by a positions version and the centroids being the same, so a moving member is
//! searched again); 107.5 M together against 123.0 M (72.2 M + 50.8 M) before, outputs equal
//! to the last bit (the drag column run's ledger is byte-identical). The drift pass
//! ([`crate::neighbour_search::CellGrid::drift`], one per call) went from 13.4 M to 10.1 M.
//! Tried and left out (measured): per-row loops over sliced arrays with the sums held in
//! locals (+2 M: no gain), a per-plane test for fluid before the per-row one (+0.4 M). With the law (2.45 M × 4) a window costs ~117 M, 14.4 % of the fluid step's 813 M
//! (16.3 % before); the issue asks for 10 %. The particles within the support of the wet points
//! (~0.2 M in sampling, ~120 instructions each, and ~0.5 M candidates at ~20) dominate.
pub mod kernel;
pub mod sampling;
pub mod spreading;
