//! The structure solver: point masses on linear springs, 6-DOF rigid bodies with washout
//! supports, prescribed loads, and the two ways to run them — standalone (`structure-solver run`)
//! and as a participant of a coupled run (`structure-solver participant`).
//!
//! [`Structure`] holds everything one participant owns and advances it to a given time under
//! external loads given as a function of time; [`LoadSchedule`] turns the case's prescribed loads
//! into such a function.

pub mod anchor;
pub mod error;
pub mod external_loads;
pub mod frame;
pub mod frame_tables;
pub mod history;
pub mod inertia;
pub mod load_history;
pub mod load_schedule;
pub mod output;
pub mod participant;
pub mod point_mass;
pub mod rigid_body;
pub mod spring;
pub mod stability;
pub mod standalone;
pub mod structure;
pub mod support;
pub mod vtu_series;

pub use error::StepError;
pub use external_loads::ExternalLoads;
pub use load_schedule::LoadSchedule;
pub use structure::Structure;
