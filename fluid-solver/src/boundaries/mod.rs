//! Where particles enter and leave the domain during a run, and the boundaries that drive or
//! absorb its waves.
//!
//! - [`open_boundary`]: inflow and outflow boundaries (particles added and removed);
//! - [`escape`]: fluid particles leaving through an open top, removed and counted;
//! - [`paddle`]: the wave maker's paddle, a wall moved by a prescribed stroke;
//! - [`damping`]: zones where the fluid's velocity is relaxed, absorbing waves.

pub mod damping;
pub mod escape;
pub mod open_boundary;
pub mod paddle;
