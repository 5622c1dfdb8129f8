//! The wave maker's paddle on the device (`shaders/paddle.wgsl`), the GPU path of
//! [`crate::boundaries::paddle`]: the host evaluates the prescribed motion for each step, as the
//! CPU path does before its step from t to t + Δt, and hands the device a few numbers in the
//! uniform block ([`PaddlePlacement`]); the device places each paddle particle from its rest
//! position, kept on the device after the bodies' member rows (32 B per paddle particle, in the
//! members' buffer, so the paddle needs no binding of its own). No particle crosses per step.
//!
//! Both motions are one rigid motion in the x–z plane about the hinge (x_h, z_h), with
//! r = rest − hinge:
//!
//!   x = x_rest + s + r_x (cos θ − 1) + r_z sin θ,   z = z_rest − r_x sin θ + r_z (cos θ − 1),
//!   v_x = v_s + r_x Δcos/Δt + r_z Δsin/Δt,          v_z = −r_x Δsin/Δt + r_z Δcos/Δt,
//!
//! y and v_y unchanged. A piston has θ = 0, s = X(t + Δt), v_s = (X(t + Δt) − X(t))/Δt; a flap
//! has s = v_s = 0, θ = θ(t + Δt), and Δcos, Δsin the changes of cos θ and sin θ over the step.
//! That is the CPU's x_h + r_x cos θ + r_z sin θ (and its chord velocity) rewritten about the
//! rest position: cos θ − 1 = −2 sin²(θ/2) and the chord's Δcos/Δt, Δsin/Δt are formed in f64 on
//! the host, so the device's f32 adds no cancellation (a displacement of |r| θ²/2 or a chord of
//! |r| Δθ rounds as itself, not as the difference of two positions).

use super::bodies::Member;
use super::frame::Frame;
use crate::boundaries::paddle::Paddle;
use schemas::wave_motion::WaveMakerMotion;

/// The paddle's particles as the device keeps them: the first id, each particle's (x, z) at rest
/// (by id − first), and the hinge (a piston's is its front face at z = 0, unused).
#[derive(Debug, Clone, PartialEq)]
pub struct PaddleSites {
    pub first: u32,
    pub rest: Vec<[f64; 2]>,
    pub hinge: [f64; 2],
}

impl PaddleSites {
    /// The sites of the solver's `paddle`.
    pub fn of(paddle: &Paddle) -> PaddleSites {
        let hinge_z = match paddle.motion() {
            WaveMakerMotion::Piston(_) => 0.0,
            WaveMakerMotion::Flap(m) => m.hinge().z(),
        };
        PaddleSites {
            first: paddle.ids().start,
            rest: paddle.rest().collect(),
            hinge: [paddle.hinge_x(), hinge_z],
        }
    }

    /// The device's rows of the paddle in the members' buffer, after the bodies' (offset: the
    /// rest position (x, 0, z) in the device's `frame`, with wide positions its high parts and
    /// the low parts of x and z in the padding; id; body: none).
    pub fn rows(&self, frame: &Frame) -> Vec<Member> {
        (self.first..)
            .zip(&self.rest)
            .map(|(id, r)| {
                let ((x, low_x), (z, low_z)) = (frame.split_along(0, r[0]), frame.split_along(2, r[1]));
                Member {
                    offset: [x, 0.0, z],
                    id,
                    body: u32::MAX,
                    pad: [low_x.to_bits(), low_z.to_bits(), 0],
                }
            })
            .collect()
    }
}

/// The paddle's motion over one step, for the device (module doc).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct PaddlePlacement {
    /// A piston's X(t + Δt) [m] and (X(t + Δt) − X(t))/Δt [m/s].
    pub shift: f64,
    pub speed: f64,
    /// A flap's cos θ(t + Δt) − 1 and sin θ(t + Δt).
    pub cos_m1: f64,
    pub sin: f64,
    /// A flap's (cos θ(t + Δt) − cos θ(t))/Δt and (sin θ(t + Δt) − sin θ(t))/Δt [1/s].
    pub dcos: f64,
    pub dsin: f64,
}

impl PaddlePlacement {
    /// The placement of `paddle` for the step from `t` to `t + dt`, at the instants
    /// [`Paddle::place`] takes.
    pub fn of(paddle: &Paddle, t: f64, dt: f64) -> PaddlePlacement {
        match paddle.motion() {
            WaveMakerMotion::Piston(m) => {
                let (x0, x1) = (m.stroke(t), m.stroke(t + dt));
                PaddlePlacement {
                    shift: x1,
                    speed: (x1 - x0) / dt,
                    ..Default::default()
                }
            }
            WaveMakerMotion::Flap(m) => {
                let (a0, a1) = (m.angle(t), m.angle(t + dt));
                let ((s0, c0), (s1, c1)) = (a0.sin_cos(), a1.sin_cos());
                let half = (0.5 * a1).sin();
                PaddlePlacement {
                    cos_m1: -2.0 * half * half,
                    sin: s1,
                    dcos: (c1 - c0) / dt,
                    dsin: (s1 - s0) / dt,
                    ..Default::default()
                }
            }
        }
    }
}
