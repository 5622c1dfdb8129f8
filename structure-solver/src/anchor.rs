//! [`Anchor`]: what a spring end is attached to.

/// A spring end: the ground, a point mass, or the centre of a rigid body (by index).
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum Anchor {
    Ground,
    Point(usize),
    Body(usize),
}
