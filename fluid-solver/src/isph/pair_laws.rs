//! The ISPH fluid–body pair laws, as force on body particle j from fluid particle i (the fluid
//! gets the reverse in the exchange's bookkeeping).
//!
//! Pressure on a body: pressure × area over the body's faces ([`body_faces`]), each body
//! particle's force `F_j = −Σ_faces max(0, p_j + ρ g·e Δs/2) e Δs²` (the faces e of its
//! lattice cell that no other body particle covers, p_j the Adami extrapolation onto it), shared
//! among its fluid neighbours i in proportion to Adami's weights, `F_ij = F_j W_ij / Σ_f W_fj`,
//! so the load and the reaction are one law (action = reaction pair by pair). A hydrostatic
//! field gives ρgV on a submerged box whatever the fluid–body gap: Adami's extrapolation is
//! exact for a linear field wherever the fluid sits. The symmetric pair term used before,
//! `V² (p_i + p_j^(i)) ∇_i W_ij`, gives ρgV only with the fluid exactly one spacing from the
//! body: a box held 0.25 Δs above its lattice site got 6.2 N for 9.0 N, and a box rising at
//! 0.02 m/s 10.3 → 12 N, since nothing in S2-8's fluid gradient holds the gap at Δs.
//!
//! Walls (and the wall-pressure sensors) keep the symmetric pair term, antisymmetric in the
//! pair, so the walls' loads sum to the water's weight; the fluid's own acceleration uses S2-8's
//! corrected difference form ([`super::operators::pressure_gradient`], which says why). Viscous,
//! with no-slip walls: the pair terms of [`super::operators::laplacian`]. The pair laws read the
//! per-pair pressure `p_i + Δp_ij` that fluid particle i's PPE saw ([`super::walls`]).
//!
//! With `pressure_gradient = "symmetric"` (case key, `schemas::case::fluid::PressureGradient`)
//! the fluid's gradient is the uncorrected symmetric form and [`symmetric_term`] is its pair term
//! with fluid and wall neighbours: the fluid's gradient sums it, and the walls' loads are V times
//! it (as with S2-8's). The pair laws are the same for both gradients. With a body
//! neighbour the fluid's pair term is the face law's share instead ([`face_share`], divided by
//! V), so a body's load and the fluid's reaction are still one function, and the load does not
//! depend on the fluid–body gap: with the symmetric term there too, a box held 0.25 Δs above its
//! lattice site read ρgV −14.7 % (its site −0.00 %); with the face share +0.86 % (site −0.08 %).
//! With `"conservative"` (the exact projection) a body's law is instead its completion of the
//! water's kernel sums ([`super::body_completion`]).

use super::body_completion::BodyCompletion;
use super::kernel::Wendland;
use super::neighbour_list::NeighbourList;
use super::walls::NeumannPair;
use crate::bodies::pair_law::{ExchangeScales, PairLaw};
use crate::particles::kind::{Kind, FLUID};
use crate::particles::Particles;
use rayon::prelude::*;

/// The symmetric form's term of fluid particle i's pressure gradient from neighbour j at
/// `d = x_i − x_j`, `q = |d| / r_e`: `t_ij = V (p_i + p_j^(i)) ∇_i W_ij` (the kernel
/// gradient corrected with `kernel_correction = "moment"`, [`super::kernel_correction`]), with p_j^(i) = p_j for a fluid
/// j and p_i + Δp_ij for a solid j (wall or body: its pressure as i's PPE saw it,
/// [`super::walls`]). The fluid's `⟨∇p⟩_i = Σ_j t_ij` ([`super::operators::pressure_gradient`]),
/// so the force on i from j is `−(m/ρ) t_ij = −V t_ij`, and the force on a solid j from i is
/// `V t_ij` ([`pressure`]); for two fluid particles `t_ij = −t_ji`, so momentum closes pair by
/// pair. The wall terms of surface water the PPE does not hold are completed by the walls
/// ([`super::surface_walls`]; with the symmetric forms only).
#[inline(always)]
pub fn symmetric_term(
    k: &Wendland,
    walls: &NeumannPair,
    i: usize,
    j: usize,
    d: [f64; 3],
    q: f64,
) -> [f64; 3] {
    let p = walls.p;
    if p.kind[j] == FLUID {
        return fluid_term(k, walls, (i, j), d, q, (p.pressure[i], p.pressure[j]));
    }
    wall_term(k, walls, (i, j), d, q, p.pressure[i])
}

