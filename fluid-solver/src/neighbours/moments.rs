//! The moment matrix of a particle's neighbourhood and its smallest eigenvalue λ_min
//! (S2-10 … S2-13, after Marrone et al. 2010, "Fast free-surface detection and level-set
//! function definition in SPH solvers", J. Comput. Phys. 229):
//! `m_i = Σ_j V_j (x_j − x_i) ⊗ ∇W_ij`, with `∇W_ij = W'(r) (x_i − x_j)/r`, so
//! `m_i = −Σ_j V_j (W'(r)/r) r_ij ⊗ r_ij` is symmetric and ≈ I in a full neighbourhood.
//!
//! We divide by its value on the full simple cubic lattice, so a particle deep in the water reads
//! exactly λ_min = 1 whatever the kernel's discretisation error there; the thresholds of
//! S2 (0.2 / 0.9) are then fractions of a full neighbourhood. λ_min falls towards 0 where half the
//! support is empty (free surface) and is what the unresolved coupling (S2-20) reads as the
//! fraction of a sample point's support that holds water.

use crate::neighbours::neighbour_search::CellGrid;
use crate::particles::Particles;

/// A radial kernel as the moment matrix needs it: its support radius and `W'(r)/r`.
pub trait RadialGradient: Sync {
    /// Support radius [m].
    fn radius(&self) -> f64;
    /// `W'(r)/r` for 0 < r < radius (≤ 0 for a kernel that decreases outwards).
    fn gradient_over_r(&self, r: f64) -> f64;
}

/// A symmetric 3×3 matrix.
pub type Matrix3 = [[f64; 3]; 3];

/// The identity.
pub const IDENTITY: Matrix3 = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];

/// `m v`.
#[inline(always)]
pub fn times(m: &Matrix3, v: [f64; 3]) -> [f64; 3] {
    std::array::from_fn(|a| m[a][0] * v[0] + m[a][1] * v[1] + m[a][2] * v[2])
}

/// A sum of symmetric outer products `Σ c d ⊗ d`, kept as its six distinct entries (the
/// moment matrices' inner loop: 6 multiply-adds per neighbour instead of 9).
#[derive(Debug, Clone, Copy, Default)]
pub struct OuterSum([f64; 6]);

impl OuterSum {
    /// Adds `c d ⊗ d`.
    #[inline(always)]
    pub fn add(&mut self, c: f64, d: [f64; 3]) {
        let (cx, cy) = (c * d[0], c * d[1]);
        let s = &mut self.0;
        s[0] += cx * d[0];
        s[1] += cx * d[1];
        s[2] += cx * d[2];
        s[3] += cy * d[1];
        s[4] += cy * d[2];
        s[5] += c * d[2] * d[2];
    }

    /// The full symmetric matrix.
    pub fn matrix(&self) -> Matrix3 {
        let s = &self.0;
        [[s[0], s[1], s[2]], [s[1], s[3], s[4]], [s[2], s[4], s[5]]]
    }
}

/// `−V Σ_j (W'(r)/r) r_ij ⊗ r_ij` over lattice neighbours of one site, spacing `spacing`:
/// the normalisation of [`moment_matrix_at`] (a multiple of I by the lattice's symmetry).
pub fn lattice_moment(kernel: &impl RadialGradient, spacing: f64) -> f64 {
    let reach = (kernel.radius() / spacing).ceil() as i32;
    let v = spacing.powi(3);
    let mut sum = 0.0;
    for i in -reach..=reach {
        for j in -reach..=reach {
            for k in -reach..=reach {
                let d = [i, j, k].map(|c| spacing * f64::from(c));
                let r = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
                if r > 0.0 && r < kernel.radius() {
                    sum -= v * kernel.gradient_over_r(r) * d[0] * d[0];
                }
            }
        }
    }
    sum
}

/// S2-10 at an arbitrary point `at`: `m = −(V / m0) Σ_j (W'(r)/r) r_j ⊗ r_j` over particles j
/// that `partner` accepts (by kind byte), r_j = x_j − at, with `m0` the [`lattice_moment`].
/// Works at a particle (it contributes nothing to its own sum) and at any sample point.
pub fn moment_matrix_at(
    grid: &CellGrid,
    p: &Particles,
    at: [f64; 3],
    kernel: &impl RadialGradient,
    volume_over_m0: f64,
    partner: impl Fn(u8) -> bool,
) -> Matrix3 {
    let mut m = OuterSum::default();
    grid.for_each_near_point(p, at, kernel.radius(), |j, r2| {
        if r2 == 0.0 || !partner(p.kind[j]) {
            return;
        }
        let d = [p.x[j] - at[0], p.y[j] - at[1], p.z[j] - at[2]];
        m.add(-volume_over_m0 * kernel.gradient_over_r(r2.sqrt()), d);
    });
    m.matrix()
}

