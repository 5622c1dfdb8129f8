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
//!
//! The faces' normals at a convex edge or corner: there a solid's own normal n_w is the mean of
//! its faces' normals (45° at a box's edge), so water running up a face past the edge read as
//! leaving that normal, and the velocity term pulled it back (tension): on the MARIN dam break
//! against a box (`cases/dam-break-obstacle`, SPHERIC test 2) the sensor P4, 2 cm below the
//! box's top edge on its face towards the water, read −1.9 / −2.3 kPa on average over 0.45 –
//! 0.6 / 0.6 – 0.8 s at Δs = 0.04 m (−1.6 / −0.8 kPa to 1.2 s at Δs = 0.02 m), where the
//! experiment reads +4.9 / +3.2 kPa. So for a solid w whose support holds less solid than
//! midway between a flat wall and an edge ([`convex_fill_limit`], flagged by [`convex`]) the
//! pair with fluid f takes the normal of the face f stands in front of
//! ([`NeumannPair::face_normal`]): P4 then reads +1.3 / +1.6 kPa at Δs = 0.04 m. (Dropping the
//! tension at convex solids instead gave +0.2 / +0.5 kPa there, but biased a held box's load:
//! fluctuations were then only pushed.) Beside a box held 5 mm off its lattice site in still
//! water (`tests/isph_bodies.rs`) the fastest fluid particle over 0.05 – 0.2 s fell from 8.9e-2
//! to 2.6e-2 m/s. This holds for walls and bodies with S2-8's corrected gradient,
//! and for walls only with the symmetric gradient: on the MARIN CI twin P4's mean over 0.6 –
//! 0.8 s then reads −20 % of the experiment's (−23 % with shifting; S2-8's −36 %), against
//! −204 % (−169 %) with the walls' own normals, and a wall box in still water leaves its water
//! at rest either way (fastest particle 1.4e-3 m/s over 0.2 s, 6.7e-4 over 0.5 – 1 s). A body
//! keeps its own normals with the symmetric gradient: its water at a held box's edges is not at
//! rest (the fastest particle 0.2 m/s with the box at its site, against 9.1e-4 m/s with S2-8's),
//! and with the faces' normals its load moved from −0.08 % to +9.6 % of ρgV (+9.8 % with
//! shifting; open), so such a case is warned about (`FluidConfig::warnings`).

use super::free_surface::SURFACE;
use super::kernel::Wendland;
use super::kernel_correction::PairVectors;
use super::neighbour_list::NeighbourList;
use crate::neighbours::vector_field::VectorField;
use crate::particles::kind::{Kind, DUMMY, FLUID, WALL};
use crate::particles::Particles;
use crate::physics::Physics;
use rayon::prelude::*;

/// A solid particle's convexity flag: 1 on a convex edge or corner of its wall or body.
pub const CONVEX: u8 = 1;

/// The normal of every solid particle with fluid near it, into the fluid:
/// `n_w = −Σ_{solid j} ∇_w W_wj / |…|` (0 for fluid particles and isolated solids).
pub fn normals(k: &Wendland, list: &NeighbourList, p: &Particles, out: &mut VectorField) {
    out.resize(p.len());
    (&mut out.x, &mut out.y, &mut out.z)
        .into_par_iter()
        .enumerate()
        .with_min_len(512)
        .for_each(|(w, (nx, ny, nz))| [*nx, *ny, *nz] = normal_and_fill(k, list, p, w, |_| false).0);
}