/// The fluid part of [`symmetric_term`] with fluid particles i and j at pressures `(pi, pj)`:
/// `V (p_i + p_j) ∇_i W_ij`, its kernel gradient corrected as the step's
/// ([`super::kernel_correction`]).
#[inline(always)]
pub fn fluid_term(
    k: &Wendland,
    walls: &NeumannPair,
    (i, j): (usize, usize),
    d: [f64; 3],
    q: f64,
    (pi, pj): (f64, f64),
) -> [f64; 3] {
    let c = k.volume * k.dw_over_r_at(q) * (pi + pj);
    walls.vectors.fluid(i, j, d.map(|v| c * v))
}

/// The wall part of [`symmetric_term`] with fluid particle i at pressure `pi`:
/// `V (2 p_i + Δp_ij) ∇_i W_ij`, completed by the walls where i is surface water the PPE does
/// not hold ([`NeumannPair::completed`]).
#[inline(always)]
pub fn wall_term(
    k: &Wendland,
    walls: &NeumannPair,
    (i, j): (usize, usize),
    d: [f64; 3],
    q: f64,
    pi: f64,
) -> [f64; 3] {
    let c = k.volume * k.dw_over_r_at(q) * (2.0 * pi + walls.difference(i, j));
    walls.completed(i, walls.vectors.solid(i, d.map(|v| c * v)))
}

/// Fluid particle i's share of body particle j's face force at `q = r / r_e`,
/// `F_ij = F_j W(r) / Σ_f W_fj` (module doc): the force on j from i; 0 for a body particle
/// without a load (dry, or no fluid neighbour) and for any other particle.
#[inline(always)]
pub fn face_share(k: &Wendland, faces: &BodyFaces, j: usize, q: f64) -> [f64; 3] {
    match (faces.force.get(j), faces.weight.get(j)) {
        (Some(f), Some(&den)) if den > 0.0 => {
            let share = k.w_at(q) / den;
            f.map(|v| v * share)
        }
        _ => [0.0; 3],
    }
}

/// Each body particle's pressure force and the sum of its fluid neighbours' weights (both 0 for
/// other particles), in the present particle order.
#[derive(Debug, Clone, Default)]
pub struct BodyFaces {
    pub force: Vec<[f64; 3]>,
    pub weight: Vec<f64>,
    /// `E_j = Σ_faces e Δs²` and `H_j = Σ_faces ρ (g·e) (Δs/2) e Δs²`: the force without the
    /// faces' clamp at 0 is `−p_j E_j − H_j`, linear in the fluid's pressures
    /// ([`super::exact_projection`]).
    pub area: Vec<[f64; 3]>,
    pub hydro: Vec<[f64; 3]>,
}

impl BodyFaces {
    /// Σ_j F_j: the pressure load on all bodies together. The pair law shares each F_j among
    /// fluid neighbours with weights that sum to 1, so −Σ_j F_j is the reaction the fluid is
    /// booked with.
    pub fn total(&self) -> [f64; 3] {
        self.force
            .iter()
            .fold([0.0; 3], |s, f| [s[0] + f[0], s[1] + f[1], s[2] + f[2]])
    }
}

