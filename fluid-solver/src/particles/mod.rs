//! The particles: their storage, what kind each one is, and the initial layout of a case on one
//! simple cubic lattice (tank walls, water, gates, bodies).
//!
//! - [`storage`]: structure-of-arrays storage ([`Particles`]), re-exported here;
//! - [`body_sites`]: which body a lattice site belongs to (a box's or a mesh's);
//! - [`body_interior`]: a body's inside for the instability detector, at its present pose;
//! - [`kind`]: fluid / wall / dummy / body / gate / inflow, and what each kind takes part in;
//! - [`lattice`]: the case's boxes moved onto the lattice's faces;
//! - [`layout`]: the initial particle layout of a case;
//! - [`solid_sites`]: the lattice sites of mesh solids and terrains, and their skin.

pub mod body_interior;
pub mod body_sites;
pub mod kind;
pub mod lattice;
pub mod layout;
pub mod solid_sites;
pub mod storage;

pub use storage::{Particles, STATE_BYTES_PER_PARTICLE};
