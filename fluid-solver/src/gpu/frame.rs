//! Where the device measures positions from, and how it keeps them.
//!
//! The origin is the tank's lower corner
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
//!
//! **Wide positions** (a tank longer than 16 777 spacings, where plain f32 would round a
//! position by more than 1e-3 Δs: [`schemas::case::fluid::FluidConfig::gpu_quantum`]): each
//! particle's position is hi + lo, hi (the position buffer) a multiple of the quantum q, a power
//! of two with 2²⁴ q beyond twice the tank's extent, so hi's are exact and so are their
//! differences; lo (a second buffer) within q/2 of 0. A pair's difference
//! (hi_j − hi_i) + (lo_j − lo_i) is then as precise as in a small tank, and a move by d keeps
//! it: lo + d, then its whole quanta carried into hi (`shaders/common.wgsl`, `shift` and
//! `place`). What reads hi alone (plane, box, zone and site tests, the cell sort) sees the
//! position within q/2; the solver widens the cell edge by q so that no pair within a kernel's
//! radius falls outside the cells searched (`reach · (h + q) ≥ r_e + q`).

use rayon::prelude::*;

/// The device's frame: positions are kept relative to `origin`, as hi + lo on a grid of
/// `quantum` when there is one (wide positions, module doc).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Frame {
    pub origin: [f64; 3],
    pub quantum: Option<f64>,
}

impl Frame {
    /// A point as the device holds it (its high part when wide; [`Frame::split`]).
    pub fn point(&self, p: [f64; 3]) -> [f32; 3] {
        self.split(p).0
    }

    /// A coordinate along axis `a` as the device holds it (its high part when wide).
    pub fn along(&self, a: usize, v: f64) -> f32 {
        self.split_along(a, v).0
    }

    /// A point as its high and low parts (the low part 0 unless wide).
    pub fn split(&self, p: [f64; 3]) -> ([f32; 3], [f32; 3]) {
        let parts: [(f32, f32); 3] = std::array::from_fn(|a| self.split_along(a, p[a]));
        (parts.map(|s| s.0), parts.map(|s| s.1))
    }

    /// A coordinate along axis `a` as its high part (a multiple of the quantum when wide) and
    /// the low part left (within half a quantum of 0; 0 unless wide).
    pub fn split_along(&self, a: usize, v: f64) -> (f32, f32) {
        let d = v - self.origin[a];
        match self.quantum {
            Some(q) if d.is_finite() => {
                let hi = (d / q).round() * q;
                (hi as f32, (d - hi) as f32)
            }
            _ => (d as f32, 0.0),
        }
    }

    /// A device coordinate along axis `a` (high and low parts) back in the case's frame.
    pub fn back(&self, a: usize, hi: f32, lo: f32) -> f64 {
        f64::from(hi) + f64::from(lo) + self.origin[a]
    }

    /// The device's positions (xyz; w: the kind) and their low parts (empty with plain
    /// positions) back in the case's frame, as x, y and z columns.
    pub fn columns_back(&self, pos: &[[f32; 4]], lo: &[[f32; 4]]) -> [Vec<f64>; 3] {
        std::array::from_fn(|a| {
            pos.par_iter()
                .enumerate()
                .map(|(i, e)| self.back(a, e[a], lo.get(i).map_or(0.0, |l| l[a])))
                .collect()
        })
    }

    /// True when positions are kept as two parts.
    pub fn wide(&self) -> bool {
        self.quantum.is_some()
    }
}

#[cfg(test)]
mod tests {
    use super::Frame;

    /// Wide: the high part is a multiple of the quantum, the low part within half of it, and
    /// both together give the coordinate back to f32 of the low part (2⁻²⁴ · q/2).
    #[test]
    fn a_wide_split_keeps_the_coordinate_to_the_low_parts_rounding() {
        let q = 2f64.powi(-12);
        let frame = Frame {
            origin: [-2000.0, 5.0, 0.0],
            quantum: Some(q),
        };
        for v in [0.0, 1.0e-7, 0.123_456_789, 2000.3, 2_012.345_678_9, -0.05] {
            let (hi, lo) = frame.split_along(0, v);
            let (hi, lo) = (f64::from(hi), f64::from(lo));
            assert_eq!((hi / q).fract(), 0.0, "{v}: hi = {hi}");
            assert!(lo.abs() <= 0.5 * q, "{v}: lo = {lo}");
            let back = frame.back(0, hi as f32, lo as f32);
            assert!(
                (back - v).abs() <= 0.5 * q * f64::from(f32::EPSILON),
                "{v} came back as {back}"
            );
        }
        assert_eq!(frame.split_along(0, f64::INFINITY), (f32::INFINITY, 0.0));
    }

    /// Plain: the low part is 0 and the high part what the device always held, x − origin in f32.
    #[test]
    fn a_plain_split_is_the_f32_offset() {
        let frame = Frame {
            origin: [1.0, 2.0, 3.0],
            quantum: None,
        };
        assert_eq!(
            frame.split([1.5, 2.25, 3.1]),
            ([0.5, 0.25, (3.1f64 - 3.0) as f32], [0.0; 3])
        );
        assert!(!frame.wide());
    }
}