/// [`normals`] of particle `w`, and the fill of its support by solids,
/// `(V W(0) + Σ_{solid j} V W_wj) / Σ_lattice V W` (0 for fluid particles), leaving out the
/// solids j for which `skip(j)`.
fn normal_and_fill(
    k: &Wendland,
    list: &NeighbourList,
    p: &Particles,
    w: usize,
    skip: impl Fn(usize) -> bool,
) -> ([f64; 3], f64) {
    let mut g = [0.0; 3];
    let mut fill = 0.0;
    if p.kind[w] != FLUID {
        fill = k.volume * k.w(0.0);
        for (j, q) in list.pairs(w) {
            if p.kind[j] == FLUID || skip(j) {
                continue;
            }
            let d = [p.x[w] - p.x[j], p.y[w] - p.y[j], p.z[w] - p.z[j]];
            let c = k.dw_over_r_at(q);
            (0..3).for_each(|a| g[a] += c * d[a]);
            fill += k.volume * k.w_at(q);
        }
    }
    let norm = (g[0] * g[0] + g[1] * g[1] + g[2] * g[2]).sqrt();
    let n = if norm > 0.0 {
        [-g[0] / norm, -g[1] / norm, -g[2] / norm]
    } else {
        [0.0; 3]
    };
    (n, fill / k.lattice_density)
}

/// The solid fill below which a solid particle lies on a convex edge or corner of its wall or
/// body: midway between the fill of a flat wall's outer layer (a half-space of lattice sites,
/// its own plane included) and that of an edge (a quarter-space), by lattice sums of the kernel:
/// 0.813 and 0.659 at a support of 2.4 Δs (limit 0.736), 0.876 and 0.765 at 2.0 Δs. A plate one
/// layer thick reads as an edge (0.625 at 2.4 Δs); two layers read as a flat wall.
pub fn convex_fill_limit(k: &Wendland) -> f64 {
    let reach = (k.radius / k.spacing).ceil() as i32;
    let (mut flat, mut edge) = (0.0, 0.0);
    for i in -reach..=reach {
        for j in -reach..=reach {
            for l in -reach..=0 {
                let w = k.volume * k.w(k.spacing * f64::from(i * i + j * j + l * l).sqrt());
                flat += w;
                if i <= 0 {
                    edge += w;
                }
            }
        }
    }
    0.5 * (flat + edge) / k.lattice_density
}

/// [`CONVEX`] for every solid particle with fluid near it whose solid fill is below
/// [`convex_fill_limit`], 0 for the others.
pub fn convex(k: &Wendland, list: &NeighbourList, p: &Particles, out: &mut Vec<u8>) {
    let limit = convex_fill_limit(k);
    out.resize(p.len(), 0);
    out.par_iter_mut()
        .enumerate()
        .with_min_len(512)
        .for_each(|(w, c)| *c = convex_flag(p, list, normal_and_fill(k, list, p, w, |_| false).1, limit, w));
}

/// Whether `w` is a solid with fluid near it (it has a list).
fn near_water(p: &Particles, list: &NeighbourList, w: usize) -> bool {
    p.kind[w] != FLUID && !list.of(w).is_empty()
}

/// [`CONVEX`] when solid `w` has fluid near it and its solid `fill` is below `limit`.
fn convex_flag(p: &Particles, list: &NeighbourList, fill: f64, limit: f64, w: usize) -> u8 {
    if near_water(p, list, w) && fill < limit {
        CONVEX
    } else {
        0
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
            *depth = depth_of(k, list, p, n, w, |_| false);
        });
}

/// [`depths`] of particle `w` with normal `n`, leaving out the solids j for which `skip(j)`.
fn depth_of(
    k: &Wendland,
    list: &NeighbourList,
    p: &Particles,
    n: [f64; 3],
    w: usize,
    skip: impl Fn(usize) -> bool,
) -> f64 {
    let mut outer: f64 = 0.0;
    if p.kind[w] != FLUID {
        for &j in list.of(w) {
            let j = j as usize;
            if p.kind[j] != FLUID && !skip(j) {
                let d = [p.x[j] - p.x[w], p.y[j] - p.y[w], p.z[j] - p.z[w]];
                outer = outer.max(d[0] * n[0] + d[1] * n[1] + d[2] * n[2]);
            }
        }
    }
    0.5 * k.spacing + outer
}

