//! Free-surface detection after Marrone et al. (2010), as S2 §2(4) uses it (S2-10 … S2-13):
//! 1. λ_min of the moment matrix ([`crate::neighbours::moments`], normalised so a full neighbourhood reads 1):
//!    `λ_min ≤ 0.2` → surface, `λ_min > 0.9` → interior (S2-11);
//! 2. in between, the geometric scan: the outward normal n_i, and the particle is on the surface
//!    when the umbrella-shaped region along n_i holds no other particle.
//!
//! The normal is Marrone's own, `n_i = −ν_i/|ν_i|`, `ν_i = m_i⁻¹ Σ_j V_j ∇W_ij` (his eq. 8, the
//! renormalised gradient of the unit field), not S2-12/S2-13's `−⟨∇λ⟩/|⟨∇λ⟩|`: λ_min is the
//! fill along a particle's emptiest direction, not a fill that grows into the water, so its
//! gradient is no surface normal where λ is low all round (the surge's toe, one or two particles
//! thick) or where wet wall particles read λ = 1 beside fluid that reads 0.7 (the waterline
//! against a wall). On the CI dam break (Δs = L/10, `tests/isph.rs`) the ∇λ normal pointed
//! forwards at toe particles open upwards, and the umbrella then held the particle ahead. Measured
//! on seven snapshots of that run (t = 0.05 … 0.4 s, 1 116 surface particles by the test's
//! brute-force truth, detection on the same positions): ∇λ missed 164 and marked 10 interior
//! particles, ν missed 107 and marked 6.
//!
//! The umbrella in 3D, with Marrone's h = r_e/2 (his kernel's support is 2h) and T = x_i + h n_i:
//! a neighbour j with |x_ji| < √2 h occupies it when it lies in the 45° cone about n_i
//! (`n·x_ji > |x_ji − (n·x_ji) n|`), a farther one when `|x_j − T| < h`. This is Marrone's 2D
//! test (a quarter-plane wedge near i, the disc about T beyond) turned about n_i.
//!
//! Walls: a wall, body or inflow particle takes part (fills the moment matrix and ν, occupies
//! the umbrella) only when it is *wet*: its own support is full (Σ V W over all
//! neighbours ≥ [`WET_FILL`] of the lattice value, see [`fill_flags`]). Water against a
//! submerged wall is then not a free surface, while the wall particles above the waterline,
//! whose support is half air, do not hide the surface particles at the contact line (a tank
//! corner's top particle read λ_min > 0.9 with them and lost its p = 0). A band particle whose
//! normal cannot be formed (m_i singular or ν = 0) is taken as interior: a false p = 0 inside
//! the water would punch a hole in the pressure field. Left open: the wall particles up to
//! about 1 Δs above the waterline still read a fill ≥ [`WET_FILL`], so at the waterline against
//! a wall ν tilts about 50° away from the wall and the umbrella's 45° cone can hold the
//! neighbour beside the particle (the misses left on the dam-break snapshot of
//! `tests/isph.rs`).

use super::kernel::Wendland;
use super::neighbour_list::NeighbourList;
use crate::neighbours::moments::{smallest_eigenvalue_up_to, solve, Matrix3, OuterSum};
use crate::particles::kind::FLUID;
use crate::particles::Particles;
use rayon::prelude::*;

/// S2-11: at or below this λ_min a particle is on the free surface (λ^splash).
pub const LAMBDA_SPLASH: f64 = 0.2;
/// S2-11: above this λ_min a particle is interior (λ^inner).
pub const LAMBDA_INNER: f64 = 0.9;

/// A particle's surface flag: 1 on the free surface (p = 0), 0 otherwise.
pub const SURFACE: u8 = 1;

/// A solid particle is wet when Σ V W over its support is at least this fraction of the lattice
/// value: submerged wall particles read ≈ 1, those at or above the waterline miss the air side.
pub const WET_FILL: f64 = 0.9;

/// 1 for the particles that take part in the detection: fluid, and solids whose support is
/// full (module doc); `fill` is Σ_j V W_ij / lattice value over all neighbours, self included.
pub fn fill_flags(p: &Particles, fill: &[f64], out: &mut Vec<u8>) {
    out.resize(p.len(), 0);
    out.par_iter_mut()
        .enumerate()
        .with_min_len(4096)
        .for_each(|(i, f)| *f = u8::from(p.kind[i] == FLUID || fill[i] >= WET_FILL));
}

