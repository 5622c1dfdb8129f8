//! Resolved rigid bodies made of particles: their kinematics in, their loads out, and their
//! contact with the walls.
//!
//! - [`rigid_bodies`]: the bodies' particles, poses and the load exchange ([`RigidBodies`]),
//!   re-exported here;
//! - [`pair_law`]: the fluid–body pair law a method hands to the exchange;
//! - [`body_wall_contact`]: the spring–dashpot contact between a body and the walls.

pub mod body_wall_contact;
pub mod pair_law;
pub mod rigid_bodies;

pub use rigid_bodies::{rotate, RigidBodies};