/// The normal, depth and convexity flag of solid `w` ([`normals`], [`depths`], [`convex`]),
/// leaving out the solids j for which `skip(j)`.
fn geometry(
    k: &Wendland,
    list: &NeighbourList,
    p: &Particles,
    limit: f64,
    w: usize,
    skip: impl Fn(usize) -> bool + Copy,
) -> ([f64; 3], f64, u8) {
    let (n, fill) = normal_and_fill(k, list, p, w, skip);
    (
        n,
        depth_of(k, list, p, n, w, skip),
        convex_flag(p, list, fill, limit, w),
    )
}

/// The normal, depth and convexity flag of solid `w` ([`geometry`]) from all its solid
/// neighbours in `list` (the GPU path keeps them by id: [`crate::gpu::isph`]).
pub fn fixed_geometry(k: &Wendland, list: &NeighbourList, p: &Particles, w: usize) -> ([f64; 3], f64, u8) {
    geometry(k, list, p, convex_fill_limit(k), w, |_| false)
}

/// The geometry of the solid particles ([`geometry`]), kept by particle id while every solid is
/// fixed (walls and dummies only: no body, gate or inflow strip). A fixed solid's solid
/// neighbours never change, nor their order in its list (the cell sort is stable and fixed
/// particles keep their cells), so its geometry comes out as the same bits every step; at S2's
/// scale computing normals and depths took 9 ms of a 270 ms step. A wave maker's paddle is kept
/// too: it moves rigidly, which leaves depths and convexity as they are; a piston's normals too,
/// a flap's turn with it ([`TurnedSolids`]: they are kept as at rest). A fixed solid's geometry
/// leaves the paddle's particles out, a piston's as a flap's: the paddle moves past it, and the
/// side walls and floor beside it are the same walls wherever it stands (with a piston's
/// particles in, water got behind a piston at H/d = 0.4 beside a side wall at Δs = d/16,
/// `cases/bridge-deck-solitary` with ISPH at 0.844 s) (a side-wall particle that first met water with the
/// flap leaning back over it kept a normal tilted by the flap's particles, and at Δs = d/16 the
/// pressure beside it reached 8 MPa and the PPE diverged at t = 1.7 s of regular waves; found
/// afresh every step with the flap in, they let 18 particles slip between the side walls and the
/// flap's edges by 0.95 s of `fluid-solver/tests/wave_maker.rs`'s solitary flap).
#[derive(Debug, Clone, Default)]
struct FixedSolids {
    normal: Vec<[f64; 3]>,
    depth: Vec<f64>,
    convex: Vec<u8>,
    known: Vec<bool>,
}

/// Solid particles moved rigidly from where they were at rest and turned about an axis along y
/// (a wave maker's paddle, [`crate::boundaries::paddle`]; a piston's angle is 0): the ids `ids`,
/// turned by `angle` θ (rad), positive turning +z towards +x. Their kept normals are their normals at rest, turned by θ as their
/// positions are:
///
///   n = (n₀ₓ cos θ + n₀_z sin θ, n₀_y, −n₀ₓ sin θ + n₀_z cos θ).
#[derive(Debug, Clone, PartialEq)]
pub struct TurnedSolids {
    pub ids: std::ops::Range<u32>,
    pub angle: f64,
}

/// `n` turned by the angle whose (sin, cos) is `sin_cos` about y (the [`TurnedSolids`] rotation).
fn turn(n: [f64; 3], (sin, cos): (f64, f64)) -> [f64; 3] {
    [n[0] * cos + n[2] * sin, n[1], -n[0] * sin + n[2] * cos]
}

