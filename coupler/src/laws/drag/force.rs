//! The fluid force on one sub-member from the flow sampled upstream of it (S2-19 … S2-21).

use nalgebra::Vector3;

/// λ_min at and above which a sample point is inside the water (S2-20's λ^inner).
pub const LAMBDA_INNER: f64 = 0.9;
/// λ_min of a point on a flat free surface, below which it is dry (S2-20's λ^surface).
pub const LAMBDA_SURFACE: f64 = 0.5;

/// S2-20: submerged length of a sub-member of length `d` whose sample point has `lambda_min`.
pub fn submerged_length(lambda_min: f64, d: f64) -> f64 {
    if lambda_min < LAMBDA_SURFACE {
        0.0
    } else if lambda_min <= LAMBDA_INNER {
        d * (lambda_min - LAMBDA_SURFACE) / (LAMBDA_INNER - LAMBDA_SURFACE)
    } else {
        d
    }
}

/// S2-19 for a velocity component `v` (the part of the relative velocity across the member, or
/// along it for the axial drag): `½ C_D ρ v |v| D l`.
pub fn drag(cd: f64, density: f64, v: &Vector3<f64>, width: f64, submerged: f64) -> Vector3<f64> {
    v * (0.5 * cd * density * v.norm() * width * submerged)
}

/// S2-21: buoyancy `−ρ g A l` (g the gravity vector, so the force points up).
pub fn buoyancy(density: f64, gravity: &Vector3<f64>, area: f64, submerged: f64) -> Vector3<f64> {
    -gravity * (density * area * submerged)
}

/// The velocity `v_rel` (fluid minus member) split into its parts across and along the unit
/// member axis `axis`: `v cos θ` of S2-19 is the first.
pub fn split(v_rel: &Vector3<f64>, axis: &Vector3<f64>) -> (Vector3<f64>, Vector3<f64>) {
    let along = axis * axis.dot(v_rel);
    (v_rel - along, along)
}

/// S2-22, S2-23: a force at element coordinate ξ shared by the element's two nodes,
/// `F_1 = ½(1 − ξ) f`, `F_2 = ½(1 + ξ) f`.
pub fn to_nodes(xi: f64, f: &Vector3<f64>) -> [Vector3<f64>; 2] {
    [f * (0.5 * (1.0 - xi)), f * (0.5 * (1.0 + xi))]
}