/// S2-10 at fluid particle i over its listed neighbours that take part (`takes_part`, from
/// [`fill_flags`]), normalised.
pub fn moment_matrix(
    k: &Wendland,
    list: &NeighbourList,
    p: &Particles,
    takes_part: &[u8],
    i: usize,
) -> Matrix3 {
    let mut m = OuterSum::default();
    let scale = -k.volume / k.lattice_moment;
    for (j, q) in list.pairs(i) {
        if takes_part[j] == 0 {
            continue;
        }
        let d = [p.x[j] - p.x[i], p.y[j] - p.y[i], p.z[j] - p.z[i]];
        m.add(scale * k.dw_over_r_at(q), d);
    }
    m.matrix()
}

/// λ_min of every fluid particle (S2-10, S2-11) where it is at most [`LAMBDA_INNER`], a lower
/// bound of it above [`LAMBDA_INNER`] elsewhere (every reader only compares it with the two
/// thresholds; [`smallest_eigenvalue_up_to`]); 1 for other particles.
pub fn lambda_min(k: &Wendland, list: &NeighbourList, p: &Particles, takes_part: &[u8], out: &mut Vec<f64>) {
    out.resize(p.len(), 1.0);
    out.par_iter_mut()
        .enumerate()
        .with_min_len(512)
        .for_each(|(i, l)| {
            *l = if p.kind[i] == FLUID {
                smallest_eigenvalue_up_to(&moment_matrix(k, list, p, takes_part, i), LAMBDA_INNER)
            } else {
                1.0
            };
        });
}

/// The surface flags of every particle (S2-11, then Marrone's normal and the scan); `lambda` from
/// [`lambda_min`].
pub fn detect(
    k: &Wendland,
    list: &NeighbourList,
    p: &Particles,
    takes_part: &[u8],
    lambda: &[f64],
    flags: &mut Vec<u8>,
) {
    flags.resize(p.len(), 0);
    flags
        .par_iter_mut()
        .enumerate()
        .with_min_len(512)
        .for_each(|(i, f)| {
            *f = if p.kind[i] != FLUID {
                0
            } else if lambda[i] <= LAMBDA_SPLASH {
                SURFACE
            } else if lambda[i] > LAMBDA_INNER {
                0
            } else {
                match outward_normal(k, list, p, takes_part, i) {
                    Some(n) if umbrella_is_empty(k, list, p, takes_part, i, n) => SURFACE,
                    _ => 0,
                }
            };
        });
}

/// The outward normal of Marrone et al. (2010, eq. 8): `n_i = −ν_i/|ν_i|`,
/// `ν_i = m_i⁻¹ Σ_j V ∇W_ij` over the neighbours that take part: the renormalised gradient of
/// the unit field, pointing to where the support lacks particles (module doc says why not
/// S2-12's ⟨∇λ⟩).
pub fn outward_normal(
    k: &Wendland,
    list: &NeighbourList,
    p: &Particles,
    takes_part: &[u8],
    i: usize,
) -> Option<[f64; 3]> {
    let mut g = [0.0; 3];
    for (j, q) in list.pairs(i) {
        if takes_part[j] == 0 {
            continue;
        }
        // ∇_i W_ij = (W'/r)(x_i − x_j)
        let d = [p.x[i] - p.x[j], p.y[i] - p.y[j], p.z[i] - p.z[j]];
        let c = k.volume * k.dw_over_r_at(q);
        for a in 0..3 {
            g[a] += c * d[a];
        }
    }
    let m = moment_matrix(k, list, p, takes_part, i);
    // m is normalised by the lattice moment; ν uses the raw m, a common factor that the
    // normalisation of n cancels.
    let g = solve(&m, g)?;
    let norm = (g[0] * g[0] + g[1] * g[1] + g[2] * g[2]).sqrt();
    if norm <= 0.0 || !norm.is_finite() {
        return None;
    }
    Some(g.map(|v| -v / norm))
}

