//! The ASI-Gauss element: a linear Timoshenko beam with one integration point at ξ = s (S2 §3,
//! docs/physics.md §5), in a co-rotational frame so that rigid motion of any size leaves it unstrained.

use super::section::Resultants;
use nalgebra::{Matrix3, Rotation3, UnitQuaternion, Vector3};

/// Integration point of an elastic member's elements, `s = ±(2/√3 − 1)`: it puts the stress-evaluation
/// points r = −s on the member's Gauss points, which makes one member exact for the cantilever.
pub const S_GAUSS: f64 = 2.0 / 1.732_050_807_568_877_2 - 1.0;

/// Local degrees of freedom per element: `[u v w θx θy θz]` at each end.
pub const ELEMENT_DOFS: usize = 12;

/// Strain–displacement matrix B(s) of the element (6 × 12): generalised strains at the integration
/// point ξ = s from the local end displacements and rotations (docs/physics.md §5, N1 = (1−ξ)/2, N2 = (1+ξ)/2).
pub fn strain_matrix(length: f64, s: f64) -> [[f64; ELEMENT_DOFS]; 6] {
    let (n1, n2) = ((1.0 - s) / 2.0, (1.0 + s) / 2.0);
    let il = 1.0 / length;
    let mut b = [[0.0; ELEMENT_DOFS]; 6];
    // axial ε = (u2 − u1)/l
    b[0][0] = -il;
    b[0][6] = il;
    // γy = (v2 − v1)/l − (N1 θz1 + N2 θz2)
    b[1][1] = -il;
    b[1][7] = il;
    b[1][5] = -n1;
    b[1][11] = -n2;
    // γz = (w2 − w1)/l + (N1 θy1 + N2 θy2)
    b[2][2] = -il;
    b[2][8] = il;
    b[2][4] = n1;
    b[2][10] = n2;
    // κx, κy, κz = (θ2 − θ1)/l
    for (row, dof) in [(3, 3), (4, 4), (5, 5)] {
        b[row][dof] = -il;
        b[row][dof + 6] = il;
    }
    b
}

/// Generalised strain increment `B(s) d` (the rows of [`strain_matrix`] written out).
pub fn strains(length: f64, s: f64, d: &[f64; ELEMENT_DOFS]) -> Resultants {
    let (n1, n2) = ((1.0 - s) / 2.0, (1.0 + s) / 2.0);
    let il = 1.0 / length;
    [
        (d[6] - d[0]) * il,
        (d[7] - d[1]) * il - n1 * d[5] - n2 * d[11],
        (d[8] - d[2]) * il + n1 * d[4] + n2 * d[10],
        (d[9] - d[3]) * il,
        (d[10] - d[4]) * il,
        (d[11] - d[5]) * il,
    ]
}

/// Stiffness `K = l Bᵀ D B` of a one-point rule (weight 2 × l/2), D a 6 × 6 section stiffness, in
/// global axes: `T K Tᵀ` with T = diag(E, E, E, E), E the element `frame`, computed as
/// `l B_gᵀ D B_g` with `B_g = B Tᵀ` (each 3-block of a row of B, rotated by E).
pub fn global_stiffness(
    frame: &Matrix3<f64>,
    length: f64,
    s: f64,
    d: &[[f64; 6]; 6],
) -> [[f64; ELEMENT_DOFS]; ELEMENT_DOFS] {
    let b = strain_matrix(length, s);
    let mut bg = [[0.0; ELEMENT_DOFS]; 6];
    for (global, local) in bg.iter_mut().zip(&b) {
        for block in 0..4 {
            let v = Vector3::new(local[3 * block], local[3 * block + 1], local[3 * block + 2]);
            if v != Vector3::zeros() {
                global[3 * block..3 * block + 3].copy_from_slice((frame * v).as_slice());
            }
        }
    }
    // C = D B_g
    let mut c = [[0.0; ELEMENT_DOFS]; 6];
    for (c_row, d_row) in c.iter_mut().zip(d) {
        for (&dmk, bk) in d_row.iter().zip(&bg) {
            if dmk != 0.0 {
                for (x, y) in c_row.iter_mut().zip(bk) {
                    *x += dmk * y;
                }
            }
        }
    }
    // K = l B_gᵀ C
    let mut k = [[0.0; ELEMENT_DOFS]; ELEMENT_DOFS];
    for (bm, cm) in bg.iter().zip(&c) {
        for (k_row, &bmi) in k.iter_mut().zip(bm) {
            if bmi != 0.0 {
                let scale = length * bmi;
                for (x, y) in k_row.iter_mut().zip(cm) {
                    *x += scale * y;
                }
            }
        }
    }
    k
}

