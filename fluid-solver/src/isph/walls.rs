//! ISPH walls: particle walls (the same wall, dummy and body particles E-MPS uses) whose pressure
//! is extrapolated from the fluid in the manner of Adami, Hu & Adams (2012, "A generalized wall
//! boundary condition for smoothed particle hydrodynamics", J. Comput. Phys. 231, eq. 27):
//! `p_w = Σ_f W_wf (p_f + Δp_fw) / Σ_f W_wf`.
//!
//! Why this model and not S2's polygon wall (IERP, Omura et al. 2023): the particle walls exist
//! already for E-MPS, bodies, gates and inflow strips, so both methods share one layout, one
//! contact model and one body exchange; IERP would need a polygon mesh and distance functions
//! for every wall, gate and moving body. Adami's extrapolation gives what IERP is there for: the
//! hydrostatic pressure at the wall (no spurious gap or pile-up at the floor) and no
//! penetration, with free or no slip chosen separately in the viscous term.
//!
//! The pressure difference across a fluid–wall pair is the Neumann condition of the projection,
//! `∂p/∂n = (ρ/Δt)(v* − v_w)·n`, written per pair:
//! `Δp_fw = ρ g·(x_w − x_f) + (ρ/Δt) ((u_f − v_w)·n_w) (n_w·(x_w − x_f))`, where
//! u_f = v*_f − gΔt is the fluid velocity before gravity and n_w the wall's normal into the
//! fluid. The first term is Adami's hydrostatic term (the wall's own acceleration is not known in
//! the fluid and is left out); the second removes, within the step, the fluid's velocity normal
//! to the wall relative to it (impermeability; only the normal part, so tangential flow feels no
//! wall pressure). The PPE takes Δp_fw as known differences (so its matrix stays symmetric), and
//! the pressure gradient reads the same per-pair wall pressure p_f + Δp_fw, so the PPE and the
//! velocity correction see one wall. The extrapolation above gives each wall particle one
//! pressure for the outputs and probes. (A first version took only approaching fluid, `min(0, ·)`;
//! it let water drift off the tank's edges.)
//!
//! No tension at the free surface: for a fluid particle on the free surface (p = 0 there) only
//! the approaching part `min(0, (u_f − v_w)·n_w)` enters, so the wall pushes it but does not hold
//! it back when it leaves. Water under the surface cannot leave a wall without leaving a void,
//! and the wall holds it (the drift above); water at the surface has air beside it and
//! separates freely, as a jet leaving a wall's edge does. With the pull, the run-up jet of the
//! CI dam break (`tests/isph_dam_break.rs`) was drawn outwards over the slab's side walls' top
//! edges, whose normals tilt upwards: 36 of 800 particles were thrown over them by t = 1.5 s
//! once the pressure gradient took the dry wall particles in ([`super::operators`]).
//!
//! No push before contact: a surface particle is pushed only by the part of its approach that
//! would carry it, within the step, closer than Δs/2 to the wall's face (where a particle
//! standing for a cube Δs wide touches it): `u_n → min(0, u_n + gap/Δt)`, the gap measured
//! along n_w from the face, which lies [`depths`] in front of w. Without it a surface particle
//! of the surge still 1–1.5 Δs from the far wall, with air between, was stopped in one step,
//! and the wall particles beside it, extrapolated from it alone, read ρ u d/Δt (20–50 kPa for
//! 3–5 steps): on the `isph_vs_emps` scene this was 68 % of the squared step-to-step change of
//! the far-wall probe at Δs = L/20; with the gap the probe's RMS change falls from 1 567 to
//! 693 Pa (L/20) and from 2 513 to 1 639 Pa (L/10). Near a corner the normals n_w (kernel sums
//! over the solid neighbours) tilt, so the gap there is only approximate; a particle that
//! arrives closer than Δs/2 is in contact at the next step and stopped then.

use super::free_surface::SURFACE;
use super::kernel::Wendland;
use super::neighbour_list::NeighbourList;
use crate::kind::{DUMMY, FLUID, WALL};
use crate::particles::Particles;
use crate::physics::Physics;
use crate::vector_field::VectorField;
use rayon::prelude::*;

/// The normal of every solid particle with fluid near it, into the fluid:
/// `n_w = −Σ_{solid j} ∇_w W_wj / |…|` (0 for fluid particles and isolated solids).
pub fn normals(k: &Wendland, list: &NeighbourList, p: &Particles, out: &mut VectorField) {
    out.resize(p.len());
    (&mut out.x, &mut out.y, &mut out.z)
        .into_par_iter()
        .enumerate()
        .with_min_len(512)
        .for_each(|(w, (nx, ny, nz))| [*nx, *ny, *nz] = normal(k, list, p, w));
}