/// What the pair differences read of a step besides the particles: the solids' normals into the
/// fluid ([`normals`]), depths behind their faces ([`depths`]) and convexity flags ([`convex`]),
/// and the surface flags of the step's PPE assembly.
#[derive(Debug, Clone, Default)]
pub struct WallFields {
    pub normals: VectorField,
    pub surface: Vec<u8>,
    /// The walls' completion of the surface particles the PPE does not hold, with the symmetric
    /// gradients ([`super::surface_walls`]; empty: none).
    pub surface_completion: Vec<[[f64; 3]; 3]>,
    /// The symmetric forms' corrections L_i of the pairs' kernel gradients
    /// ([`super::kernel_correction`]; empty: none).
    pub kernel_correction: Vec<[[f64; 3]; 3]>,
    pub depth: Vec<f64>,
    pub convex: Vec<u8>,
    /// The solids moved from rest at the present positions (a wave maker's paddle), if any.
    pub turned: Option<TurnedSolids>,
    fixed: FixedSolids,
}

impl WallFields {
    /// [`normals`], [`depths`] and [`convex`] of the particles in their present order (without
    /// `body_edges` no body particle is convex: its pairs take its own normal): those of a solid
    /// with fluid near it taken from [`FixedSolids`] once known there, while every solid is fixed.
    /// The [`TurnedSolids`]' normals are kept turned back to rest and read turned by their angle;
    /// the other solids' geometry leaves them out ([`FixedSolids`]).
    pub fn update_geometry(&mut self, k: &Wendland, list: &NeighbourList, p: &Particles, body_edges: bool) {
        let limit = convex_fill_limit(k);
        let body = Kind::Body.code();
        let all_fixed = p.kind.par_iter().all(|&c| matches!(c, FLUID | WALL | DUMMY));
        let cache = &mut self.fixed;
        if all_fixed {
            let ids = p.id.par_iter().max().map_or(0, |&m| m as usize + 1);
            if cache.known.len() < ids {
                cache.known.resize(ids, false);
                cache.normal.resize(ids, [0.0; 3]);
                cache.depth.resize(ids, 0.0);
                cache.convex.resize(ids, 0);
            }
        }
        self.normals.resize(p.len());
        self.depth.resize(p.len(), 0.0);
        self.convex.resize(p.len(), 0);
        // (ids, sin θ, cos θ) of the turned solids
        let turned = self.turned.as_ref().map(|t| (t.ids.clone(), t.angle.sin_cos()));
        let turned = turned.as_ref();
        // Whether solid j is left out of the geometry of solid w: a turned one, of a fixed one.
        let turned_ids = turned.map(|(ids, _)| ids);
        let skip = |w: usize, j: usize| {
            turned_ids.is_some_and(|ids| !ids.contains(&p.id[w]) && ids.contains(&p.id[j]))
        };
        // A solid with water near: its geometry is read from, or recorded in, the cache while
        // every solid is fixed (or turned with the flap).
        let cached = |w: usize| all_fixed && near_water(p, list, w);
        let known = &cache.known;
        let (normal_of, depth_of_id, convex_of) = (&cache.normal, &cache.depth, &cache.convex);
        let new = (
            &mut self.normals.x,
            &mut self.normals.y,
            &mut self.normals.z,
            &mut self.depth,
            &mut self.convex,
        )
            .into_par_iter()
            .enumerate()
            .with_min_len(512)
            .map(|(w, (nx, ny, nz, depth, convex))| {
                let id = p.id[w] as usize;
                let keep = cached(w);
                let (n, d, c, new) = if keep && known[id] {
                    let n = match turned {
                        Some((ids, sin_cos)) if ids.contains(&p.id[w]) => turn(normal_of[id], *sin_cos),
                        _ => normal_of[id],
                    };
                    (n, depth_of_id[id], convex_of[id], 0)
                } else {
                    let (n, d, c) = geometry(k, list, p, limit, w, |j| skip(w, j));
                    let c = if p.kind[w] == body && !body_edges { 0 } else { c };
                    (n, d, c, usize::from(keep))
                };
                [*nx, *ny, *nz] = n;
                (*depth, *convex) = (d, c);
                new
            })
            .sum::<usize>();
        if new > 0 {
            for w in 0..p.len() {
                let id = p.id[w] as usize;
                if cached(w) && !cache.known[id] {
                    cache.known[id] = true;
                    let n = [self.normals.x[w], self.normals.y[w], self.normals.z[w]];
                    cache.normal[id] = match turned {
                        Some((ids, (sin, cos))) if ids.contains(&p.id[w]) => turn(n, (-sin, *cos)),
                        _ => n,
                    };
                    cache.depth[id] = self.depth[w];
                    cache.convex[id] = self.convex[w];
                }
            }
        }
    }

