//! [`Spring`]: a linear spring on displacements between two anchors, `f_a = k (u_b − u_a)`,
//! `f_b = −f_a` (the law of the issue; it is not a length-based spring, so it suits small motions).

use crate::anchor::Anchor;
use nalgebra::Vector3;

/// A spring between anchors `a` and `b` with stiffness `k` [N/m].
#[derive(Debug, Clone, serde::Serialize, serde::Deserialize)]
pub struct Spring {
    pub a: Anchor,
    pub b: Anchor,
    pub stiffness: f64,
}

impl Spring {
    /// Adds this spring's forces to the point and body force accumulators, given the
    /// displacements of every point mass and body centre.
    pub fn add_forces(
        &self,
        point_u: &[Vector3<f64>],
        body_u: &[Vector3<f64>],
        point_f: &mut [Vector3<f64>],
        body_f: &mut [Vector3<f64>],
    ) {
        let u = |anchor: Anchor| match anchor {
            Anchor::Ground => Vector3::zeros(),
            Anchor::Point(i) => point_u[i],
            Anchor::Body(i) => body_u[i],
        };
        let f_a = self.stiffness * (u(self.b) - u(self.a));
        let mut apply = |anchor: Anchor, f: Vector3<f64>| match anchor {
            Anchor::Ground => {}
            Anchor::Point(i) => point_f[i] += f,
            Anchor::Body(i) => body_f[i] += f,
        };
        apply(self.a, f_a);
        apply(self.b, -f_a);
    }
}