/// Adds the geometric stiffness of the axial force N to a global stiffness: the string term
/// `(N/l) [P −P; −P P]` on the two ends' translations, `P = e₂e₂ᵀ + e₃e₃ᵀ` (the element `frame`'s
/// transverse axes), which turns the force with the chord (without it, the one-solve-per-step update
/// feeds energy into spinning members).
pub fn add_axial_geometric_stiffness(
    k: &mut [[f64; ELEMENT_DOFS]; ELEMENT_DOFS],
    frame: &Matrix3<f64>,
    axial_force: f64,
    length: f64,
) {
    let (e2, e3) = (frame.column(1), frame.column(2));
    let p = (e2 * e2.transpose() + e3 * e3.transpose()) * (axial_force / length);
    for i in 0..3 {
        for j in 0..3 {
            k[i][j] += p[(i, j)];
            k[6 + i][6 + j] += p[(i, j)];
            k[i][6 + j] -= p[(i, j)];
            k[6 + i][j] -= p[(i, j)];
        }
    }
}

/// Local end forces `f = l Bᵀ σ` of resultants σ read at the stress-evaluation point (the columns
/// of [`strain_matrix`] written out).
pub fn local_forces(length: f64, s: f64, sigma: &Resultants) -> [f64; ELEMENT_DOFS] {
    let (n1, n2) = ((1.0 - s) / 2.0, (1.0 + s) / 2.0);
    let [n, qy, qz, t, my, mz] = *sigma;
    [
        -n,
        -qy,
        -qz,
        -t,
        length * n1 * qz - my,
        -length * n1 * qy - mz,
        n,
        qy,
        qz,
        t,
        length * n2 * qz + my,
        -length * n2 * qy + mz,
    ]
}

/// Bending moments `(My, Mz)` at ξ of an element whose resultants σ are read at r = −s: the moment
/// varies linearly with slope set by the shear (dM/dx = Q), `My(ξ) = My + l Qz (ξ + s)/2`,
/// `Mz(ξ) = Mz − l Qy (ξ + s)/2`.
pub fn moments_at(length: f64, s: f64, sigma: &Resultants, xi: f64) -> (f64, f64) {
    let shift = length * (xi + s) / 2.0;
    (sigma[4] + sigma[2] * shift, sigma[5] - sigma[1] * shift)
}

/// Re-expresses σ for a new integration point `s_new` with the same end forces (the hinge moves).
pub fn move_integration_point(length: f64, s: f64, s_new: f64, sigma: &mut Resultants) {
    let (my, mz) = moments_at(length, s, sigma, -s_new);
    sigma[4] = my;
    sigma[5] = mz;
}

/// Current co-rotational frame of an element and its natural deformations.
#[derive(Debug, Clone, Copy, serde::Serialize, serde::Deserialize)]
pub struct Corotated {
    /// Columns: local x (the chord), y, z in global axes.
    pub frame: Matrix3<f64>,
    /// Local `[u v w θx θy θz]` at both ends: only the elongation `u2` and the end rotations
    /// relative to the chord frame are nonzero.
    pub deformation: [f64; ELEMENT_DOFS],
    /// Current chord length.
    pub length: f64,
}

/// Co-rotational frame and natural deformations from the end positions and nodal rotations.
/// `reference` is the rotation to the element frame at t = 0 (nodal rotations are measured from
/// there, see [`quaternion_of`]); `length0` its length then.
pub fn corotate(
    xa: &Vector3<f64>,
    xb: &Vector3<f64>,
    qa: &UnitQuaternion<f64>,
    qb: &UnitQuaternion<f64>,
    reference: &UnitQuaternion<f64>,
    length0: f64,
) -> Corotated {
    let chord = xb - xa;
    let length = chord.norm();
    let e1 = chord / length;
    // the end triads are R·reference; in quaternions, their rotations relative to the chord frame
    // are q_frame⁻¹ q q_reference
    let y_reference = reference.transform_vector(&Vector3::y());
    let y_mean = (qa.transform_vector(&y_reference) + qb.transform_vector(&y_reference)) * 0.5;
    let e3 = e1.cross(&y_mean).normalize();
    let e2 = e3.cross(&e1);
    let frame = Matrix3::from_columns(&[e1, e2, e3]);
    let to_frame = quaternion_of(&frame).inverse();
    let theta_a = quaternion_log(&(to_frame * qa * reference));
    let theta_b = quaternion_log(&(to_frame * qb * reference));
    let mut deformation = [0.0; ELEMENT_DOFS];
    deformation[3..6].copy_from_slice(theta_a.as_slice());
    deformation[6] = length - length0;
    deformation[9..12].copy_from_slice(theta_b.as_slice());
    Corotated {
        frame,
        deformation,
        length,
    }
}

