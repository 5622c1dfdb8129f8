//! The symmetric forms' kernel gradients corrected by both particles' moment matrices
//! (`kernel_correction = "moment"`, docs/physics.md §4.15): each pair's `V ∇W_ij` becomes
//!
//! `a_ij = ½ (L_i + L_j) V ∇W_ij` (fluid j), `a_iw = L_i V ∇W_iw` (solid w),
//!
//! with `L_i = m_i⁻¹`, m_i the moment matrix `−Σ_j V (W'/r) d ⊗ d` over every listed neighbour
//! (S2-10 before its normalisation; I on the full lattice), in the water's interior away from
//! bodies: neither i nor any fluid neighbour on the free surface or beside a body (a body particle
//! among its neighbours), and λ_min(m_i) > [`LAMBDA_INNER`]. Elsewhere `L_i = I`. For two
//! fluid particles `a_ij = −a_ji`, so the pressure force stays antisymmetric pair by pair and
//! momentum closes as with the plain form (Bonet & Lok 1999 antisymmetrised their correction the
//! same way).
//!
//! Why: the plain symmetric gradient reads a linear field as `2 p_i S_i + m_i ∇p`. Where the
//! lattice is sheared, as under a gravity wave, m_i ≠ I, and the hydrostatic gradient ρg is read
//! with a sideways part of order ρ g times the strain: a force against the wave of the wave's own
//! order, whatever the resolution. A standing wave (a/d = 0.1, d/16,
//! `tests/standing_wave/mod.rs`) lost a quarter of its amplitude in the first quarter period and
//! half by the second swing; with the correction it reaches 0.98 A and keeps 0.93 A at the
//! second swing. Where the support is cut (the free surface) m_i⁻¹ would multiply the zero-order
//! term `2 p_i S_i` that holds the surface layer, as Bonet & Lok's correction everywhere did
//! (the tank failed within 0.02 s at 2.4 Δs, docs/notes/isph-momentum-and-divergence.md): there
//! the plain gradient stays. Measured on the hydrostatic tank (`tests/isph.rs`): corrected
//! wherever λ_min > 0.9, the top corner particle reached 1.85e-3 m/s at 0.2 s (bound 1.71e-3, plain
//! 1.04e-3); with the surface band left out, 1.04e-3, and the wave's first swing 0.981 A instead of
//! 0.989. Beside a body the completion ([`super::body_completion`]) already makes each row exact;
//! corrected there too, a box held 5 mm above its lattice site read ρgV +1.30 % (plain −0.01 %),
//! with the body's neighbours left out +0.32 %, with their fluid neighbours too +0.06 %
//! (`tests/isph_bodies.rs`).

use super::free_surface::{LAMBDA_INNER, SURFACE};
use super::kernel::Wendland;
use super::neighbour_list::NeighbourList;
use crate::neighbours::moments::{inverse, smallest_eigenvalue_up_to, times, Matrix3, OuterSum, IDENTITY};
use crate::particles::kind::{Kind, FLUID};
use crate::particles::Particles;
use rayon::prelude::*;

/// `L_i` of the module doc for every particle into `out` (the identity for solids, near the free
/// surface and near bodies); `surface` holds the step's surface flags; `beside_body` is scratch.
pub fn corrections(
    k: &Wendland,
    list: &NeighbourList,
    p: &Particles,
    surface: &[u8],
    beside_body: &mut Vec<bool>,
    out: &mut Vec<Matrix3>,
) {
    let body = Kind::Body.code();
    beside_body.resize(p.len(), false);
    beside_body
        .par_iter_mut()
        .enumerate()
        .with_min_len(4096)
        .for_each(|(i, b)| *b = list.of(i).iter().any(|&j| p.kind[j as usize] == body));
    let beside_body = &*beside_body;
    // Near the free surface or a body: the plain gradient stays (module doc).
    let edge = |i: usize| surface.get(i) == Some(&SURFACE) || beside_body[i];
    out.resize(p.len(), IDENTITY);
    out.par_iter_mut()
        .enumerate()
        .with_min_len(512)
        .for_each(|(i, l)| {
            *l = IDENTITY;
            if p.kind[i] != FLUID || edge(i) {
                return;
            }
            let mut m = OuterSum::default();
            for (j, q) in list.pairs(i) {
                if p.kind[j] == FLUID && edge(j) {
                    return;
                }
                let d = [p.x[i] - p.x[j], p.y[i] - p.y[j], p.z[i] - p.z[j]];
                m.add(-k.volume * k.dw_over_r_at(q), d);
            }
            let m = m.matrix();
            if smallest_eigenvalue_up_to(&m, LAMBDA_INNER) > LAMBDA_INNER {
                if let Some(inv) = inverse(&m) {
                    *l = inv;
                }
            }
        });
}

/// The pair vectors of the module doc from the step's `L` (empty: no correction, every pair's
/// vector is its plain kernel gradient).
#[derive(Debug, Clone, Copy)]
pub struct PairVectors<'a>(pub &'a [Matrix3]);

impl PairVectors<'_> {
    /// `a_ij` for fluid i and fluid j, with `v = V ∇W_ij` (times any scalar).
    #[inline(always)]
    pub fn fluid(&self, i: usize, j: usize, v: [f64; 3]) -> [f64; 3] {
        if self.0.is_empty() {
            return v;
        }
        let (a, b) = (times(&self.0[i], v), times(&self.0[j], v));
        std::array::from_fn(|c| 0.5 * (a[c] + b[c]))
    }

    /// `a_iw` for fluid i and solid w, with `v = V ∇W_iw` (times any scalar).
    #[inline(always)]
    pub fn solid(&self, i: usize, v: [f64; 3]) -> [f64; 3] {
        if self.0.is_empty() {
            return v;
        }
        times(&self.0[i], v)
    }

    /// [`Self::fluid`] or [`Self::solid`] by whether j `is_fluid`.
    #[inline(always)]
    pub fn pair(&self, i: usize, j: usize, is_fluid: bool, v: [f64; 3]) -> [f64; 3] {
        if is_fluid {
            self.fluid(i, j, v)
        } else {
            self.solid(i, v)
        }
    }
}
