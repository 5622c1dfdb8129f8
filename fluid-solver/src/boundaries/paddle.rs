//! The wave maker's paddle (`[fluid.NAME.wave_maker]`): a box of wall particles moved rigidly
//! along +x by the prescribed stroke X(t) ([`schemas::wave_motion::PistonMotion`]).
//!
//! Before each step from t to t + Δt the paddle's particles are placed at their rest position
//! plus X(t + Δt) and given the velocity (X(t + Δt) − X(t))/Δt, as the inflow strip is
//! ([`super::open_boundary`]): the fluid's predicted positions r* of the step meet the paddle
//! where it is at the step's end, and the wall laws see its velocity (E-MPS's collision stage,
//! ISPH's Neumann condition `(u_f − v_w)·n_w`). Over the run the paddle moves exactly by the
//! stroke: its position is never integrated, only set.
//!
//! Its particles are [`Kind::Wall`] and keep their kind; they are pushed last in the layout, so
//! their ids are one contiguous range. A piston only translates, so ISPH's wall normals, depths
//! and edge flags, found once per particle, stay right as it moves.

use crate::particles::Particles;
use rayon::prelude::*;
use schemas::wave_motion::PistonMotion;
use std::sync::Arc;

/// The paddle's particles and motion.
#[derive(Debug, Clone)]
pub struct Paddle {
    motion: Arc<PistonMotion>,
    /// Id of the first paddle particle; the paddle's ids are `first..first + rest_x.len()`.
    first: u32,
    /// Each paddle particle's x at rest, by id − `first`.
    rest_x: Vec<f64>,
}

impl Paddle {
    /// The paddle whose particles have ids `first..first + rest_x.len()` and rest positions
    /// `rest_x`, moving by `motion`.
    pub fn new(motion: Arc<PistonMotion>, first: u32, rest_x: Vec<f64>) -> Paddle {
        Paddle {
            motion,
            first,
            rest_x,
        }
    }

    /// Places the paddle's particles for the step from `t` to `t + dt` (module doc).
    pub fn place(&self, p: &mut Particles, t: f64, dt: f64) {
        let (x0, x1) = (self.motion.stroke(t), self.motion.stroke(t + dt));
        let v = (x1 - x0) / dt;
        let (first, rest) = (self.first, &self.rest_x);
        (&mut p.x, &mut p.vx, &p.id)
            .into_par_iter()
            .with_min_len(4096)
            .for_each(|(x, vx, &id)| {
                if let Some(&x_rest) = id.checked_sub(first).and_then(|k| rest.get(k as usize)) {
                    *x = x_rest + x1;
                    *vx = v;
                }
            });
    }
}
