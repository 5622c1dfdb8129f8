//! The wave maker's paddle (`[fluid.NAME.wave_maker]`): a box of wall particles moved rigidly by
//! the prescribed stroke X(t) ([`schemas::wave_motion::WaveMakerMotion`]): a piston along +x, a
//! flap by turning about its hinge.
//!
//! Before each step from t to t + Δt the paddle's particles are placed where the motion has them
//! at t + Δt and given the velocity (r(t + Δt) − r(t))/Δt, as the inflow strip is
//! ([`super::open_boundary`]): the fluid's predicted positions r* of the step meet the paddle
//! where it is at the step's end, and the wall laws see its velocity (E-MPS's collision stage,
//! ISPH's Neumann condition `(u_f − v_w)·n_w`). Over the run the paddle moves exactly by the
//! motion: its position is never integrated, only set.
//!
//! - A piston's particle stands at its rest x plus X(t + Δt), with velocity
//!   (X(t + Δt) − X(t))/Δt along x.
//! - A flap's particle turns by θ(t) = atan(X(t) / L) ([`schemas::wave_motion::FlapMotion`])
//!   about the hinge (x_h, z_h), x_h the paddle's front face at rest, z_h its `hinge_z`: with
//!   r = rest − hinge,
//!
//!     x = x_h + r_x cos θ + r_z sin θ,   z = z_h − r_x sin θ + r_z cos θ,   y unchanged
//!
//!   ([`schemas::wave_motion::flap::turned`]), and its velocity is the chord of that arc over the
//!   step, within O(Δθ²) of ω × r at the step's middle.
//!
//! Its particles are [`Kind::Wall`](crate::Kind::Wall) and keep their kind; they are pushed
//! last in the layout, so their ids are one contiguous range. ISPH keeps each wall particle's
//! normal, depth and edge flag once found ([`crate::isph::walls`]). A rigid motion leaves depths
//! and edge flags as they are, and a piston's normals: it only translates. A flap's normals turn
//! with it. [`Paddle::turned_solids`] tells ISPH the paddle's ids and angle (0 for a piston):
//! ISPH keeps their normals as at rest and turns them by θ, and leaves the paddle out of the
//! fixed walls' geometry.

use crate::isph::walls::TurnedSolids;
use crate::particles::layout::PaddleParticles;
use crate::particles::Particles;
use rayon::prelude::*;
use schemas::wave_motion::flap::turned;
use schemas::wave_motion::{FlapMotion, PistonMotion, WaveMakerMotion};
use std::sync::Arc;

/// The paddle's particles and motion.
#[derive(Debug, Clone)]
pub struct Paddle {
    motion: Arc<WaveMakerMotion>,
    /// Id of the first paddle particle; the paddle's ids are `first..first + rest_x.len()`.
    first: u32,
    /// Each paddle particle's x at rest, by id − `first`.
    rest_x: Vec<f64>,
    /// Each paddle particle's z at rest, by id − `first`.
    rest_z: Vec<f64>,
    /// x of a flap's hinge: the paddle's front face at rest.
    hinge_x: f64,
}

impl Paddle {
    /// The paddle of the layout's `particles`, moving by `motion`; `front` is the x of its front
    /// face at rest (where a flap's hinge lies).
    pub fn new(motion: Arc<WaveMakerMotion>, particles: PaddleParticles, front: f64) -> Paddle {
        Paddle {
            motion,
            first: particles.first,
            rest_x: particles.rest_x,
            rest_z: particles.rest_z,
            hinge_x: front,
        }
    }

    /// Places the paddle's particles for the step from `t` to `t + dt` (module doc).
    pub fn place(&self, p: &mut Particles, t: f64, dt: f64) {
        match self.motion.as_ref() {
            WaveMakerMotion::Piston(m) => self.translate(m, p, t, dt),
            WaveMakerMotion::Flap(m) => self.turn(m, p, t, dt),
        }
    }

    /// The paddle's particle ids and its angle θ(`t`) (`None`: at rest, θ = 0, before the first
    /// step; a piston never turns, θ = 0), for ISPH's wall geometry (module doc): the fixed walls'
    /// geometry leaves the paddle out, whichever way it moves past them.
    pub fn turned_solids(&self, t: Option<f64>) -> TurnedSolids {
        let angle = match self.motion.as_ref() {
            WaveMakerMotion::Piston(_) => 0.0,
            WaveMakerMotion::Flap(m) => t.map_or(0.0, |t| m.angle(t)),
        };
        TurnedSolids {
            ids: self.first..self.first + self.rest_x.len() as u32,
            angle,
        }
    }

    /// The paddle's particle ids (one contiguous range).
    pub fn ids(&self) -> std::ops::Range<u32> {
        self.first..self.first + self.rest_x.len() as u32
    }

    /// Each paddle particle's (x, z) at rest, by id − the first id.
    pub fn rest(&self) -> impl Iterator<Item = [f64; 2]> + '_ {
        self.rest_x.iter().zip(&self.rest_z).map(|(&x, &z)| [x, z])
    }

    /// The prescribed motion.
    pub fn motion(&self) -> &WaveMakerMotion {
        &self.motion
    }

    /// x of a flap's hinge: the paddle's front face at rest.
    pub fn hinge_x(&self) -> f64 {
        self.hinge_x
    }

    /// The index into the rest positions of particle `id`, if it is a paddle particle.
    fn index(&self, id: u32) -> Option<usize> {
        id.checked_sub(self.first)
            .map(|k| k as usize)
            .filter(|&k| k < self.rest_x.len())
    }

    /// A piston: x = rest x + X(t + dt), vx = (X(t + dt) − X(t))/dt.
    fn translate(&self, m: &PistonMotion, p: &mut Particles, t: f64, dt: f64) {
        let (x0, x1) = (m.stroke(t), m.stroke(t + dt));
        let v = (x1 - x0) / dt;
        (&mut p.x, &mut p.vx, &p.id)
            .into_par_iter()
            .with_min_len(4096)
            .for_each(|(x, vx, &id)| {
                if let Some(k) = self.index(id) {
                    *x = self.rest_x[k] + x1;
                    *vx = v;
                }
            });
    }

    /// A flap: each particle turned by θ(t + dt) about the hinge, its velocity the chord from
    /// its place at θ(t) over dt.
    fn turn(&self, m: &FlapMotion, p: &mut Particles, t: f64, dt: f64) {
        let hinge = [self.hinge_x, m.hinge().z()];
        let (a0, a1) = (m.angle(t).sin_cos(), m.angle(t + dt).sin_cos());
        (&mut p.x, &mut p.z, &mut p.vx, &mut p.vz, &p.id)
            .into_par_iter()
            .with_min_len(4096)
            .for_each(|(x, z, vx, vz, &id)| {
                if let Some(k) = self.index(id) {
                    let rest = [self.rest_x[k], self.rest_z[k]];
                    let (r0, r1) = (turned(rest, hinge, a0), turned(rest, hinge, a1));
                    [*x, *z] = r1;
                    *vx = (r1[0] - r0[0]) / dt;
                    *vz = (r1[1] - r0[1]) / dt;
                }
            });
    }
}
