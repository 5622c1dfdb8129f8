//! Where the device measures positions from: the tank's lower corner
//! ([`schemas::case::fluid::FluidConfig::gpu_frame_origin`]). Every position that goes to the
//! device (particles, wall blocks, the grid's origin, the tank, solids, bodies' centres, the
//! paddle, damping zones, the open boundaries' planes, the drag coupling's points) is sent as
//! `x − origin` in f32 and comes back as that plus the origin in f64, so the f32 rounding is
//! |x − origin|·2⁻²⁴, at most the tank's extent·2⁻²⁴, wherever the tank lies: georeferenced
//! coordinates (a DEM in UTM metres, 10⁵–10⁶ m from the origin) round as a tank at the origin
//! does, and a tank whose lower corner is the origin runs on the same f32 numbers as before.
//! (From the tank's centre the rounding would halve, but every f32 number of today's tanks would
//! change, and the GPU-vs-CPU comparisons past an impact moved by up to 150× with them:
//! docs/notes/gpu-precision.md.)

/// The device's frame: positions are kept relative to `origin`.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Frame {
    pub origin: [f64; 3],
}

impl Frame {
    /// A point as the device holds it.
    pub fn point(&self, p: [f64; 3]) -> [f32; 3] {
        std::array::from_fn(|a| self.along(a, p[a]))
    }

    /// A coordinate along axis `a` as the device holds it.
    pub fn along(&self, a: usize, v: f64) -> f32 {
        (v - self.origin[a]) as f32
    }

    /// A device coordinate along axis `a` back in the case's frame.
    pub fn back(&self, a: usize, v: f32) -> f64 {
        f64::from(v) + self.origin[a]
    }
}
