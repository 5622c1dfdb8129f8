//! Section forces an engineer reads: the resultants `[N, Vy, Vz, T, My, Mz]` (local axes of the
//! element: x along the chord from its first node, y and z the section's axes) at both ends of every
//! element. N, V and T are constant along an ASI-Gauss element; the moments vary linearly with the
//! shear (`element::moments_at`). Also the nodes' rotations.

use super::element::moments_at;
use super::hinge::StressState;
use super::section::Resultants;
use super::topology::Element;
use super::Frame;

/// Resultants at the first (ξ = −1) and second (ξ = +1) node of element `e` in stress state
/// `stress`.
pub fn end_forces(e: &Element, stress: &StressState) -> [Resultants; 2] {
    [-1.0, 1.0].map(|xi| {
        let (my, mz) = moments_at(e.length0, stress.s, &stress.sigma, xi);
        let s = &stress.sigma;
        [s[0], s[1], s[2], s[3], my, mz]
    })
}

impl Frame {
    /// Section forces at both ends of every element (two elements per member, in member order).
    pub fn section_forces(&self) -> Vec<[Resultants; 2]> {
        self.elements
            .iter()
            .zip(self.stresses.current())
            .map(|(e, s)| end_forces(e, s))
            .collect()
    }

    /// Member and half (0: the member's first element, 1: its second) of every element.
    pub fn element_members(&self) -> Vec<(usize, usize)> {
        self.elements.iter().map(|e| (e.member, e.half)).collect()
    }

    /// Rotation of every node from its initial orientation as a rotation vector (axis × angle,
    /// global) [rad], 3 per node.
    pub fn node_rotations(&self) -> Vec<f64> {
        self.nodes
            .iter()
            .flat_map(|n| {
                let v = n.rotation.scaled_axis();
                [v.x, v.y, v.z]
            })
            .collect()
    }
}
