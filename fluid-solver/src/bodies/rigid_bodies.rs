//! Rigid bodies made of particles: their kinematics come in (pose and velocity from the
//! structure solver), their hydrodynamic loads go out.
//!
//! A body's pose is its centre and a unit quaternion (w, x, y, z) relative to its initial
//! placement: at t = 0 the centre is the middle of its `[[body]]` box (a mesh body's: the mesh's
//! volume centroid) and the quaternion is (1, 0, 0, 0). Each body particle keeps its offset from the initial centre.
//!
//! What the fluid exchanges with a body, pair by pair between a fluid particle i and a body
//! particle j, comes from the fluid method's pair laws ([`crate::bodies::pair_law`]): each pair force
//! acts on the body and, reversed, on the fluid, with its moment taken at r_j on both sides, so
//! action = reaction holds to round-off for forces and moments. E-MPS hands over
//! ([`crate::emps::pair_laws`]):
//! - the pressure pair terms of S1-3 (body particles carry pressure like walls, S1-14, and fill
//!   the fluid's number density, S1-15; the seed's PMS, S1-19 … S1-21, moves them as fluid
//!   instead and reads the body force from their velocity change);
//! - the collision stage's impulses between close approaching fluid and body particles (see
//!   [`crate::neighbours::collision`]), with the body particle's rigid velocity, reported as impulse / Δt of
//!   the last step;
//! - when the viscous term is on, S1-4's pair terms with the body particles' rigid velocities
//!   (no slip on the body).
//!
//! Gravity is counted once: the fluid reports only these contact forces. Buoyancy is their
//! resultant (the pressure of the water's own weight acting on the body's surface); the body's
//! weight is applied by the structure solver's `gravity`, never here.

use crate::bodies::pair_law::PairLaw;
use crate::neighbours::neighbour_search::CellGrid;
use crate::particles::kind::{Kind, FLUID};
use crate::particles::layout::BodyParticles;
use crate::particles::Particles;
use rayon::prelude::*;

/// The bodies of a fluid participant and the reference offsets of their particles.
#[derive(Debug, Clone, Default)]
pub struct RigidBodies {
    names: Vec<String>,
    /// Initial centre of each body.
    centres: Vec<[f64; 3]>,
    /// (particle id, body index, offset from the initial centre), sorted by id.
    members: Vec<(u32, usize, [f64; 3])>,
    /// The part of the loads this fluid reports when it is one slab of a fluid cut into slabs.
    share: Option<LoadShare>,
}

/// The part of the bodies' loads one slab of the fluid reports ([`crate::ranks`]): the pairs
/// with the fluid it owns, and the walls' contact on the body particles between its cuts
/// (`lo ≤ x < hi`; every slab holds every body particle), so the slabs' loads and reactions add
/// up to the whole fluid's.
#[derive(Debug, Clone, Default)]
pub struct LoadShare {
    /// Whether the slab owns the fluid particle of each id (an id past the end: no).
    pub owned: Vec<bool>,
    pub lo: f64,
    pub hi: f64,
}

impl LoadShare {
    fn owns(&self, id: u32) -> bool {
        self.owned.get(id as usize).copied().unwrap_or(false)
    }
}

