//! The fluid's side of the unresolved drag coupling (S2 §4, docs/physics.md §6): the coupler's
//! drag law asks for the flow at sample points and hands back point reactions.
//!
//! - [`kernel`]: the smooth SPH kernel of these two operations (support 2.4 Δs, S2 Table 1).
//! - [`sampling`]: velocity (Shepard-normalised) and λ_min (moment matrix, S2-10) at a point.
//! - [`spreading`]: a reaction spread over the fluid particles around it (S2-24), over the
//!   footprint of a member wider than a particle.
//!
//! Both find the particles near a point in the step's own cell list
//! ([`crate::neighbours::neighbour_search::CellGrid::for_each_near_point_trimmed`]) instead of a second grid
//! over the query points (which copied every particle near them each call). The list must be
//! sorted for the particles' present order (the solver re-sorts it when particles were added or
//! removed since the step's sort); positions may have moved since the sort: one pass per call
//! measures how far ([`crate::neighbours::neighbour_search::CellGrid::drift`], 0 at the window end of an
//! E-MPS step), and each point visits only the cells that can hold a particle within the
//! kernel's support given that drift (rows trimmed to the sphere, empty rows skipped, rows
//! without water skipped for the spreading): the same particles in the same order as the 7³
//! block of 1.05 Δs cells around the point, so the sums are equal to the last bit (test
//! `the_trimmed_point_query_sees_what_the_full_block_sees_after_particles_drifted`).
//!
//! Cost, callgrind on the drag cost bench (`coupler/benches/drag_cost.rs`, t = 0.004 s, 1
//! thread, 10 080 sub-members, 3 270 wet), per call: sampling 94.4 M instructions with the
//! shares of the reactions found in the same search, spreading 7.6 M by reusing them (the
//! fluid participant samples at the window end with the window's reactions and spreads the
//! next step's at the same particle positions: [`crate::FluidSolver::sample_points_for`],
//! guarded by a positions version and the centroids being the same, so a moving member is
//! searched again), outputs equal to the last bit (the bench prints a digest of them). With the
//! law (2.45 M × 4) a window costs ~112 M, 13.8 % of the fluid step's 813 M; the issue asks for
//! 10 %. Where the sampling's instructions go (callgrind `--dump-instr`, per call): the
//! accepted particles' work (Shepard sums, moment matrix, shares: ~210 k particles within the
//! support, ~255 k fluid particles within the widened reach) and the candidates' distance test
//! (~590 k at ~24 instructions) ~47 M; choosing the rows of cells (~110 k rows, ~110
//! instructions each, and ~250 per point) ~17 M; the drift pass
//! ([`crate::neighbours::neighbour_search::CellGrid::drift`]) 10 M; λ_min ~1 M (not worth skipping).
//! History: 99.9 M with one call per particle; 97.3 M with one loop over each row's arrays
//! ([`crate::neighbours::neighbour_search::CellGrid::for_each_row_near_point`]); 94.4 M with the test for
//! water done plane by plane first. Tried and left out (measured): the moment matrix's terms
//! written out (no gain), the drift pass cell by cell over the sorted ranges (+4.8 M: the
//! empty cells cost more than finding each particle's cell again). Next step: batching the
//! sample points of one member (they lie a Δs apart, so each particle is within the support
//! of ~5 of them): their rows and candidates read once for all of them.
pub mod kernel;
pub mod sampling;
pub mod spreading;
