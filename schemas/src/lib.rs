//! The contract between the coupler and its participants: case files ([`case`]),
//! interface messages ([`message`]) with their interpolation in a window ([`waveform`]),
//! recordings ([`recording`]), the iceoryx2 link ([`link`]), the participant loop
//! ([`participant`]), checkpoints for resuming a run ([`checkpoint`]) and the stop signals both sides heed ([`signals`]); and the output files every solver writes: ParaView's time series ([`pvd`]), each
//! file written whole or not at all ([`atomic_file`]); and the record a validation test writes ([`validation`]); and the geometry of walls and
//! terrains read from STL, OBJ and ESRI ASCII grid files and filled with lattice sites ([`geometry`]),
//! and the motions of a piston wave maker ([`wave_motion`]), which case files name.

pub mod atomic_file;
pub mod case;
pub mod checkpoint;
pub mod f64s;
pub mod geometry;
pub mod link;
pub mod markdown;
pub mod message;
pub mod participant;
pub mod pvd;
pub mod recording;
pub mod signals;
pub mod validation;
pub mod wave_motion;
pub mod waveform;

pub use f64s::F64s;