/// Whether no listed neighbour of i occupies the umbrella along `n` (module doc).
pub fn umbrella_is_empty(
    k: &Wendland,
    list: &NeighbourList,
    p: &Particles,
    takes_part: &[u8],
    i: usize,
    n: [f64; 3],
) -> bool {
    let h = 0.5 * k.radius;
    let t = [p.x[i] + h * n[0], p.y[i] + h * n[1], p.z[i] + h * n[2]];
    let near2 = 2.0 * h * h;
    !list.of(i).iter().any(|&j| {
        let j = j as usize;
        if takes_part[j] == 0 {
            return false;
        }
        let d = [p.x[j] - p.x[i], p.y[j] - p.y[i], p.z[j] - p.z[i]];
        let r2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
        if r2 < near2 {
            let along = d[0] * n[0] + d[1] * n[1] + d[2] * n[2];
            let across2 = (r2 - along * along).max(0.0);
            along > 0.0 && across2 < along * along
        } else {
            let e = [p.x[j] - t[0], p.y[j] - t[1], p.z[j] - t[2]];
            e[0] * e[0] + e[1] * e[1] + e[2] * e[2] < h * h
        }
    })
}

/// The Dirichlet value of each surface particle (0 elsewhere): p = 0 holds on the free surface,
/// which lies half a spacing beyond the surface particles' centres (each particle stands for a
/// cube Δs wide), so the particle carries the pressure of that half spacing,
/// `p_s = (Δs/2) ∂p/∂m` along the inward normal `m = Σ_j ∇_i W_ij / |…|` (W' < 0, so the sum points into the fluid) (over the neighbours
/// that take part). In the fluid `∇p = ρ(g − a)`: at rest `p_s = −ρ (g·n) Δs/2`, in free fall
/// 0. The fluid's acceleration is not known before the solve, so `∂p/∂m` is the least-squares
/// slope of the last step's pressures (in `p.pressure`, the PPE's warm start) along m over the
/// fluid neighbours, `Σ_j W_ij (p_j − p_i)(x_j − x_i)·m / Σ_j W_ij ((x_j − x_i)·m)²`; it is
/// kept within `[0, ρ (−g·n) Δs/2]` (no tension; and no more than hydrostatic, so the explicit
/// lag cannot feed an impact's pressure back into the surface). Without this the whole
/// pressure field is ρgΔs/2 short: the walls of a tank 0.3 m deep carried 3.3 % less than the
/// water's weight at Δs = 0.02 m and a floating box 4 cm deep 27 % less than ρgV, so it sank.
#[allow(clippy::too_many_arguments)]
pub fn surface_pressure(
    k: &Wendland,
    list: &NeighbourList,
    p: &Particles,
    takes_part: &[u8],
    flags: &[u8],
    density: f64,
    gravity: [f64; 3],
    out: &mut Vec<f64>,
) {
    out.resize(p.len(), 0.0);
    out.par_iter_mut()
        .enumerate()
        .with_min_len(4096)
        .for_each(|(i, o)| {
            *o = 0.0;
            if flags[i] != SURFACE || p.kind[i] != FLUID {
                return;
            }
            let mut s = [0.0; 3];
            for (j, q) in list.pairs(i) {
                if takes_part[j] == 0 {
                    continue;
                }
                let d = [p.x[i] - p.x[j], p.y[i] - p.y[j], p.z[i] - p.z[j]];
                let c = k.dw_over_r_at(q);
                (0..3).for_each(|a| s[a] += c * d[a]);
            }
            let norm = (s[0] * s[0] + s[1] * s[1] + s[2] * s[2]).sqrt();
            if !(norm > 0.0 && norm.is_finite()) {
                return;
            }
            // s = Σ_j ∇_i W_ij points into the fluid (W' < 0): m = s/|s|.
            let m = s.map(|v| v / norm);
            let hydrostatic = density * (gravity[0] * m[0] + gravity[1] * m[1] + gravity[2] * m[2]);
            let cap = hydrostatic * 0.5 * k.spacing;
            if cap <= 0.0 {
                return;
            }
            let (mut num, mut den) = (0.0, 0.0);
            for (j, q) in list.pairs(i) {
                if p.kind[j] != FLUID || j == i {
                    continue;
                }
                let d = [p.x[j] - p.x[i], p.y[j] - p.y[i], p.z[j] - p.z[i]];
                let dm = d[0] * m[0] + d[1] * m[1] + d[2] * m[2];
                let w = k.w_at(q);
                num += w * (p.pressure[j] - p.pressure[i]) * dm;
                den += w * dm * dm;
            }
            let slope = if den > 0.0 { num / den } else { 0.0 };
            *o = (0.5 * k.spacing * slope).clamp(0.0, cap);
        });
}