/// The smallest eigenvalue of a symmetric 3×3 matrix (S2-11's λ_min), by the trigonometric
/// closed form of the characteristic cubic (Smith 1961, "Eigenvalues of a symmetric 3 × 3
/// matrix", Commun. ACM 4).
pub fn smallest_eigenvalue(m: &Matrix3) -> f64 {
    let p1 = m[0][1] * m[0][1] + m[0][2] * m[0][2] + m[1][2] * m[1][2];
    let q = (m[0][0] + m[1][1] + m[2][2]) / 3.0;
    if p1 <= 1e-30 * (q * q).max(1e-300) {
        return m[0][0].min(m[1][1]).min(m[2][2]);
    }
    let p2 = (m[0][0] - q).powi(2) + (m[1][1] - q).powi(2) + (m[2][2] - q).powi(2) + 2.0 * p1;
    let p = (p2 / 6.0).sqrt();
    let b: Matrix3 =
        std::array::from_fn(|a| std::array::from_fn(|c| (m[a][c] - if a == c { q } else { 0.0 }) / p));
    let det = b[0][0] * (b[1][1] * b[2][2] - b[1][2] * b[2][1])
        - b[0][1] * (b[1][0] * b[2][2] - b[1][2] * b[2][0])
        + b[0][2] * (b[1][0] * b[2][1] - b[1][1] * b[2][0]);
    let phi = (det / 2.0).clamp(-1.0, 1.0).acos() / 3.0;
    // The eigenvalues are q + 2p cos(φ + 2πk/3); k = 1 gives the smallest.
    q + 2.0 * p * (phi + 2.0 * std::f64::consts::PI / 3.0).cos()
}

/// λ_min of a symmetric 3×3 matrix where it is at most `settled`; above, any lower bound of it
/// that exceeds `settled`: Gershgorin's `min_a (m_aa − Σ_{b≠a} |m_ab|)` where that bound already
/// does. A caller that compares the result with `settled` (or with any threshold below it)
/// decides exactly as with [`smallest_eigenvalue`], and the closed form's acos and cos run only
/// for the particles near the free surface (at S2's scale about 5 ms of a 280 ms step).
pub fn smallest_eigenvalue_up_to(m: &Matrix3, settled: f64) -> f64 {
    let off = |a: usize, b: usize, c: usize| m[a][b].abs() + m[a][c].abs();
    let bound = (m[0][0] - off(0, 1, 2))
        .min(m[1][1] - off(1, 0, 2))
        .min(m[2][2] - off(2, 0, 1));
    if bound > settled {
        bound
    } else {
        smallest_eigenvalue(m)
    }
}

/// The cofactor `C_ab` of a 3×3 `m` and its determinant, or `None` when `m` is singular (|det|
/// below 1e-12 of its scale). For symmetric m the cofactors are symmetric.
fn cofactors(m: &Matrix3) -> Option<(Matrix3, f64)> {
    let c = |a: usize, b: usize| {
        let (a1, a2) = ((a + 1) % 3, (a + 2) % 3);
        let (b1, b2) = ((b + 1) % 3, (b + 2) % 3);
        m[a1][b1] * m[a2][b2] - m[a1][b2] * m[a2][b1]
    };
    let c: Matrix3 = std::array::from_fn(|a| std::array::from_fn(|b| c(a, b)));
    let det = m[0][0] * c[0][0] + m[0][1] * c[0][1] + m[0][2] * c[0][2];
    let scale = m.iter().flatten().map(|x| x.abs()).fold(0.0, f64::max).powi(3);
    if det.abs() <= 1e-12 * scale || det.is_nan() {
        return None;
    }
    Some((c, det))
}

/// `m⁻¹ v` for a symmetric 3×3 `m`, or `None` when `m` is singular (|det| below 1e-12 of its scale).
pub fn solve(m: &Matrix3, v: [f64; 3]) -> Option<[f64; 3]> {
    // Inverse = adjugate / det; for symmetric m the cofactor matrix is symmetric.
    let (c, det) = cofactors(m)?;
    Some(times(&c, v).map(|x| x / det))
}

/// `m⁻¹` of a symmetric 3×3 `m`, or `None` when `m` is singular (as [`solve`]).
pub fn inverse(m: &Matrix3) -> Option<Matrix3> {
    let (c, det) = cofactors(m)?;
    Some(c.map(|row| row.map(|x| x / det)))
}
