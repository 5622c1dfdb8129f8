//! [`FluidState`]: everything a step changes, in one value that clones whole, so a checkpoint of
//! implicit coupling is `state.clone()` and its restore `clone_from` (no hand-listed fields to
//! forget when a method gains state).

use crate::boundaries::open_boundary::OpenBoundaries;
use crate::method::MethodState;
use crate::neighbours::neighbour_search::CellGrid;
use crate::particles::Particles;

/// The forces between fluid and bodies in the last step (6 per body: force, moment about the
/// centre), as the bodies took them and as the fluid gave them, summed over the pair laws the
/// method handed to the body exchange (see [`crate::bodies`]).
#[derive(Debug, Clone, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct BodyExchange {
    pub loads: Vec<f64>,
    pub reaction: Vec<f64>,
}

/// The state of a fluid participant.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct FluidState {
    pub particles: Particles,
    /// The cell list matching the particles' order (loads are read through it).
    pub grid: CellGrid,
    /// The method's own state (e.g. ISPH's surface flags and PPE record).
    pub method: MethodState,
    /// Present pose (7 per body: centre, quaternion w x y z) and velocity (6 per body: V, ω).
    pub body_pose: Vec<f64>,
    pub body_velocity: Vec<f64>,
    pub body_exchange: BodyExchange,
    pub time: f64,
    pub steps: u64,
    pub gates_removed: bool,
    pub open_boundaries: OpenBoundaries,
    /// Fluid particles removed after leaving through the open top ([`crate::boundaries::escape`]).
    pub escaped: u64,
    /// Running totals (impulses, counts): a repeated window must not count its rejected tries.
    pub totals: crate::solver::RunTotals,
}

/// The rest of a fluid solver's state that a resumed run needs: whether the first step was taken,
/// the stability monitor's energy reference (initial energy, allowed growth, driven), and the point
/// reactions of the unresolved coupling in force.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct RunState {
    pub started: bool,
    pub energy_reference: (Option<f64>, f64, bool),
    pub point_reactions: PointReactions,
}

/// The reactions of the unresolved coupling (see [`crate::unresolved::spreading`]), applied at
/// every step until replaced.
#[derive(Debug, Clone, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct PointReactions {
    /// Centroid and force, 6 per reaction.
    pub reactions: Vec<f64>,
    /// The paired sample points (fall-backs), 3 per reaction, or none.
    pub sample_points: Vec<f64>,
    /// Width of each reaction's member, 1 per reaction, or none (all points, S2-24).
    pub widths: Vec<f64>,
}
