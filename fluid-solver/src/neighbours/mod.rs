//! A particle's neighbours and the passes over them that both methods share: the cell-list
//! search, the vector field a pass fills, the moment matrix (λ_min) and the collision stage.
//!
//! - [`neighbour_search`]: cell lists with counting sort, and point queries;
//! - [`vector_field`]: a per-particle vector and the totals a pass over the pairs returns;
//! - [`moments`]: the moment matrix of a neighbourhood and its λ_min (S2-10 … S2-13);
//! - [`collision`]: collision of close approaching particles and its fluid–body pair law;
//! - [`interacting_pairs`]: how many fluid–neighbour pairs a pass sums over (GPIPS).

pub mod collision;
pub mod interacting_pairs;
pub mod moments;
pub mod neighbour_search;
pub mod vector_field;
