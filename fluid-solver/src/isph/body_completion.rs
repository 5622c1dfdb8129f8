//! The bodies' pressure law of the exact projection (`pressure_gradient = "conservative"`): a
//! body completes the kernel sums of the fluid particles beside it, so that under water each
//! such particle's symmetric gradient is exact for a linear pressure field wherever the body
//! stands relative to the fluid's lattice.
//!
//! Fluid particle i's symmetric gradient over its fluid and wall neighbours j is, for a field
//! `p_j = p_i + a·(x_j − x_i)` (walls through their Neumann differences),
//! `Σ_j V (p_i + p_j) ∇W_ij = 2 p_i S_i + N_i a` with `S_i = Σ_j V ∇W_ij` (0 in a full
//! support) and `N_i = −Σ_j V (W'/r) d_ij ⊗ d_ij` (I in a full support, the kernel being
//! renormalised on the lattice). The body's term is `t_i = 2 p_i B_i + h_i`:
//!
//! - under water (i and its fluid neighbours all PPE unknowns, none on the free surface):
//!   `B_i = −S_i`, `h_i = (I − N_i) ρ g`, the whole of what the support misses, which is the
//!   body's there;
//! - beside the free surface (i or a fluid neighbour on it), where air misses too: the body's own
//!   pair sums, `b_i = Σ_{body w} V ∇W_iw` and `h_i^b = Σ_w V ρ g·(x_w − x_i) ∇W_iw` (the walls'
//!   term of [`super::pair_laws::symmetric_term`] without its velocity part), scaled to complete
//!   the support along the body's direction `n_i = b_i/|b_i|`: `B_i = β b_i`,
//!   `β = max(0, −S_i·n_i)/|b_i|`, `h_i = α h_i^b`, `α = n_i·(I − N_i) n_i / n_i·N_b n_i` (N_b the
//!   body's N); on the free surface itself (p = 0 there) `α = β = 1`.
//!
//! With `kernel_correction = "moment"` every sum takes the pairs' corrected vectors
//! ([`super::kernel_correction`]), so the completion stays exact for the corrected gradient.
//!
//! The force on i is `−V t_i` and the body takes `+V t_i`, shared among i's body neighbours w by
//! `W_iw / Σ_w' W_iw'`, so action equals reaction pair by pair. In the exact projection
//! `2 p_i B_i` is the body's part of G and `(D u)_i` gains `2 (u_i − ū_i)·B_i` (ū_i the body
//! neighbours' velocity by the same weights): a body moving with the water adds no divergence.
//!
//! Why (held 12 cm box in still water, `tests/isph_bodies.rs`; floating box,
//! `tests/tests/isph_floating.rs`; 30 Nov 2026):
//! - the walls' pair term on a body gives each fluid particle a force that grows as the body comes
//!   closer than the lattice's spacing, in proportion to the absolute pressure: the box held a
//!   quarter spacing above its lattice site read ρgV −12 %; the completion under water reads
//!   −0.01 % there (−0.00 % at the site), the water beside it moving at 1.4e-2 m/s at most;
//! - the face law (pressure × area shared by W) read ρgV +4.8 % there but pushed water in front of
//!   one face along another face's normal at a corner, which no pressure field balances: the
//!   water at the box's corner ran at 0.22 m/s (docs/notes/isph-exact-projection.md);
//! - the whole completion beside the free surface also completes the air, as hydrostatic water
//!   with negative pressure above the surface: the floating box sank to a mean 1 cm below its
//!   equilibrium; the body's own sums unscaled there left its draft 6.5 % deep, scaled 1.3 %
//!   shallow; scaled under water too, the off-site box read +16 % (at its corners n_i is not the
//!   direction of the missing sums).

use super::kernel::Wendland;
use super::kernel_correction::PairVectors;
use super::neighbour_list::NeighbourList;
use crate::neighbours::moments::IDENTITY;
use crate::particles::kind::{Kind, FLUID};
use crate::particles::Particles;
use rayon::prelude::*;

/// Each fluid particle's body term (module doc), 0 for particles without a body neighbour.
#[derive(Debug, Clone, Default)]
pub struct BodyCompletion {
    /// B_i, the coefficient of `2 p_i`.
    pub zero: Vec<[f64; 3]>,
    /// h_i, the known first-order part.
    pub first: Vec<[f64; 3]>,
    /// `Σ_{body w} W_iw`, the denominator of the body particles' shares.
    pub weight: Vec<f64>,
    /// ū_i, the body neighbours' velocity by the shares.
    pub velocity: Vec<[f64; 3]>,
    /// Whether any fluid particle has a body neighbour.
    any: bool,
}