/// Rotates `v` by the unit quaternion `q = (w, x, y, z)`.
pub fn rotate(q: [f64; 4], v: [f64; 3]) -> [f64; 3] {
    let [w, x, y, z] = q;
    let u = [x, y, z];
    let t = cross(u, v).map(|c| 2.0 * c);
    let ut = cross(u, t);
    [
        v[0] + w * t[0] + ut[0],
        v[1] + w * t[1] + ut[1],
        v[2] + w * t[2] + ut[2],
    ]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

impl RigidBodies {
    /// Records the bodies of a fresh layout (`p` still in layout order: index = id) with their
    /// initial `centres` ([`schemas::case::fluid::BodyConfig::centre`]).
    pub fn new(bodies: &[BodyParticles], centres: &[[f64; 3]], p: &Particles) -> RigidBodies {
        let mut out = RigidBodies::default();
        for (b, (body, &centre)) in bodies.iter().zip(centres).enumerate() {
            out.names.push(body.name.clone());
            out.centres.push(centre);
            for &id in &body.ids {
                let r = p.position(id as usize);
                out.members
                    .push((id, b, std::array::from_fn(|a| r[a] - centre[a])));
            }
        }
        out.members.sort_by_key(|m| m.0);
        out
    }

    /// Makes these bodies report only `share` of their loads (a slab of the fluid), or all of
    /// them (`None`).
    pub fn set_share(&mut self, share: Option<LoadShare>) {
        self.share = share;
    }

    /// The share set by [`RigidBodies::set_share`], to update in place.
    pub fn share_mut(&mut self) -> Option<&mut LoadShare> {
        self.share.as_mut()
    }

    /// Whether particle `i` of `p` is fluid whose pairs with the bodies count here.
    fn counts_fluid(&self, p: &Particles, i: usize) -> bool {
        p.kind[i] == FLUID && self.share.as_ref().is_none_or(|s| s.owns(p.id[i]))
    }

    /// Whether the walls' contact on body particle `j` of `p` counts here.
    pub(crate) fn counts_body_particle(&self, p: &Particles, j: usize) -> bool {
        self.share
            .as_ref()
            .is_none_or(|s| s.lo <= p.x[j] && p.x[j] < s.hi)
    }

    /// Body names, in the order of the interface arrays.
    pub fn names(&self) -> &[String] {
        &self.names
    }

    /// Initial centre of body `b`.
    pub fn initial_centre(&self, b: usize) -> [f64; 3] {
        self.centres[b]
    }

    /// (particle id, body index, offset from the body's initial centre) of every body particle,
    /// sorted by id (the GPU path's member table).
    pub fn members(&self) -> &[(u32, usize, [f64; 3])] {
        &self.members
    }

    fn member(&self, id: u32) -> Option<&(u32, usize, [f64; 3])> {
        self.members
            .binary_search_by_key(&id, |m| m.0)
            .ok()
            .map(|k| &self.members[k])
    }

    /// Gives every body particle the rigid velocity `u = V + ω × (r − c)` (S1-21) of its body at
    /// `pose` and places it at `r − u·lead`, r its place at `pose`: a step of length `lead`, which
    /// moves body particles by `u Δt` (S1-11; S2-4 in ISPH), ends with them at `pose` (`lead` = 0
    /// places them there). `pose`: 7 per body (centre, quaternion w x y z); `velocity`: 6 per
    /// body (V, ω).
    pub fn set_kinematics(&self, p: &mut Particles, pose: &[f64], velocity: &[f64], lead: f64) {
        (
            &mut p.x, &mut p.y, &mut p.z, &mut p.vx, &mut p.vy, &mut p.vz, &p.kind, &p.id,
        )
            .into_par_iter()
            .with_min_len(4096)
            .filter(|t| *t.6 == Kind::Body.code())
            .for_each(|(x, y, z, u, v, w, _, &id)| {
                let Some(&(_, b, offset)) = self.member(id) else {
                    return;
                };
                let c = [pose[7 * b], pose[7 * b + 1], pose[7 * b + 2]];
                let q = [pose[7 * b + 3], pose[7 * b + 4], pose[7 * b + 5], pose[7 * b + 6]];
                let arm = rotate(q, offset);
                let vel = [velocity[6 * b], velocity[6 * b + 1], velocity[6 * b + 2]];
                let omega = [velocity[6 * b + 3], velocity[6 * b + 4], velocity[6 * b + 5]];
                let spin = cross(omega, arm);
                (*u, *v, *w) = (vel[0] + spin[0], vel[1] + spin[1], vel[2] + spin[2]);
                (*x, *y, *z) = (
                    c[0] + arm[0] - *u * lead,
                    c[1] + arm[1] - *v * lead,
                    c[2] + arm[2] - *w * lead,
                );
            });
    }

    /// The force and moment about `centres` of pair law `law` on each body, summed over the
    /// body's particles (the loads), and the reaction on the fluid, summed over the fluid
    /// particles (6 per body each). Both sums read the one law, so the reaction equals minus the
    /// loads up to round-off when the pair search is symmetric, which the coupler's
    /// action–reaction ledger checks.
    pub fn exchange(
        &self,
        grid: &CellGrid,
        p: &Particles,
        centres: &[f64],
        law: &PairLaw,
    ) -> (Vec<f64>, Vec<f64>) {
        let pair = |i: usize, j: usize| law.force(i, j);
        let fluid = |i: usize| self.counts_fluid(p, i);
        let loads = self.body_side_sum(grid, p, law.radius, centres, |_| true, fluid, pair);
        let reaction = self.fluid_side_sum(grid, p, law.radius, centres, pair);
        (loads, reaction)
    }

    /// Σ over the body particles j that `body` accepts of `pair(i, j)` over neighbours i within
    /// `radius` that `partner` accepts, per body, with the moment about the body's centre at r_j
    /// (6 per body).
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn body_side_sum(
        &self,
        grid: &CellGrid,
        p: &Particles,
        radius: f64,
        centres: &[f64],
        body: impl Fn(usize) -> bool + Sync,
        partner: impl Fn(usize) -> bool + Sync,
        pair: impl Fn(usize, usize) -> Option<[f64; 3]> + Sync,
    ) -> Vec<f64> {
        let reach = grid.reach(radius);
        let per_particle: Vec<(usize, [f64; 3], [f64; 3])> = (0..p.len())
            .into_par_iter()
            .with_min_len(1024)
            .filter(|&j| p.kind[j] == Kind::Body.code() && body(j))
            .filter_map(|j| {
                let &(_, b, _) = self.member(p.id[j])?;
                let mut f = [0.0; 3];
                grid.for_each_range(j, reach, |s, e| {
                    for i in (s..e).filter(|&i| partner(i)) {
                        if let Some(fij) = pair(i, j) {
                            (0..3).for_each(|a| f[a] += fij[a]);
                        }
                    }
                });
                Some((b, p.position(j), f))
            })
            .collect();
        let mut loads = vec![0.0; 6 * self.names.len()];
        for (b, r, f) in per_particle {
            add_with_moment(&mut loads[6 * b..6 * b + 6], r, &centres[7 * b..7 * b + 3], f);
        }
        loads
    }

    /// −Σ over fluid particles i of `pair(i, j)` over body neighbours j within `radius`, per body,
    /// with the moment about the body's centre taken at the body particle r_j, as in
    /// [`RigidBodies::body_side_sum`], so that the moments balance too (the viscous pair force is
    /// not along r_ij) (6 per body).
    fn fluid_side_sum(
        &self,
        grid: &CellGrid,
        p: &Particles,
        radius: f64,
        centres: &[f64],
        pair: impl Fn(usize, usize) -> Option<[f64; 3]> + Sync,
    ) -> Vec<f64> {
        let reach = grid.reach(radius);
        let bodies = self.names.len();
        let body = Kind::Body.code();
        (0..p.len())
            .into_par_iter()
            .with_min_len(1024)
            .filter(|&i| self.counts_fluid(p, i))
            .fold(
                || vec![0.0; 6 * bodies],
                |mut acc, i| {
                    grid.for_each_range(i, reach, |s, e| {
                        for j in (s..e).filter(|&j| p.kind[j] == body) {
                            let Some(&(_, b, _)) = self.member(p.id[j]) else {
                                continue;
                            };
                            if let Some(fij) = pair(i, j) {
                                let f = fij.map(|v| -v);
                                add_with_moment(
                                    &mut acc[6 * b..6 * b + 6],
                                    p.position(j),
                                    &centres[7 * b..7 * b + 3],
                                    f,
                                );
                            }
                        }
                    });
                    acc
                },
            )
            .reduce(
                || vec![0.0; 6 * bodies],
                |a, b| a.iter().zip(&b).map(|(x, y)| x + y).collect(),
            )
    }
}

/// Adds force `f` acting at `r` and its moment about `centre` to `out` (fx fy fz mx my mz).
fn add_with_moment(out: &mut [f64], r: [f64; 3], centre: &[f64], f: [f64; 3]) {
    let m = cross([r[0] - centre[0], r[1] - centre[1], r[2] - centre[2]], f);
    for a in 0..3 {
        out[a] += f[a];
        out[3 + a] += m[a];
    }
}