/// [`normals`] of particle `w`.
fn normal(k: &Wendland, list: &NeighbourList, p: &Particles, w: usize) -> [f64; 3] {
    let mut g = [0.0; 3];
    if p.kind[w] != FLUID {
        for (j, q) in list.pairs(w) {
            if p.kind[j] == FLUID {
                continue;
            }
            let d = [p.x[w] - p.x[j], p.y[w] - p.y[j], p.z[w] - p.z[j]];
            let c = k.dw_over_r_at(q);
            (0..3).for_each(|a| g[a] += c * d[a]);
        }
    }
    let norm = (g[0] * g[0] + g[1] * g[1] + g[2] * g[2]).sqrt();
    if norm > 0.0 {
        [-g[0] / norm, -g[1] / norm, -g[2] / norm]
    } else {
        [0.0; 3]
    }
}

/// The depth of every solid particle with fluid near it behind its wall's face, along its
/// normal: `Δs/2 + max(0, max_j n_w·(x_j − x_w))` over its solid neighbours j (the face lies
/// Δs/2 beyond the outermost layer); Δs/2 for the others.
pub fn depths(k: &Wendland, list: &NeighbourList, p: &Particles, normals: &VectorField, out: &mut Vec<f64>) {
    out.resize(p.len(), 0.0);
    out.par_iter_mut()
        .enumerate()
        .with_min_len(512)
        .for_each(|(w, depth)| {
            let n = [normals.x[w], normals.y[w], normals.z[w]];
            *depth = depth_of(k, list, p, n, w);
        });
}

/// [`depths`] of particle `w` with normal `n`.
fn depth_of(k: &Wendland, list: &NeighbourList, p: &Particles, n: [f64; 3], w: usize) -> f64 {
    let mut outer: f64 = 0.0;
    if p.kind[w] != FLUID {
        for &j in list.of(w) {
            let j = j as usize;
            if p.kind[j] != FLUID {
                let d = [p.x[j] - p.x[w], p.y[j] - p.y[w], p.z[j] - p.z[w]];
                outer = outer.max(d[0] * n[0] + d[1] * n[1] + d[2] * n[2]);
            }
        }
    }
    0.5 * k.spacing + outer
}

/// The normals and depths of the solid particles, kept by particle id while every solid is fixed
/// (walls and dummies only: no body, gate or inflow strip). A fixed solid's solid neighbours
/// never change, nor their order in its list (the cell sort is stable and fixed particles keep
/// their cells), so its normal and depth come out as the same bits every step; at S2's scale
/// computing them took 9 ms of a 270 ms step.
#[derive(Debug, Clone, Default)]
struct FixedSolids {
    normal: Vec<[f64; 3]>,
    depth: Vec<f64>,
    known: Vec<bool>,
}

/// What the pair differences read of a step besides the particles: the solids' normals into the
/// fluid ([`normals`]) and depths behind their faces ([`depths`]), and the surface flags of the
/// step's PPE assembly.
#[derive(Debug, Clone, Default)]
pub struct WallFields {
    pub normals: VectorField,
    pub surface: Vec<u8>,
    pub depth: Vec<f64>,
    fixed: FixedSolids,
}

impl WallFields {
    /// [`normals`] and [`depths`] of the particles in their present order: those of a solid with
    /// fluid near it taken from [`FixedSolids`] once known there, while every solid is fixed.
    pub fn update_geometry(&mut self, k: &Wendland, list: &NeighbourList, p: &Particles) {
        if !p.kind.par_iter().all(|&c| matches!(c, FLUID | WALL | DUMMY)) {
            normals(k, list, p, &mut self.normals);
            depths(k, list, p, &self.normals, &mut self.depth);
            return;
        }
        let ids = p.id.par_iter().max().map_or(0, |&m| m as usize + 1);
        let cache = &mut self.fixed;
        if cache.known.len() < ids {
            cache.known.resize(ids, false);
            cache.normal.resize(ids, [0.0; 3]);
            cache.depth.resize(ids, 0.0);
        }
        self.normals.resize(p.len());
        self.depth.resize(p.len(), 0.0);
        // A solid with water near (it has a list): its geometry is read from, or recorded in, the cache.
        let near_water = |w: usize| p.kind[w] != FLUID && !list.of(w).is_empty();
        let known = &cache.known;
        let (normal_of, depth_by_id) = (&cache.normal, &cache.depth);
        let new = (
            &mut self.normals.x,
            &mut self.normals.y,
            &mut self.normals.z,
            &mut self.depth,
        )
            .into_par_iter()
            .enumerate()
            .with_min_len(512)
            .map(|(w, (nx, ny, nz, depth))| {
                let id = p.id[w] as usize;
                let near = near_water(w);
                let (n, d, new) = if near && known[id] {
                    (normal_of[id], depth_by_id[id], 0)
                } else {
                    let n = normal(k, list, p, w);
                    (n, depth_of(k, list, p, n, w), usize::from(near))
                };
                [*nx, *ny, *nz] = n;
                *depth = d;
                new
            })
            .sum::<usize>();
        if new > 0 {
            for w in 0..p.len() {
                let id = p.id[w] as usize;
                if near_water(w) && !cache.known[id] {
                    cache.known[id] = true;
                    cache.normal[id] = [self.normals.x[w], self.normals.y[w], self.normals.z[w]];
                    cache.depth[id] = self.depth[w];
                }
            }
        }
    }