/// The pressure force on each wet body particle from its exposed faces (module doc), with the
/// fluid pressures and the velocities v* the step moves the fluid by. A face is exposed when
/// no body particle sits one spacing away across it: the lattice directions to the body
/// neighbours at Δs (±10 %) are the covered faces, and the opposite of a covered direction
/// whose own opposite is not covered is an exposed one (a body one particle thin along an axis
/// has neither and gets no load along it). A face's pressure is the extrapolated pressure
/// carried hydrostatically to the face's centre, never below 0 (no tension where the face is
/// above the water). Only the wet body particles (`takes_part`, of
/// [`super::free_surface::fill_flags`]) carry a load. (The fluid's gradient reads dry solids
/// too, since the change for drops on dry wall tops in [`super::operators::pressure_gradient`];
/// whether dry body particles should then carry a load is open. Loaded before that change, a box under a falling 8 cm cube of water took 230–450 N per step for 6 steps before
/// the water reached it, from the extrapolated impermeability term of the approaching surface
/// particles, while the water fell freely: 9.0 N s in 0.1 s where the water gave up 1.2 N s.)
pub fn body_faces(
    k: &Wendland,
    list: &NeighbourList,
    walls: &NeumannPair,
    takes_part: &[u8],
    out: &mut BodyFaces,
) {
    let p = walls.p;
    let body = Kind::Body.code();
    let (ds, r2max) = (k.spacing, k.radius * k.radius);
    let (g, rho) = (walls.gravity, walls.density);
    out.force.resize(p.len(), [0.0; 3]);
    out.weight.resize(p.len(), 0.0);
    out.area.resize(p.len(), [0.0; 3]);
    out.hydro.resize(p.len(), [0.0; 3]);
    (&mut out.force, &mut out.weight, &mut out.area, &mut out.hydro)
        .into_par_iter()
        .enumerate()
        .with_min_len(4096)
        .for_each(|(j, (force, weight, area, hydro))| {
            (*force, *weight, *area, *hydro) = ([0.0; 3], 0.0, [0.0; 3], [0.0; 3]);
            if p.kind[j] != body || takes_part[j] == 0 {
                return;
            }
            let (mut num, mut den) = (0.0, 0.0);
            let mut covered: Vec<[f64; 3]> = Vec::with_capacity(6);
            for &i in list.of(j) {
                let i = i as usize;
                let d = [p.x[i] - p.x[j], p.y[i] - p.y[j], p.z[i] - p.z[j]];
                let r2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
                if p.kind[i] == FLUID && r2 < r2max {
                    let w = k.w(r2.sqrt());
                    num += w * (p.pressure[i] + walls.difference(i, j));
                    den += w;
                } else if p.kind[i] == body && (r2 - ds * ds).abs() < 0.21 * ds * ds {
                    let r = r2.sqrt();
                    covered.push(d.map(|v| v / r));
                }
            }
            if den <= 0.0 {
                return;
            }
            let pj = num / den;
            let (mut f, mut e_sum, mut h_sum) = ([0.0; 3], [0.0; 3], [0.0; 3]);
            for u in &covered {
                let dot = |v: &[f64; 3]| u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
                if covered.iter().any(|v| dot(v) < -0.9) {
                    continue;
                }
                // Exposed face e = −u, its centre Δs/2 from the particle.
                let e = u.map(|v| -v);
                let head = rho * (g[0] * e[0] + g[1] * e[1] + g[2] * e[2]) * 0.5 * ds;
                let face = (pj + head).max(0.0);
                for a in 0..3 {
                    f[a] -= face * e[a] * ds * ds;
                    e_sum[a] += e[a] * ds * ds;
                    h_sum[a] += head * e[a] * ds * ds;
                }
            }
            (*force, *weight, *area, *hydro) = (f, den, e_sum, h_sum);
        });
}

/// Whatever the fluid's gradient: on a body particle j its share [`face_share`] of the face
/// force of [`body_faces`] (computed on the same state; with the symmetric gradient also the
/// fluid's pair term with j); on a wall particle `V t_ij` of [`symmetric_term`],
/// `V² (p_i + p_j^(i)) ∇_i W_ij` with p_j^(i) = p_i + Δp_ij the wall particle's pressure as fluid
/// particle i's PPE saw it ([`super::walls`]).
/// With the exact projection (`completion` given) a body particle j takes instead its share
/// `V t_i W_ij / Σ_w W_iw` of fluid particle i's body term ([`BodyCompletion`]).
pub fn pressure<'a>(
    k: &Wendland,
    walls: NeumannPair<'a>,
    faces: &'a BodyFaces,
    completion: Option<&'a BodyCompletion>,
) -> PairLaw<'a> {
    let k = *k;
    let p = walls.p;
    let body = Kind::Body.code();
    PairLaw::new(k.radius, move |i, j| {
        let d = [p.x[i] - p.x[j], p.y[i] - p.y[j], p.z[i] - p.z[j]];
        let r2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
        if !(r2 < k.radius * k.radius && r2 > 0.0) {
            return None;
        }
        if p.kind[j] == body {
            let q = k.q(r2.sqrt());
            return Some(match completion {
                Some(c) => {
                    let share = k.volume * c.share(&k, i, q);
                    c.term(i, p.pressure[i]).map(|t| share * t)
                }
                None => face_share(&k, faces, j, q),
            });
        }
        let t = symmetric_term(&k, &walls, i, j, d, k.q(r2.sqrt()));
        Some(t.map(|v| k.volume * v))
    })
}

/// `−m ν F_ij (v_j − v_i)`, F_ij = −2 V W'/r: the reverse of the fluid's viscous force from j.
pub fn viscous<'a>(k: &Wendland, scales: &ExchangeScales, p: &'a Particles) -> PairLaw<'a> {
    let k = *k;
    let m_nu = scales.particle_mass * scales.viscosity;
    PairLaw::new(k.radius, move |i, j| {
        let d = [p.x[j] - p.x[i], p.y[j] - p.y[i], p.z[j] - p.z[i]];
        let r2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
        if !(r2 < k.radius * k.radius && r2 > 0.0) {
            return None;
        }
        let c = m_nu * 2.0 * k.volume * k.dw_over_r(r2.sqrt());
        Some([
            c * (p.vx[j] - p.vx[i]),
            c * (p.vy[j] - p.vy[i]),
            c * (p.vz[j] - p.vz[i]),
        ])
    })
}
