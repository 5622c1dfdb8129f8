//! The walls' share of the support of free-surface water that the PPE does not hold, with the
//! symmetric gradients (`pressure_gradient = "symmetric"`, `"conservative"`): there the walls
//! complete the support, as a body does under water ([`super::body_completion`]).
//!
//! A particle on the free surface has p = 0, and so do its surface neighbours. Where it has an
//! unknown of the PPE among its neighbours, the PPE holds it: pressing down, it raises their
//! pressure. Where it has none (a sheet of water one particle deep, a drop), the symmetric gradient
//! `Σ_j V (p_i + p_j) ∇W_ij + Σ_w V (2 p_i + Δp_iw) ∇W_iw` holds it on a wall by the walls'
//! Neumann differences Δp_iw alone ([`super::walls`]): their sum is `N_w a` for a linear field
//! `a` (the hydrostatic ρg; the velocity part likewise along each wall's normal), with
//! `N_w = −Σ_w V (W'/r) d ⊗ d` the walls' first-order sum, half of the identity for a flat wall
//! at the lattice's distance. So a sheet one particle deep on a floor carried half its weight,
//! sank to 0.3 Δs above the floor's face within 0.4 s and put a particle through it at 1.9 s
//! (Δs = 0.02 m, `tests/wall_top.rs`; S2-8's corrected gradient carries it whole by its moment
//! matrix). For such a particle i each wall term t_iw becomes `M_i t_iw` with
//!
//! `M_i = (I − N_f) N_w⁻¹`,
//!
//! N_f the fluid neighbours' first-order sum: the walls complete what the fluid leaves missing,
//! so the sum is `(I − N_f) a`, exact for a linear field. Only where `λ_min(N_w) ≥`
//! [`MIN_WALL_SHARE`] (a wall that is only grazed stands for nothing more). Measured alternatives
//! (same sheet; hydrostatic tank, `tests/isph.rs`):
//! - every surface particle beside a wall, its terms scaled along the walls' direction by
//!   `n·(I − N_f) n / n·N_w n`: the tank's top corner particles, held by the PPE already, rose at
//!   7e-3 m/s (bound 1.7e-3); only the components along n scaled: the tank held, but the sheet's
//!   particles at the tank's edges (n tilted) still sank 1.1 cm in 4 s;
//! - the velocity part alone scaled: the sheet sank as before (the velocity part leaves gravity's
//!   increment to the hydrostatic part).
//!
//! The walls' loads take the same terms, so momentum still closes; these particles are no PPE
//! unknowns, so the exact projection's matrix is unchanged (only its known part).

use super::free_surface::SURFACE;
use super::kernel::Wendland;
use super::neighbour_list::NeighbourList;
use crate::neighbours::moments::{inverse, smallest_eigenvalue, times, OuterSum, IDENTITY};
use crate::particles::kind::{Kind, FLUID};
use crate::particles::Particles;
use rayon::prelude::*;

/// The least `λ_min(N_w)` at which the walls complete a particle's support (a flat wall at the
/// lattice's distance gives about 0.3 at a support of 2.0 Δs, its tangential directions sharing
/// the moment with the particle's own plane).
pub const MIN_WALL_SHARE: f64 = 0.1;

/// `M_i` of the module doc for every particle into `out` (all zero where the terms stay as
/// they are); `surface` holds the step's surface flags.
pub fn completions(
    k: &Wendland,
    list: &NeighbourList,
    p: &Particles,
    surface: &[u8],
    out: &mut Vec<[[f64; 3]; 3]>,
) {
    let body = Kind::Body.code();
    out.resize(p.len(), [[0.0; 3]; 3]);
    out.par_iter_mut()
        .enumerate()
        .with_min_len(512)
        .for_each(|(i, m)| {
            *m = [[0.0; 3]; 3];
            if p.kind[i] != FLUID || surface.get(i) != Some(&SURFACE) {
                return;
            }
            let (mut fluid, mut wall) = (OuterSum::default(), OuterSum::default());
            for (j, q) in list.pairs(i) {
                if p.kind[j] == FLUID && surface.get(j) != Some(&SURFACE) {
                    return; // the PPE holds it
                }
                if p.kind[j] == body {
                    continue;
                }
                let d = [p.x[i] - p.x[j], p.y[i] - p.y[j], p.z[i] - p.z[j]];
                let sum = if p.kind[j] == FLUID { &mut fluid } else { &mut wall };
                sum.add(-k.volume * k.dw_over_r_at(q), d);
            }
            let (fluid, wall) = (fluid.matrix(), wall.matrix());
            if smallest_eigenvalue(&wall) < MIN_WALL_SHARE {
                return;
            }
            let Some(inv) = inverse(&wall) else {
                return;
            };
            for (r, row) in m.iter_mut().enumerate() {
                for (s, v) in row.iter_mut().enumerate() {
                    *v = (0..3).map(|e| (IDENTITY[r][e] - fluid[r][e]) * inv[e][s]).sum();
                }
            }
        });
}

/// Wall term `t` with a particle's `m` of [`completions`] applied (`t` itself where m is zero).
#[inline(always)]
pub fn completed(t: [f64; 3], m: &[[f64; 3]; 3]) -> [f64; 3] {
    if m[0][0] == 0.0 && m[1][1] == 0.0 && m[2][2] == 0.0 {
        return t;
    }
    times(m, t)
}
