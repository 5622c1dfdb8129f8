//! Where particles enter and leave the domain during a run.
//!
//! - [`open_boundary`]: inflow and outflow boundaries (particles added and removed);
//! - [`escape`]: fluid particles leaving through an open top, removed and counted.

pub mod escape;
pub mod open_boundary;
