//! Interface messages between the coupler and a participant, with the protocol version.
//!
//! Every exchange is lock-step: the coupler sends one [`ToParticipant`], the participant answers
//! with one [`FromParticipant`] — before which, while it works on a long window, it may send any
//! number of [`FromParticipant::Progress`] reports. Bulk data travel as [`Fields`] of flat `f64`
//! arrays whose order is fixed by the participant's [`InterfaceDecl`] at the handshake.

use crate::f64s::F64s;
use bincode::{Decode, Encode};

/// Version of this message set; a participant with another version is refused at the handshake.
/// Version 4 added [`FromParticipant::Progress`].
pub const PROTOCOL_VERSION: u32 = 4;

/// The oldest protocol version whose recordings this build replays: every recorded message of
/// versions 3 and 4 encodes the same ([`FromParticipant::Progress`], new in 4, is never recorded).
pub const OLDEST_REPLAYABLE_PROTOCOL: u32 = 3;

/// Which solver a participant is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Encode, Decode)]
pub enum Role {
    Fluid,
    Structure,
}

/// What a participant exposes at the interface; array order in [`Fields`] follows these lists.
#[derive(Debug, Clone, Default, PartialEq, Encode, Decode)]
pub struct InterfaceDecl {
    /// Point masses (structure): 3 values per point in the `point_*` arrays.
    pub points: Vec<String>,
    /// Rigid bodies: 6 values per body in `body_force`/`body_velocity`, 7 in `body_pose`.
    pub bodies: Vec<String>,
    /// Beam frame nodes (structure): 3 per node in `node_position`, 6 in `node_force`/`node_velocity`.
    pub frame_nodes: u32,
}

/// First message of a participant.
#[derive(Debug, Clone, PartialEq, Encode, Decode)]
pub struct Hello {
    pub protocol: u32,
    pub role: Role,
    /// The participant's name in the case.
    pub name: String,
    /// FNV-1a hash of the case text the participant loaded.
    pub case_hash: u64,
    pub pid: u32,
    pub interface: InterfaceDecl,
}

/// Where a message sits in the run.
#[derive(Debug, Clone, Copy, PartialEq, Encode, Decode)]
pub struct Header {
    pub protocol: u32,
    /// Coupling window index, from 0.
    pub window: u64,
    /// Iteration inside the window, from 0 (always 0 for explicit coupling).
    pub iteration: u32,
    /// Simulated time the message refers to (the window end for an `Advance`).
    pub time: f64,
}

/// State handling requested before an advance (implicit coupling).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Encode, Decode)]
pub enum Checkpoint {
    /// Just advance.
    None,
    /// Save the state at the window start, then advance.
    Save,
    /// Go back to the saved window-start state, then advance again.
    Restore,
}

/// Member geometry of a beam frame (changes when a member fractures).
#[derive(Debug, Clone, Default, PartialEq, Encode, Decode)]
pub struct Geometry {
    /// Two node indices per member.
    pub member_nodes: Vec<u32>,
    /// Projected width of each member [m].
    pub member_width: F64s,
    /// Cross-section area of each member [m²].
    pub member_area: F64s,
}

