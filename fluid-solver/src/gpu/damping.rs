//! Damping zones (`[[damping]]`) on the device (`shaders/damping.wgsl`): the law of
//! [`crate::boundaries::damping`], u ← u exp(−rate s² Δt) for the fluid in a zone after each
//! step, s rising from 0 at the zone's near face to 1 at its far one.

use super::frame::Frame;
use bytemuck::{Pod, Zeroable};
use schemas::case::fluid::DampingConfig;

/// Mirror of `DampingZone` in `shaders/common.wgsl` (48 B): the zone's box, the axis (0 x, 1 y)
/// and sign of the direction the damping grows along, the rate at the far face [1/s].
#[repr(C)]
#[derive(Debug, Clone, Copy, Pod, Zeroable)]
pub struct Zone {
    pub lo: [f32; 3],
    pub axis: u32,
    pub hi: [f32; 3],
    pub sign: f32,
    pub rate: f32,
    pub pad: [u32; 3],
}

/// The device's zones of the `[[damping]]` tables, as [`crate::solver`] parses them (a table
/// whose axis validation refuses has none).
pub fn zones(tables: &[DampingConfig], frame: &Frame) -> Vec<Zone> {
    tables
        .iter()
        .filter_map(|d| {
            let (axis, sign) = d.direction()?;
            let zone = d.zone();
            Some(Zone {
                lo: frame.point(zone.min),
                axis: axis as u32,
                hi: frame.point(zone.max),
                sign: sign as f32,
                rate: d.rate as f32,
                pad: [0; 3],
            })
        })
        .collect()
}
