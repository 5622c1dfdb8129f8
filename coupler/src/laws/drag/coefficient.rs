//! C_D of a square section against its attack angle: a table of the case (S2 §4(1)d, Fig. 1;
//! default `schemas::case::drag::square_prism_drag`), linear between rows.

use nalgebra::Vector3;

/// `[[angle_deg, C_D], …]` from 0° to 45°, angles rising (checked when the case is loaded).
#[derive(Debug, Clone)]
pub struct DragTable {
    rows: Vec<[f64; 2]>,
}

impl DragTable {
    /// The table of a validated case.
    pub fn new(rows: &[[f64; 2]]) -> DragTable {
        DragTable { rows: rows.to_vec() }
    }

    /// C_D at `angle` degrees (clamped to the table's range), linear between rows.
    pub fn at(&self, angle: f64) -> f64 {
        let rows = &self.rows;
        let Some(k) = rows.iter().position(|r| r[0] >= angle) else {
            return rows.last().map_or(0.0, |r| r[1]);
        };
        if k == 0 {
            return rows[0][1];
        }
        let ([a0, c0], [a1, c1]) = (rows[k - 1], rows[k]);
        c0 + (c1 - c0) * (angle - a0) / (a1 - a0)
    }
}

/// S2-18's D, the width of a square section of side `side` projected across the flow at attack
/// angle `alpha` [deg]: `side (cos α + sin α)` (√2 side corner-on). C_D tables are taken on it.
pub fn projected_width(side: f64, alpha: f64) -> f64 {
    let a = alpha.to_radians();
    side * (a.cos() + a.sin())
}

/// Attack angle [deg] of the cross-flow `v_normal` (already normal to the member axis `axis`) on
/// a square section with face normal `section_axis`: the angle between `v_normal` and the face
/// normal projected across the member, folded into [0°, 45°] by the square's symmetry. Without
/// a face normal, or when it lies along the member, or with no cross-flow: 0°.
pub fn attack_angle(
    v_normal: &Vector3<f64>,
    axis: &Vector3<f64>,
    section_axis: Option<&Vector3<f64>>,
) -> f64 {
    let Some(s) = section_axis else {
        return 0.0;
    };
    let face = s - axis * axis.dot(s);
    let (fn_, vn) = (face.norm(), v_normal.norm());
    if fn_ <= 1e-12 * s.norm() || vn == 0.0 {
        return 0.0;
    }
    let cos = (face.dot(v_normal) / (fn_ * vn)).abs().min(1.0);
    let angle = cos.acos().to_degrees();
    angle.min(90.0 - angle)
}