/// First-order kinematics (`geometry = "linear"`): the element keeps its frame at t = 0 and its
/// length `length0`, and its "deformations" are the end displacements `x − x0` and rotation vectors
/// of the nodal rotations, in that frame (the strains then follow from [`strain_matrix`] as in a
/// small-displacement analysis; the rotation vector equals the sum of the rotation increments for
/// rotations about a fixed axis).
#[allow(clippy::too_many_arguments)]
pub fn linear_kinematics(
    xa: &Vector3<f64>,
    xb: &Vector3<f64>,
    xa0: &Vector3<f64>,
    xb0: &Vector3<f64>,
    qa: &UnitQuaternion<f64>,
    qb: &UnitQuaternion<f64>,
    reference: &UnitQuaternion<f64>,
    length0: f64,
) -> Corotated {
    let to_local = reference.inverse();
    let mut deformation = [0.0; ELEMENT_DOFS];
    let parts = [xa - xa0, quaternion_log(qa), xb - xb0, quaternion_log(qb)];
    for (block, v) in parts.iter().enumerate() {
        deformation[3 * block..3 * block + 3].copy_from_slice(to_local.transform_vector(v).as_slice());
    }
    Corotated {
        frame: *reference.to_rotation_matrix().matrix(),
        deformation,
        length: length0,
    }
}

/// Rotation vector (axis × angle, |angle| ≤ π) of a rotation matrix, exact down to the smallest
/// angles (through the quaternion: θ = 2 atan2(|v|, w) v/|v|).
pub fn rotation_vector(r: &Matrix3<f64>) -> Vector3<f64> {
    quaternion_log(&quaternion_of(r))
}

/// The unit quaternion of a rotation matrix (e.g. an element frame, whose columns are its axes).
pub fn quaternion_of(r: &Matrix3<f64>) -> UnitQuaternion<f64> {
    UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix_unchecked(*r))
}

/// Rotation vector of a unit quaternion, θ = 2 atan2(|v|, w) v/|v| taken with w ≥ 0 (|angle| ≤ π).
fn quaternion_log(q: &UnitQuaternion<f64>) -> Vector3<f64> {
    let (w, v) = if q.w < 0.0 {
        (-q.w, -q.imag())
    } else {
        (q.w, q.imag())
    };
    let s = v.norm();
    if s == 0.0 {
        Vector3::zeros()
    } else if s < SMALL_HALF_ANGLE * w {
        // atan x = x − x³/3 + x⁵/5 − x⁷/7 + O(x⁹): below 0.01 the rest is under 1e-17 relative
        let x = s / w;
        let x2 = x * x;
        v * (2.0 / w * (1.0 - x2 * (1.0 / 3.0 - x2 * (1.0 / 5.0 - x2 / 7.0))))
    } else {
        v * (2.0 * s.atan2(w) / s)
    }
}

/// tan(θ/2) below which [`quaternion_log`] takes the arc tangent from its series (the usual case:
/// an element's end rotations relative to its chord are small).
const SMALL_HALF_ANGLE: f64 = 0.01;

/// Rotates a local 12-vector to global axes.
pub fn to_global_vector(frame: &Matrix3<f64>, f: &[f64; ELEMENT_DOFS]) -> [f64; ELEMENT_DOFS] {
    let mut out = [0.0; ELEMENT_DOFS];
    for b in 0..4 {
        let g = frame * Vector3::new(f[3 * b], f[3 * b + 1], f[3 * b + 2]);
        out[3 * b..3 * b + 3].copy_from_slice(g.as_slice());
    }
    out
}

/// Element frame at t = 0: x along the member, y from `orientation` (projected normal to x), or by
/// default horizontal (global z × x; global y for a vertical member).
pub fn initial_frame(axis: &Vector3<f64>, orientation: Option<[f64; 3]>) -> Matrix3<f64> {
    let e1 = axis.normalize();
    let hint = match orientation {
        Some(o) => Vector3::new(o[0], o[1], o[2]),
        None => {
            let horizontal = Vector3::z().cross(&e1);
            if horizontal.norm() > 1e-6 {
                horizontal
            } else {
                Vector3::y()
            }
        }
    };
    let e2 = (hint - e1 * e1.dot(&hint)).normalize();
    let e3 = e1.cross(&e2);
    Matrix3::from_columns(&[e1, e2, e3])
}