impl BodyCompletion {
    /// Computes the terms of the present positions, with the walls' hydrostatic gradient
    /// `rho_g` = ρ g (the gravity vector times the density); `unknown(i)` says whether fluid
    /// particle i is one of the PPE's unknowns (not on the free surface).
    pub fn update(
        &mut self,
        k: &Wendland,
        list: &NeighbourList,
        p: &Particles,
        rho_g: [f64; 3],
        unknown: impl Fn(usize) -> bool + Sync,
        vectors: PairVectors,
    ) {
        let n = p.len();
        self.zero.resize(n, [0.0; 3]);
        self.first.resize(n, [0.0; 3]);
        self.weight.resize(n, 0.0);
        self.velocity.resize(n, [0.0; 3]);
        let body = Kind::Body.code();
        if !p.kind.par_iter().any(|&c| c == body) {
            self.zero.fill([0.0; 3]);
            self.first.fill([0.0; 3]);
            self.any = false;
            return;
        }
        self.any = (
            &mut self.zero,
            &mut self.first,
            &mut self.weight,
            &mut self.velocity,
        )
            .into_par_iter()
            .enumerate()
            .with_min_len(512)
            .map(|(i, (zero, first, weight, velocity))| {
                (*zero, *first, *weight, *velocity) = ([0.0; 3], [0.0; 3], 0.0, [0.0; 3]);
                if p.kind[i] != FLUID || !list.of(i).iter().any(|&j| p.kind[j as usize] == body) {
                    return false;
                }
                let mut sums = Sums::default();
                let mut near_air = !unknown(i);
                for (j, q) in list.pairs(i) {
                    let d = [p.x[i] - p.x[j], p.y[i] - p.y[j], p.z[i] - p.z[j]];
                    let c = k.volume * k.dw_over_r_at(q);
                    let v = vectors.pair(i, j, p.kind[j] == FLUID, d.map(|x| c * x));
                    if p.kind[j] == body {
                        let w = k.w_at(q);
                        sums.weight += w;
                        sums.velocity[0] += w * p.vx[j];
                        sums.velocity[1] += w * p.vy[j];
                        sums.velocity[2] += w * p.vz[j];
                        let dp = -(rho_g[0] * d[0] + rho_g[1] * d[1] + rho_g[2] * d[2]);
                        add(&mut sums.body, &mut sums.body_moment, v, d);
                        (0..3).for_each(|a| sums.body_head[a] += dp * v[a]);
                    } else {
                        near_air |= p.kind[j] == FLUID && !unknown(j);
                        add(&mut sums.rest, &mut sums.rest_moment, v, d);
                    }
                }
                if sums.weight <= 0.0 {
                    return false;
                }
                (*zero, *first) = if near_air {
                    sums.scaled(unknown(i))
                } else {
                    sums.complete(rho_g)
                };
                *weight = sums.weight;
                *velocity = sums.velocity.map(|v| v / sums.weight);
                true
            })
            .reduce(|| false, |a, b| a || b);
    }

    /// Whether any fluid particle has a body neighbour (the passes over bodies are skipped
    /// otherwise).
    pub fn any(&self) -> bool {
        self.any
    }

    /// Fluid particle i's body term `t_i = 2 p_i B_i + h_i` (module doc).
    #[inline(always)]
    pub fn term(&self, i: usize, pressure: f64) -> [f64; 3] {
        let (b, h) = (self.zero[i], self.first[i]);
        [
            2.0 * pressure * b[0] + h[0],
            2.0 * pressure * b[1] + h[1],
            2.0 * pressure * b[2] + h[2],
        ]
    }

    /// Body particle w's share of fluid particle i's term at `q = r_iw / r_e`: `W_iw / Σ W`.
    #[inline(always)]
    pub fn share(&self, k: &Wendland, i: usize, q: f64) -> f64 {
        let den = self.weight[i];
        if den > 0.0 {
            k.w_at(q) / den
        } else {
            0.0
        }
    }
}

/// One fluid particle's kernel sums (module doc).
#[derive(Default)]
struct Sums {
    /// S_i and N_i over the fluid and wall neighbours.
    rest: [f64; 3],
    rest_moment: [[f64; 3]; 3],
    /// b_i, N_b and h_i^b over the body neighbours.
    body: [f64; 3],
    body_moment: [[f64; 3]; 3],
    body_head: [f64; 3],
    /// Σ_w W_iw and Σ_w W_iw u_w.
    weight: f64,
    velocity: [f64; 3],
}

impl Sums {
    /// `(B_i, h_i) = (−S_i, (I − N_i) ρ g)`: the whole of what the support misses.
    fn complete(&self, rho_g: [f64; 3]) -> ([f64; 3], [f64; 3]) {
        let mut h = [0.0; 3];
        for (a, h) in h.iter_mut().enumerate() {
            *h = (0..3)
                .map(|e| (IDENTITY[a][e] - self.rest_moment[a][e]) * rho_g[e])
                .sum();
        }
        (self.rest.map(|v| -v), h)
    }

    /// `(β b_i, α h_i^b)`, the body's own sums scaled to complete the support along n_i, or
    /// unscaled when `scale` is false (on the free surface).
    fn scaled(&self, scale: bool) -> ([f64; 3], [f64; 3]) {
        let b = self.body;
        let norm = (b[0] * b[0] + b[1] * b[1] + b[2] * b[2]).sqrt();
        let (mut beta, mut alpha) = (1.0, 1.0);
        if scale && norm > 0.0 {
            let n = b.map(|v| v / norm);
            let s = self.rest;
            beta = (-(s[0] * n[0] + s[1] * n[1] + s[2] * n[2]) / norm).max(0.0);
            let (mut missing, mut filled) = (0.0, 0.0);
            for a in 0..3 {
                for e in 0..3 {
                    missing += n[a] * (IDENTITY[a][e] - self.rest_moment[a][e]) * n[e];
                    filled += n[a] * self.body_moment[a][e] * n[e];
                }
            }
            if filled > 0.0 {
                alpha = (missing / filled).max(0.0);
            }
        }
        (b.map(|v| beta * v), self.body_head.map(|v| alpha * v))
    }
}

/// Adds a neighbour's kernel-gradient vector `v` (`V ∇W_ij = c d`, or its correction) to a
/// zero-order sum and `−v ⊗ d` to a moment.
#[inline(always)]
fn add(sum: &mut [f64; 3], moment: &mut [[f64; 3]; 3], v: [f64; 3], d: [f64; 3]) {
    for a in 0..3 {
        sum[a] += v[a];
        for e in 0..3 {
            moment[a][e] -= v[a] * d[e];
        }
    }
}