macro_rules! fields {
    ($($(#[$doc:meta])* $name:ident),* $(,)?) => {
        /// Interface data at one instant; arrays a participant does not use stay empty.
        #[derive(Debug, Clone, Default, PartialEq, Encode, Decode)]
        pub struct Fields {
            $($(#[$doc])* pub $name: F64s,)*
        }

        impl Fields {
            /// Every array with its name, in a fixed order.
            pub fn arrays(&self) -> Vec<(&'static str, &F64s)> {
                vec![$((stringify!($name), &self.$name)),*]
            }

            /// Every array, mutable, in the order of [`Fields::arrays`].
            pub fn arrays_mut(&mut self) -> Vec<(&'static str, &mut F64s)> {
                vec![$((stringify!($name), &mut self.$name)),*]
            }
        }
    };
}

fields! {
    /// Structure → coupler: displacement of each point mass (3 per point).
    point_displacement,
    /// Structure → coupler: velocity of each point mass (3 per point).
    point_velocity,
    /// Coupler → structure: external force on each point mass (3 per point).
    point_force,
    /// Fluid → coupler → structure: hydrodynamic force and torque about the centre (6 per body).
    body_force,
    /// Fluid → coupler: force and torque (about the body's centre) the body exerted on the fluid,
    /// summed over the fluid's particles — the reaction the ledger sets against `body_force`.
    body_reaction,
    /// Structure → coupler → fluid: centre and unit quaternion w, x, y, z (7 per body).
    body_pose,
    /// Structure → coupler → fluid: velocity of the centre and angular velocity (6 per body).
    body_velocity,
    /// Coupler → structure: force and moment on each frame node, global axes (6 per node).
    node_force,
    /// Structure → coupler: position of each frame node (3 per node).
    node_position,
    /// Structure → coupler: velocity and angular velocity of each frame node (6 per node).
    node_velocity,
    /// Coupler → fluid: points where the fluid velocity and λ_min are wanted (3 per point).
    sample_point,
    /// Fluid → coupler: fluid velocity at each sample point (3 per point).
    sampled_velocity,
    /// Fluid → coupler: smallest eigenvalue of the moment matrix at each sample point (S2-10).
    sampled_lambda_min,
    /// Coupler → fluid: point reactions, point and force (6 per reaction, S2-24).
    reaction,
    /// Coupler → fluid: width of the member each reaction comes from [m] (1 per reaction, or
    /// none: every reaction a point); the fluid spreads a reaction over the member's footprint
    /// (`fluid-solver/src/unresolved/spreading.rs`).
    reaction_width,
}

/// Interface data at a series of instants of one window; `times[0]` is the window start and
/// the last time the window end. Between samples, data are interpolated (see [`crate::waveform`]).
#[derive(Debug, Clone, Default, PartialEq, Encode, Decode)]
pub struct Waveform {
    pub times: Vec<f64>,
    pub samples: Vec<Fields>,
}

/// Coupler → participant.
#[derive(Debug, Clone, PartialEq, Encode, Decode)]
pub enum ToParticipant {
    /// The handshake is accepted.
    Welcome { run_id: String },
    /// The handshake is refused; the participant exits with the reason.
    Refused { reason: String },
    /// Advance over one window with these inputs.
    Advance {
        header: Header,
        checkpoint: Checkpoint,
        inputs: Waveform,
    },
    /// The run is over: write final output and exit.
    Finish,
    /// Write the full state at the end of window `window` (accepted) to the file `path`
    /// ([`crate::checkpoint`]), after writing every output row and frame kept back from it; answered by
    /// `CheckpointWritten`. Not recorded: a recording holds the same messages whether or not the run
    /// took checkpoints (protocol version 2).
    WriteCheckpoint { window: u64, path: String },
}

/// Participant → coupler. (Variants differ in size; a message is built and moved once per
/// window, so boxing would only add an allocation.)
#[allow(clippy::large_enum_variant)]
#[derive(Debug, Clone, PartialEq, Encode, Decode)]
pub enum FromParticipant {
    Hello(Hello),
    /// Interface outputs at t = 0, answered right after `Welcome`.
    Initial {
        outputs: Fields,
        geometry: Option<Geometry>,
    },
    /// The window is done: the header's time is the time the solver reached, and the outputs
    /// are given at each input time. `geometry`: the member geometry after a fracture in this
    /// window (nodes a fracture adds take no load until then); it takes effect at the window end.
    /// In implicit coupling the sweep that brings it ends its window, not converged (the coupler
    /// does not repeat a sweep across a topology change).
    Advanced {
        header: Header,
        outputs: Waveform,
        geometry: Option<Geometry>,
    },
    /// The solver stopped (instability, bad state): the diagnostic says where and why.
    Failed {
        header: Header,
        diagnostic: String,
    },
    /// Final output written.
    Finished,
    /// The state asked for by `WriteCheckpoint` is on disk (synced), `bytes` long.
    CheckpointWritten {
        window: u64,
        bytes: u64,
    },
    /// Not an answer: the participant is still working on the `Advance` of `header`'s window and
    /// iteration, and has taken `steps` solver steps of it so far, reaching `header.time` [s]. Sent
    /// at most every `--progress-interval` seconds of wall time, only after a step; the coupler
    /// takes a participant as hung when neither a report nor an answer comes for
    /// `coupling.timeout`. Not recorded: reports come at wall-clock times, so a run and its replay
    /// differ in them (protocol version 4).
    Progress {
        header: Header,
        steps: u64,
    },
}
