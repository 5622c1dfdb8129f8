//! A wall-pressure sensor as an experiment mounts one: a disc of diameter D on a face of the
//! tank, a wall box or a body, with the face's outward normal n (into the water).
//!
//! Reading: the normal force the fluid exerts on the wall particles behind the disc, per unit
//! area, `P = −n · Σ_{j∈S} Σ_{i fluid} f_ij / (N Δs²)`, where f_ij is the method's pressure pair
//! force on wall particle j from fluid particle i (E-MPS: S1-3's pair term, the very force that
//! holds the water back, so the disc's reading times its area is the load on that patch), S the
//! pressure-carrying wall or body particles whose centres lie within D/2 of the disc's axis and
//! at most two layers behind the face (the fluid's r_e,grad = 2.1 Δs reaches no deeper), and N
//! the sites of the first layer in S (N Δs² is the area the particles stand for).
//!
//! Against the point probe (`kind = "pressure"`, a kernel-weighted mean of particle pressures
//! at a point): the point probe reads the fluid's pressure field where it is put, so its value
//! at a wall depends on how far off the wall it sits (half a spacing changes an impact peak by
//! 7–12 %) and it follows each particle's pressure noise. The sensor reads the force on the face
//! itself, averaged over an area fixed in metres, not in spacings, so it converges as Δs shrinks
//! and matches a transducer of the same diameter; its `window` box filter plays the sensor's
//! sampling rate.

use crate::bodies::pair_law::PairLaw;
use crate::particles::kind::Kind;
use crate::particles::Particles;
use schemas::case::fluid::ProbeConfig;

/// Layers behind a face the fluid's pressure pair forces reach (r_e,grad = 2.1 Δs from a fluid
/// particle half a spacing off the face reaches centres 0.5 Δs and 1.5 Δs deep).
const LAYERS_REACHED: f64 = 2.0;

/// The disc of a sensor: centre, normal axis and sign, radius.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Disc {
    pub centre: [f64; 3],
    pub axis: usize,
    pub sign: f64,
    pub radius: f64,
}

impl Disc {
    /// The disc of a validated wall-pressure probe.
    pub fn of(probe: &ProbeConfig) -> Disc {
        let (axis, sign) = probe.normal_direction();
        Disc {
            centre: [probe.position[0], probe.position[1], probe.position[2]],
            axis,
            sign,
            radius: 0.5 * probe.diameter.unwrap_or(0.0),
        }
    }

    /// Height above the face along the normal (negative behind it) and distance from the axis.
    fn local(&self, r: [f64; 3]) -> (f64, f64) {
        let d: [f64; 3] = std::array::from_fn(|a| r[a] - self.centre[a]);
        let along = self.sign * d[self.axis];
        let lateral2: f64 = (0..3).filter(|&a| a != self.axis).map(|a| d[a] * d[a]).sum();
        (along, lateral2.sqrt())
    }

    /// A box holding every particle [`Disc::pressure`] reads with a law of reach `reach`: the
    /// wall layers behind the disc and the fluid within `reach` in front of it, out to the
    /// radius plus `reach` (where the GPU path gathers them from, [`crate::gpu::gather`]).
    pub fn bounds(&self, reach: f64, spacing: f64) -> ([f64; 3], [f64; 3]) {
        let side = self.radius + reach;
        let mut lo = self.centre.map(|c| c - side);
        let mut hi = self.centre.map(|c| c + side);
        let (behind, front) = (LAYERS_REACHED * spacing, reach);
        let a = self.axis;
        (lo[a], hi[a]) = match self.sign > 0.0 {
            true => (self.centre[a] - behind, self.centre[a] + front),
            false => (self.centre[a] - front, self.centre[a] + behind),
        };
        (lo, hi)
    }

    /// The wall and body particles behind the disc, and how many of them form its first layer.
    pub fn wall_particles(&self, p: &Particles, spacing: f64) -> (Vec<usize>, usize) {
        let mut set = Vec::new();
        let mut first_layer = 0;
        for i in 0..p.len() {
            if !matches!(p.kind_of(i), Kind::Wall | Kind::Body) {
                continue;
            }
            let (along, lateral) = self.local(p.position(i));
            if lateral <= self.radius && along < 0.0 && along >= -LAYERS_REACHED * spacing {
                set.push(i);
                if along >= -spacing {
                    first_layer += 1;
                }
            }
        }
        (set, first_layer)
    }

    /// The pressure the fluid exerts on the disc [Pa] (see the module doc); `None` when no wall
    /// particle lies behind it.
    pub fn pressure(&self, p: &Particles, law: &PairLaw, spacing: f64) -> Option<f64> {
        let (walls, first_layer) = self.wall_particles(p, spacing);
        if first_layer == 0 {
            return None;
        }
        let fluid: Vec<usize> = (0..p.len())
            .filter(|&i| p.kind_of(i) == Kind::Fluid)
            .filter(|&i| {
                let (along, lateral) = self.local(p.position(i));
                along > 0.0 && along <= law.radius && lateral <= self.radius + law.radius
            })
            .collect();
        let mut normal_force = 0.0;
        for &j in &walls {
            for &i in &fluid {
                if let Some(f) = law.force(i, j) {
                    normal_force += self.sign * f[self.axis];
                }
            }
        }
        Some(-normal_force / (first_layer as f64 * spacing * spacing))
    }
}