    /// The pair differences for a step of `dt` with v* in `p`.
    pub fn pair<'a>(
        &'a self,
        physics: &Physics,
        spacing: f64,
        list: &'a NeighbourList,
        p: &'a Particles,
        dt: f64,
    ) -> NeumannPair<'a> {
        NeumannPair {
            density: physics.density,
            gravity: physics.gravity,
            dt,
            p,
            list,
            normals: &self.normals,
            convex: &self.convex,
            surface: &self.surface,
            surface_completion: &self.surface_completion,
            vectors: PairVectors(&self.kernel_correction),
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
    /// The step's neighbour list (a convex solid's face neighbours, [`NeumannPair::face_normal`]).
    pub list: &'a NeighbourList,
    pub normals: &'a VectorField,
    /// [`CONVEX`] for the solids on convex edges and corners ([`convex`]; empty: none).
    pub convex: &'a [u8],
    /// [`SURFACE`] for the fluid particles on the free surface (empty: none).
    pub surface: &'a [u8],
    /// The walls' completion of the surface particles ([`super::surface_walls`]; empty: none).
    pub surface_completion: &'a [[[f64; 3]; 3]],
    /// The pairs' kernel gradients, corrected or plain ([`super::kernel_correction`]).
    pub vectors: PairVectors<'a>,
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
        let n = if self.convex.get(w) == Some(&CONVEX) {
            self.face_normal(f, w)
        } else {
            [self.normals.x[w], self.normals.y[w], self.normals.z[w]]
        };
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

    /// Fluid particle f's wall term `t`, completed by the walls if f is surface water the PPE
    /// does not hold ([`super::surface_walls`]).
    #[inline(always)]
    pub fn completed(&self, f: usize, t: [f64; 3]) -> [f64; 3] {
        match self.surface_completion.get(f) {
            Some(m) => super::surface_walls::completed(t, m),
            None => t,
        }
    }

    /// The normal of the face that fluid particle f stands in front of, for a solid w on a convex
    /// edge or corner (module doc): among w's solid neighbours on a face (outer layer, not
    /// convex), the normal n_j with the largest `n_j·(x_f − x_w)`; w's own normal if it has none.
    fn face_normal(&self, f: usize, w: usize) -> [f64; 3] {
        let p = self.p;
        let d = [p.x[f] - p.x[w], p.y[f] - p.y[w], p.z[f] - p.z[w]];
        // The outer layer: depth Δs/2, more where the normal tilts near an edge (the layer
        // behind lies at 1.5 Δs, an interior particle at more than Δs whatever its normal).
        let outer = self.spacing;
        let mut best = (
            f64::NEG_INFINITY,
            [self.normals.x[w], self.normals.y[w], self.normals.z[w]],
        );
        for &j in self.list.of(w) {
            let j = j as usize;
            if p.kind[j] == FLUID || self.convex[j] == CONVEX || self.depth[j] >= outer {
                continue;
            }
            let n = [self.normals.x[j], self.normals.y[j], self.normals.z[j]];
            let ahead = n[0] * d[0] + n[1] * d[1] + n[2] * d[2];
            if n != [0.0; 3] && ahead > best.0 {
                best = (ahead, n);
            }
        }
        best.1
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
