//! Rigid bodies made of particles: their kinematics come in (pose and velocity from the
//! structure solver), their hydrodynamic loads go out.
//!
//! A body's pose is its centre and a unit quaternion (w, x, y, z) relative to its initial
//! placement: at t = 0 the centre is the middle of its `[[body]]` box and the quaternion is
//! (1, 0, 0, 0). Each body particle keeps its offset from the initial centre.

use crate::kernel::Kernel;
use crate::kind::{Kind, FLUID};
use crate::layout::BodyParticles;
use crate::neighbour_search::CellGrid;
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
    /// Records the bodies of a fresh layout (`p` still in layout order: index = id).
    pub fn new(bodies: &[BodyParticles], boxes: &[([f64; 3], [f64; 3])], p: &Particles) -> RigidBodies {
        let mut out = RigidBodies::default();
        for (b, (body, (lo, hi))) in bodies.iter().zip(boxes).enumerate() {
            let centre = std::array::from_fn(|a| 0.5 * (lo[a] + hi[a]));
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

    /// Body names, in the order of the interface arrays.
    pub fn names(&self) -> &[String] {
        &self.names
    }

    /// Initial centre of body `b`.
    pub fn initial_centre(&self, b: usize) -> [f64; 3] {
        self.centres[b]
    }

    fn member(&self, id: u32) -> Option<&(u32, usize, [f64; 3])> {
        self.members
            .binary_search_by_key(&id, |m| m.0)
            .ok()
            .map(|k| &self.members[k])
    }

    /// Places every body particle by its body's pose and gives it the rigid velocity
    /// `V + ω × (r − c)` (S1-21). `pose`: 7 per body (centre, quaternion w x y z);
    /// `velocity`: 6 per body (V, ω).
    pub fn set_kinematics(&self, p: &mut Particles, pose: &[f64], velocity: &[f64]) {
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
                (*x, *y, *z) = (c[0] + arm[0], c[1] + arm[1], c[2] + arm[2]);
                let vel = [velocity[6 * b], velocity[6 * b + 1], velocity[6 * b + 2]];
                let omega = [velocity[6 * b + 3], velocity[6 * b + 4], velocity[6 * b + 5]];
                let spin = cross(omega, arm);
                (*u, *v, *w) = (vel[0] + spin[0], vel[1] + spin[1], vel[2] + spin[2]);
            });
    }

    /// Pressure force of the fluid on each body and its moment about `centres` (6 per body):
    /// the reaction of S1-3's pair terms, `f_j = m/ρ0 · d/n0_grad Σ_i (P_i + P_j) r_ij/|r_ij|² w_grad`
    /// over fluid neighbours i of body particle j (r_ij = r_j − r_i), so that the pair forces
    /// on fluid and body balance exactly.
    pub fn pressure_loads(
        &self,
        grid: &CellGrid,
        kernel: &Kernel,
        p: &Particles,
        centres: &[f64],
    ) -> Vec<f64> {
        let re = kernel.re_grad;
        let re2 = re * re;
        let reach = grid.reach(re);
        // Particle volume m/ρ0 = Δs³ times S1-3's d/n0_grad.
        let scale = kernel.spacing.powi(3) * kernel.gradient_factor();
        let per_particle: Vec<(usize, [f64; 3], [f64; 3])> = (0..p.len())
            .into_par_iter()
            .with_min_len(1024)
            .filter(|&j| p.kind[j] == Kind::Body.code())
            .filter_map(|j| {
                let &(_, b, _) = self.member(p.id[j])?;
                let rj = p.position(j);
                let mut f = [0.0; 3];
                grid.for_each_range(j, reach, |s, e| {
                    for i in (s..e).filter(|&i| p.kind[i] == FLUID) {
                        let d = [rj[0] - p.x[i], rj[1] - p.y[i], rj[2] - p.z[i]];
                        let r2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
                        if r2 < re2 && r2 > 0.0 {
                            let r = r2.sqrt();
                            let c = (p.pressure[i] + p.pressure[j]) * (re / r - r / re) / r2;
                            for a in 0..3 {
                                f[a] += scale * c * d[a];
                            }
                        }
                    }
                });
                Some((b, rj, f))
            })
            .collect();
        let mut loads = vec![0.0; 6 * self.names.len()];
        for (b, r, f) in per_particle {
            let c = [centres[7 * b], centres[7 * b + 1], centres[7 * b + 2]];
            let m = cross([r[0] - c[0], r[1] - c[1], r[2] - c[2]], f);
            for a in 0..3 {
                loads[6 * b + a] += f[a];
                loads[6 * b + 3 + a] += m[a];
            }
        }
        loads
    }

    /// The reaction of [`RigidBodies::pressure_loads`] evaluated from the fluid's side: for each
    /// fluid particle i, the S1-3 pair terms of its body neighbours j,
    /// `f_i = −Δs³ d/n0_grad Σ_j (P_i + P_j) r_ij/|r_ij|² w_grad`, summed per body with their moment
    /// about `centres` (6 per body). It equals minus the loads up to round-off when the pair
    /// search is symmetric, which the coupler's action–reaction ledger checks.
    pub fn pressure_reaction(
        &self,
        grid: &CellGrid,
        kernel: &Kernel,
        p: &Particles,
        centres: &[f64],
    ) -> Vec<f64> {
        let re = kernel.re_grad;
        let re2 = re * re;
        let reach = grid.reach(re);
        let scale = kernel.spacing.powi(3) * kernel.gradient_factor();
        let bodies = self.names.len();
        let body = Kind::Body.code();
        (0..p.len())
            .into_par_iter()
            .with_min_len(1024)
            .filter(|&i| p.kind[i] == FLUID)
            .fold(
                || vec![0.0; 6 * bodies],
                |mut acc, i| {
                    let ri = p.position(i);
                    grid.for_each_range(i, reach, |s, e| {
                        for j in (s..e).filter(|&j| p.kind[j] == body) {
                            let d = [p.x[j] - ri[0], p.y[j] - ri[1], p.z[j] - ri[2]];
                            let r2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
                            let Some(&(_, b, _)) = self.member(p.id[j]) else {
                                continue;
                            };
                            if r2 < re2 && r2 > 0.0 {
                                let r = r2.sqrt();
                                let c = -scale * (p.pressure[i] + p.pressure[j]) * (re / r - r / re) / r2;
                                let f = d.map(|v| c * v);
                                let centre = [centres[7 * b], centres[7 * b + 1], centres[7 * b + 2]];
                                let m = cross([ri[0] - centre[0], ri[1] - centre[1], ri[2] - centre[2]], f);
                                for a in 0..3 {
                                    acc[6 * b + a] += f[a];
                                    acc[6 * b + 3 + a] += m[a];
                                }
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
