//! The device's per-workgroup partials of `reduce_step` (`shaders/reduce.wgsl`) and their sum on
//! the host: the step's totals and what the instability detector found.

use bytemuck::{Pod, Zeroable};

/// Mirror of `Partial` in `shaders/common.wgsl` (48 B per workgroup of 256 particles).
#[repr(C)]
#[derive(Debug, Clone, Copy, Pod, Zeroable)]
pub struct Partial {
    pub wall: [f32; 3],
    pub energy: f32,
    pub candidates: u32,
    pub finding: u32,
    pub escaped: u32,
    pub fluid: u32,
    pub fastest: f32,
    pub pad: [u32; 3],
}

/// What the device found in one step (sums in f64 over the workgroups' f32 partials).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct StepReport {
    /// Force of walls, dummies and bodies on the fluid [N].
    pub force_from_walls: [f64; 3],
    /// Σ ½|u|² − g·r over the fluid [J/kg].
    pub energy: f64,
    pub candidates: u64,
    /// The particle with the smallest id that has a finding, and the finding's code
    /// (`shaders/reduce.wgsl`: 1 not finite, 2 inside a wall, 3 left the domain, 4 too fast,
    /// 5 inside a body).
    pub finding: Option<(u32, u32)>,
    /// Fluid particles that left through the open top (removed before the next step).
    pub escaped: u64,
    pub fluid: u64,
    /// The fastest fluid particle's speed at the step's end [m/s] (ISPH's advective limit).
    pub fastest: f64,
}

/// Sums the partials.
pub fn sum(partials: &[Partial]) -> StepReport {
    let mut r = StepReport::default();
    let mut finding = u32::MAX;
    for p in partials {
        for a in 0..3 {
            r.force_from_walls[a] += f64::from(p.wall[a]);
        }
        r.energy += f64::from(p.energy);
        r.candidates += u64::from(p.candidates);
        finding = finding.min(p.finding);
        r.escaped += u64::from(p.escaped);
        r.fluid += u64::from(p.fluid);
        r.fastest = r.fastest.max(f64::from(p.fastest));
    }
    if finding != u32::MAX {
        r.finding = Some((finding / 8, finding % 8));
    }
    r
}