    /// The pair differences for a step of `dt` with v* in `p`.
    pub fn pair<'a>(&'a self, physics: &Physics, spacing: f64, p: &'a Particles, dt: f64) -> NeumannPair<'a> {
        NeumannPair {
            density: physics.density,
            gravity: physics.gravity,
            dt,
            p,
            normals: &self.normals,
            surface: &self.surface,
            depth: &self.depth,
            spacing,
        }
    }
}

/// What a pair difference needs: ρ, g, Δt, the velocities before gravity u = v* − gΔt of the
/// fluid, the wall normals and the free-surface flags of the step.
pub struct NeumannPair<'a> {
    pub density: f64,
    pub gravity: [f64; 3],
    pub dt: f64,
    pub p: &'a Particles,
    pub normals: &'a VectorField,
    /// [`SURFACE`] for the fluid particles on the free surface (empty: none).
    pub surface: &'a [u8],
    /// Each solid particle's depth behind its wall's face ([`depths`]; empty: none).
    pub depth: &'a [f64],
    /// Δs [m].
    pub spacing: f64,
}

impl NeumannPair<'_> {
    /// `Δp_fw = p_w − p_f` for fluid f (moving with v*) and solid w (module doc).
    #[inline]
    pub fn difference(&self, f: usize, w: usize) -> f64 {
        let p = self.p;
        let d = [p.x[w] - p.x[f], p.y[w] - p.y[f], p.z[w] - p.z[f]];
        let g = self.gravity;
        let hydro = self.density * (g[0] * d[0] + g[1] * d[1] + g[2] * d[2]);
        let n = [self.normals.x[w], self.normals.y[w], self.normals.z[w]];
        let u = [
            p.vx[f] - g[0] * self.dt - p.vx[w],
            p.vy[f] - g[1] * self.dt - p.vy[w],
            p.vz[f] - g[2] * self.dt - p.vz[w],
        ];
        let mut un = u[0] * n[0] + u[1] * n[1] + u[2] * n[2];
        let dn = d[0] * n[0] + d[1] * n[1] + d[2] * n[2];
        if self.surface.get(f) == Some(&SURFACE) {
            // No tension at the free surface, and no push before contact (module doc): the gap
            // is how far f's centre may still move towards the face, to Δs/2 from it.
            let depth = self.depth.get(w).copied().unwrap_or(0.5 * self.spacing);
            let gap = (-dn - depth - 0.5 * self.spacing).max(0.0);
            un = (un + gap / self.dt).min(0.0);
        }
        hydro + self.density / self.dt * un * dn
    }
}

/// Adami's extrapolation onto every solid particle (module doc) from the fluid pressures in
/// `pair.p`: (particle, pressure) for each solid, 0 for those without fluid neighbours.
pub fn extrapolated(k: &Wendland, list: &NeighbourList, pair: &NeumannPair) -> Vec<(usize, f64)> {
    let p = pair.p;
    (0..p.len())
        .into_par_iter()
        .with_min_len(512)
        .filter(|&w| p.kind[w] != FLUID)
        .map(|w| {
            let (mut num, mut den) = (0.0, 0.0);
            for (f, q) in list.pairs(w) {
                if p.kind[f] != FLUID {
                    continue;
                }
                let wf = k.w_at(q);
                num += wf * (p.pressure[f] + pair.difference(f, w));
                den += wf;
            }
            (w, if den > 0.0 { num / den } else { 0.0 })
        })
        .collect()
}
